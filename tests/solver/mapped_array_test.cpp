// The growable array the solver keeps its links in (solver/src/links/mapped_array.h): its elements
// survive growth by remapping, resizing, assignment and moves.

#include "links/mapped_array.h"

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

namespace penumbra::solver {
namespace {

struct Pair {
    std::uint32_t a = 7, b = 9;
};

TEST(MappedArray, KeepsItsElementsThroughGrowthResizeAssignAndMove) {
    MappedArray<Pair> v;
    EXPECT_TRUE(v.empty());
    // Past many pages, so that it remaps (and may move) several times.
    for (std::uint32_t i = 0; i < 300000; ++i)
        v.push_back({i, 2 * i});
    ASSERT_EQ(v.size(), 300000u);
    for (std::uint32_t i = 0; i < v.size(); i += 997)
        ASSERT_EQ(v[i].b, 2 * i);
    v.resize(10);
    v.resize(12); // new elements are value-initialised
    EXPECT_EQ(v[9].a, 9u);
    EXPECT_EQ(v[11].a, 7u);
    EXPECT_EQ(v[11].b, 9u);
    v.shrink_to_fit();
    EXPECT_EQ(v[9].b, 18u);
    const std::vector<Pair> values{{1, 2}, {3, 4}};
    MappedArray<Pair> w;
    w.assign(values);
    MappedArray<Pair> moved = std::move(w);
    EXPECT_TRUE(w.empty());
    ASSERT_EQ(moved.size(), 2u);
    EXPECT_EQ(moved[1].b, 4u);
    moved = std::move(v);
    EXPECT_EQ(moved.size(), 12u);
    EXPECT_EQ(moved.span().back().a, 7u);
}

} // namespace
} // namespace penumbra::solver
