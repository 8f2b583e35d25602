// The false-colour plan of a grid (grid_NAME.png): its colour map against viridis' published
// colours, round scales, the layout's size from its documented constants, and a plan of values
// that grow linearly across the grid: colours between the points follow the interpolated
// values, the legend rises monotonically and the iso-lines sit where the values cross a step.

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "canvas.h"
#include "colour_scale.h"
#include "grid_plan.h"

namespace penumbra::app {
namespace {

/// Rec. 709 luma of the sRGB-encoded values: rises with lightness along viridis.
double luma(Rgb8 c) {
    return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

TEST(ColourMap, ViridisEndsAndMiddleAreThePublishedColours) {
    EXPECT_EQ(viridis(0), (Rgb8{0x44, 0x01, 0x54}));
    EXPECT_EQ(viridis(0.5), (Rgb8{0x21, 0x90, 0x8c}));
    EXPECT_EQ(viridis(1), (Rgb8{0xfd, 0xe7, 0x25}));
    EXPECT_EQ(viridis(-3), viridis(0));
    EXPECT_EQ(viridis(7), viridis(1));
}

// To within the rounding to 8 bits (half a code value of luma).
TEST(ColourMap, LightnessRisesThroughout) {
    for (int i = 1; i <= 1000; ++i)
        EXPECT_GE(luma(viridis(i / 1000.0)), luma(viridis((i - 1) / 1000.0)) - 0.5) << i;
    EXPECT_GT(luma(viridis(1)) - luma(viridis(0)), 180);
}

TEST(ColourScale, LinearRoundStepsUpToARoundTop) {
    const auto check = [](double max, double step, double top) {
        const ColourScale s = ColourScale::covering(0, max);
        EXPECT_FALSE(s.logarithmic);
        EXPECT_DOUBLE_EQ(s.bottom(), 0) << max;
        EXPECT_DOUBLE_EQ(s.levels[1], step) << max;
        EXPECT_DOUBLE_EQ(s.top(), top) << max;
        EXPECT_LE(s.levels.size(), 9u) << max;
    };
    check(369, 50, 400);
    check(400, 50, 400); // a maximum on a step adds none
    check(130, 20, 140);
    check(1, 0.2, 1);
    check(2.3, 0.5, 2.5);
    check(17, 2.5, 17.5);
    check(0, 1, 1);                                       // all dark
    const ColourScale s = ColourScale::covering(40, 369); // within a decade: linear from 0
    EXPECT_FALSE(s.logarithmic);
    EXPECT_EQ(s.band(49.9), 0);
    EXPECT_EQ(s.band(50.1), 1);
    EXPECT_DOUBLE_EQ(s.fraction(200), 0.5);
}

// More than a decade: 1-2-5 levels around the values, positions by the logarithm.
TEST(ColourScale, LogarithmicOverMoreThanADecade) {
    const ColourScale s = ColourScale::covering(0.73, 18.9);
    EXPECT_TRUE(s.logarithmic);
    EXPECT_EQ(s.levels, (std::vector<double>{0.5, 1, 2, 5, 10, 20}));
    EXPECT_NEAR(s.fraction(1), std::log(2) / std::log(40), 1e-12);
    EXPECT_NEAR(s.fraction(std::sqrt(10.0)), std::log(2 * std::sqrt(10.0)) / std::log(40), 1e-12);
    EXPECT_EQ(s.band(0.9), 0);
    EXPECT_EQ(s.band(1), 1);
    EXPECT_EQ(s.band(19), 4);
    EXPECT_EQ(ColourScale::covering(2, 50).levels, (std::vector<double>{2, 5, 10, 20, 50}));
    // Past three decades, decades only.
    EXPECT_EQ(ColourScale::covering(0.3, 4000).levels,
              (std::vector<double>{0.1, 1, 10, 100, 1000, 10000}));
}

/// A 4 m × 6 m floor grid at spacing 0.5, 0.5 m from the walls (7 × 11 points, all present).
SensorGrid office_grid() {
    SensorGrid grid;
    grid.name = "wp";
    grid.origin = {0.5, 0.5, 0.85};
    grid.spacing_m = 0.5;
    grid.rows = 11;
    grid.columns = 7;
    for (std::uint32_t i = 0; i < 77; ++i)
        grid.sensors.emplace_back(i);
    const std::vector<Vec3> corners{{0, 0, 0.85}, {4, 0, 0.85}, {4, 6, 0.85}, {0, 6, 0.85}};
    for (std::size_t i = 0; i < 4; ++i)
        grid.outline.push_back({corners[i], corners[(i + 1) % 4]});
    return grid;
}

// The longer side (6 m) spans 480 px: 80 px/m, a 320 × 480 plan; the picture adds the margins
// (16), the title (64) and the legend (116), and is at least 496 wide.
TEST(GridPlan, LayoutFromTheOutlinesExtent) {
    const PlanLayout l = PlanLayout::of(office_grid());
    EXPECT_DOUBLE_EQ(l.px_per_m, 80);
    EXPECT_EQ(l.plan_width, 320);
    EXPECT_EQ(l.plan_height, 480);
    EXPECT_EQ(l.width, 496); // 16 + 320 + 116 + 16 = 468 < 496
    EXPECT_EQ(l.height, 64 + 480 + 16);
    EXPECT_EQ(l.bar_height, 480);
    // Lattice point (0, 0) at (0.5, 0.5) m: 40 px from the plan's left and bottom edges.
    const auto [x, y] = l.pixel_at(office_grid(), 0, 0);
    EXPECT_DOUBLE_EQ(x, 16 + 40 - 0.5);
    EXPECT_DOUBLE_EQ(y, 64 + 480 - 40 - 0.5);
}

// Values 60 × column (0 … 360 lx): the scale is 0 … 400 in steps of 50.
std::vector<double> linear_values(const SensorGrid& grid) {
    std::vector<double> values;
    for (int r = 0; r < grid.rows; ++r)
        for (int c = 0; c < grid.columns; ++c)
            values.push_back(60.0 * c);
    return values;
}

class LinearPlan : public ::testing::Test {
protected:
    SensorGrid grid_ = office_grid();
    PlanLayout layout_ = PlanLayout::of(grid_);
    Canvas canvas_ = draw_grid_plan(grid_, linear_values(grid_), {"illuminance", "lx", 1});
};

TEST_F(LinearPlan, ColoursFollowTheInterpolatedValues) {
    ASSERT_EQ(canvas_.width(), layout_.width);
    ASSERT_EQ(canvas_.height(), layout_.height);
    const ColourScale scale = ColourScale::covering(0, 360);
    // Half-way between two points of row 5 the value is 60 × (c + 0.5), away from iso-lines.
    for (int c = 0; c + 1 < grid_.columns; ++c) {
        const auto [x, y] = layout_.pixel_at(grid_, 5.25, c + 0.5);
        const Rgb8 got = canvas_.at(int(std::lround(x)), int(std::lround(y)));
        const Rgb8 expected = scale.colour(60.0 * (c + 0.5));
        EXPECT_NEAR(got.r, expected.r, 2) << c;
        EXPECT_NEAR(got.g, expected.g, 2) << c;
        EXPECT_NEAR(got.b, expected.b, 2) << c;
    }
    // Beyond the outermost points (the wall offset) values hold: the left margin shows 0 lx.
    const auto [x0, y0] = layout_.pixel_at(grid_, 5.25, -0.5);
    EXPECT_EQ(canvas_.at(int(x0), int(y0)), scale.colour(0));
}

TEST_F(LinearPlan, LegendRisesMonotonicallyWithNumbersBesideIt) {
    const int x = layout_.bar_x + PlanLayout::k_bar_width / 2;
    const int bottom = layout_.bar_y + layout_.bar_height - 1;
    EXPECT_EQ(canvas_.at(x, bottom), viridis(0.5 / layout_.bar_height));
    for (int y = bottom; y > layout_.bar_y; --y)
        EXPECT_GE(luma(canvas_.at(x, y - 1)), luma(canvas_.at(x, y)) - 0.5) << y;
    // Ink right of the ticks: the numbers 0 … 400.
    int ink = 0;
    for (int y = layout_.bar_y - 8; y < bottom + 8; ++y)
        for (int lx = layout_.bar_x + 30; lx < layout_.width; ++lx)
            ink += luma(canvas_.at(lx, y)) < 60;
    EXPECT_GT(ink, 9 * 20); // 9 labels of at least 20 dark pixels each
}

// Iso-lines at 50, 100, … 350 lx cross row 5.25 where 60 × column = k × 50.
TEST_F(LinearPlan, IsoLinesWhereTheValueCrossesAStep) {
    const Rgb8 line{45, 45, 45};
    const auto [x_left, y] = layout_.pixel_at(grid_, 5.25, 0);
    const auto [x_right, unused] = layout_.pixel_at(grid_, 5.25, 6);
    std::vector<int> found;
    for (int x = int(std::ceil(x_left)); x <= int(x_right); ++x)
        if (canvas_.at(x, int(std::lround(y))) == line)
            found.push_back(x);
    ASSERT_EQ(found.size(), 7u);
    for (int k = 1; k <= 7; ++k) {
        const auto [x, unused_y] = layout_.pixel_at(grid_, 5.25, k * 50.0 / 60.0);
        EXPECT_NEAR(found[std::size_t(k - 1)], x, 1.0) << k * 50 << " lx";
    }
}

} // namespace
} // namespace penumbra::app
