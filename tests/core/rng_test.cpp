#include "core/rng.h"

#include <cmath>
#include <set>

#include <gtest/gtest.h>

namespace penumbra {
namespace {

TEST(Pcg32, AdvanceMatchesStepping) {
    Pcg32 a(42, 54), b(42, 54);
    for (int i = 0; i < 1000; ++i)
        a.next_u32();
    b.advance(1000);
    EXPECT_EQ(a.state(), b.state());
    EXPECT_EQ(a.next_u32(), b.next_u32());
}

TEST(Pcg32, AdvanceBackwardsReturns) {
    Pcg32 a(7, 3);
    const std::uint64_t start = a.state();
    for (int i = 0; i < 37; ++i)
        a.next_u32();
    a.advance(-37);
    EXPECT_EQ(a.state(), start);
}

TEST(Pcg32, StreamsAreNamedByContent) {
    Pcg32 a = Pcg32::for_stream(RngPurpose::pixel_sample, 3, 4, 0, 9);
    Pcg32 b = Pcg32::for_stream(RngPurpose::pixel_sample, 3, 4, 0, 9);
    Pcg32 c = Pcg32::for_stream(RngPurpose::pixel_sample, 4, 3, 0, 9);
    Pcg32 d = Pcg32::for_stream(RngPurpose::form_factor_visibility, 3, 4, 0, 9);
    std::uint32_t va = a.next_u32();
    EXPECT_EQ(va, b.next_u32());
    EXPECT_NE(va, c.next_u32());
    EXPECT_NE(va, d.next_u32());
}

TEST(Pcg32, UniformFloatsHaveMeanAndVarianceOfU01) {
    Pcg32 rng(1, 1);
    const int n = 200000;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        double u = rng.next_float();
        ASSERT_GE(u, 0.0);
        ASSERT_LT(u, 1.0);
        sum += u;
        sum2 += u * u;
    }
    double mean = sum / n, var = sum2 / n - mean * mean;
    // 5 standard errors: σ_mean = sqrt(1/12 / n) ≈ 6.5e-4.
    EXPECT_NEAR(mean, 0.5, 5 * std::sqrt(1.0 / 12.0 / n));
    EXPECT_NEAR(var, 1.0 / 12.0, 2e-3);
}

TEST(Hash, DistinctWordsGiveDistinctHashes) {
    std::set<std::uint64_t> seen;
    for (std::uint64_t a = 0; a < 100; ++a)
        for (std::uint64_t b = 0; b < 100; ++b)
            seen.insert(hash_words({a, b}));
    EXPECT_EQ(seen.size(), 10000u);
}

} // namespace
} // namespace penumbra
