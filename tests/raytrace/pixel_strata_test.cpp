#include "pixel_strata.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace penumbra::raytrace {
namespace {

TEST(PixelStrata, PermutedIsABijectionForEveryLength) {
    for (std::uint32_t n : {1u, 2u, 3u, 7u, 16u, 100u, 1025u})
        for (std::uint64_t key : {0ull, 1ull, 0x9e3779b97f4a7c15ull}) {
            std::vector<int> seen(n, 0);
            for (std::uint32_t i = 0; i < n; ++i) {
                const std::uint32_t p = permuted(i, n, key);
                ASSERT_LT(p, n);
                ++seen[p];
            }
            for (std::uint32_t i = 0; i < n; ++i)
                EXPECT_EQ(seen[i], 1) << "n " << n << " key " << key << " value " << i;
        }
}

TEST(PixelStrata, DifferentKeysGiveDifferentPermutations) {
    int moved = 0;
    for (std::uint32_t i = 0; i < 64; ++i)
        moved += permuted(i, 64, 1) != permuted(i, 64, 2);
    EXPECT_GT(moved, 32); // two random permutations of 64 agree in about one place
}

// A pixel of s² camera samples, each with g² stratified gather points: every sample keeps one
// point in each of its g × g strata, and the pixel's points fill the (g·s)² grid once each.
TEST(PixelStrata, APixelsSamplesFillTheFineGridOnce) {
    const int s = 4, g = 3, fine = g * s;
    std::vector<int> cells(std::size_t(fine * fine), 0);
    for (int sample = 0; sample < s * s; ++sample) {
        const PixelStrata pixel{s, sample, 12345};
        for (int k = 0; k < g * g; ++k) {
            const Vec2 u = pixel.position(k % g, k / g, g, {0.5, 0.5});
            EXPECT_EQ(int(u.x * g), k % g);
            EXPECT_EQ(int(u.y * g), k / g);
            ++cells[std::size_t(int(u.y * fine) * fine + int(u.x * fine))];
        }
    }
    for (int c : cells)
        EXPECT_EQ(c, 1);
}

TEST(PixelStrata, OneDimensionalStrataFillTheirFineCellsOnce) {
    const int s = 3, count = 5, fine = count * s * s;
    std::vector<int> cells(std::size_t(fine), 0);
    for (int sample = 0; sample < s * s; ++sample) {
        const PixelStrata pixel{s, sample, 7};
        for (int k = 0; k < count; ++k) {
            const double u = pixel.position(k, count, 0.5);
            EXPECT_EQ(int(u * count), k);
            ++cells[std::size_t(u * fine)];
        }
    }
    for (int c : cells)
        EXPECT_EQ(c, 1);
}

} // namespace
} // namespace penumbra::raytrace
