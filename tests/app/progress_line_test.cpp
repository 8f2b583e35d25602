// The terminal progress bar's line (issue #28 asks for the time remaining): the estimate from
// the pace so far, its readable form, and where the line leaves it out.

#include <gtest/gtest.h>

#include "progress_line.h"

namespace penumbra::app {
namespace {

TEST(ProgressLine, TimeLeftFollowsThePaceSoFar) {
    // A quarter done after 10 s: three quarters more at 40 s per whole.
    ASSERT_TRUE(seconds_left(0.25, 10.0));
    EXPECT_NEAR(*seconds_left(0.25, 10.0), 30.0, 1e-12);
    EXPECT_NEAR(*seconds_left(0.9, 90.0), 10.0, 1e-12);
    EXPECT_FALSE(seconds_left(0.01, 5.0)); // too early to tell
    EXPECT_FALSE(seconds_left(1.0, 5.0));  // done
    EXPECT_FALSE(seconds_left(0.0, 5.0));
}

TEST(ProgressLine, DurationsReadAsPeopleSayThem) {
    EXPECT_EQ(readable_duration(0.4), "0 s");
    EXPECT_EQ(readable_duration(42.4), "42 s");
    EXPECT_EQ(readable_duration(185), "3 min 05 s");
    EXPECT_EQ(readable_duration(3725), "1 h 02 min");
}

TEST(ProgressLine, ShowsStageBarPercentElapsedAndTimeLeft) {
    const std::string line = progress_line("render", 0.25, 10.0);
    EXPECT_EQ(line, "render         [##########..............................]  25%   10.0 s, "
                    "30 s left");
    // No estimate at the start nor at the end.
    EXPECT_EQ(progress_line("solve", 0.0, 1.5).find("left"), std::string::npos);
    EXPECT_EQ(progress_line("solve", 1.0, 1.5).find("left"), std::string::npos);
}

} // namespace
} // namespace penumbra::app
