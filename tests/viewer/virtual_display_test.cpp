// VirtualDisplay: a private Xvfb that sets DISPLAY while it lives, picks a free display
// number (two at once differ), cleans up, and fails with a clear ConfigError without Xvfb.

#include "virtual_display.h"

#include "common/test_util.h"
#include "core/error.h"

#include <sys/stat.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace penumbra::viewer {
namespace {

namespace fs = std::filesystem;

/// Sets or unsets an environment variable for one scope.
class ScopedEnv {
public:
    ScopedEnv(const char* name, const char* value) : name_(name) {
        if (const char* old = std::getenv(name))
            old_ = old;
        if (value)
            ::setenv(name, value, 1);
        else
            ::unsetenv(name);
    }
    ~ScopedEnv() {
        if (old_)
            ::setenv(name_, old_->c_str(), 1);
        else
            ::unsetenv(name_);
    }

private:
    const char* name_;
    std::optional<std::string> old_;
};

std::string socket_of(const std::string& display) {
    return "/tmp/.X11-unix/X" + display.substr(1);
}

TEST(VirtualDisplay, SetsDisplayAndCleansUp) {
    ScopedEnv no_display("DISPLAY", nullptr);
    std::string socket;
    struct stat ours {};
    {
        VirtualDisplay display(640, 480);
        ASSERT_EQ(display.display().rfind(':', 0), 0u) << display.display();
        EXPECT_TRUE(has_display());
        EXPECT_EQ(std::string(std::getenv("DISPLAY")), display.display());
        socket = socket_of(display.display());
        EXPECT_TRUE(fs::exists(socket)) << socket;
        ASSERT_EQ(0, ::stat(socket.c_str(), &ours)) << socket;
    }
    EXPECT_FALSE(has_display());
    // Gone, or another test's server (ctest -j) has taken the freed number since: a new file.
    struct stat now {};
    const bool same = ::stat(socket.c_str(), &now) == 0 && now.st_ino == ours.st_ino &&
                      now.st_ctim.tv_sec == ours.st_ctim.tv_sec &&
                      now.st_ctim.tv_nsec == ours.st_ctim.tv_nsec;
    EXPECT_FALSE(same) << "Xvfb still running: " << socket;
}

TEST(VirtualDisplay, TwoAtOnceGetDifferentNumbersAndRestoreDisplay) {
    ScopedEnv display_env("DISPLAY", ":4242");
    {
        VirtualDisplay a(320, 240);
        VirtualDisplay b(320, 240);
        EXPECT_NE(a.display(), b.display());
        EXPECT_EQ(std::string(std::getenv("DISPLAY")), b.display());
    }
    EXPECT_EQ(std::string(std::getenv("DISPLAY")), ":4242");
}

TEST(VirtualDisplay, MissingXvfbIsAConfigError) {
    ScopedEnv no_display("DISPLAY", nullptr);
    ScopedEnv path("PATH", test::temp_dir("no-xvfb").c_str());
    try {
        VirtualDisplay display(640, 480);
        FAIL() << "no exception";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("install xvfb"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(has_display());
}

} // namespace
} // namespace penumbra::viewer
