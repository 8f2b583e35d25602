// Grid results through the bake pipeline: a point light over a black floor, whose work-plane
// illuminance is Lambert's E = I cos θ / d² at every point (no reflected light), so that
// sensors.csv, grids.csv and grid_NAME.png/.vtp are checked against values computed here.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "app/pipeline.h"
#include "common/bake_util.h"
#include "common/output_files.h"
#include "common/test_util.h"
#include "core/scene_io.h"

#include "daylight.h"
#include "grid_plan.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

constexpr double k_intensity_cd = 1000;
const Vec3 k_light{1.0, 1.5, 2.0};

/// A black 4 m × 6 m floor, a 1000 cd point light and a work plane at 0.85 m named
/// \p grid_name (spacing 0.5, 0.5 m from the walls: 7 × 11 points). Sensors gather at the
/// points themselves, so fixed elements (shooting) do as well as a refined hierarchy here.
Scene lit_floor(const std::string& grid_name = "wp") {
    return parse_scene(R"json({
  "materials": {"black": {"reflectance": 0}},
  "polygons": [{"name": "floor", "material": "black",
                "vertices": [[0,0,0],[4,0,0],[4,6,0],[0,6,0]]}],
  "point_lights": [{"position": [1.0, 1.5, 2.0], "intensity_cd": 1000}],
  "sensors": [[2, 3, 0, 0, 0, 1]],
  "grids": {")json" + grid_name +
                           R"json(": {"floor": "floor", "height": 0.85, "spacing": 0.5,
                          "wall_offset": 0.5}},
  "mesher": {"max_edge_length": 1},
  "solver": {"method": "shooting"}
})json",
                       "scene.json", ".");
}

double lambert_lx(const Vec3& p) {
    const Vec3 d = k_light - p;
    return k_intensity_cd * d.z / std::pow(length(d), 3);
}

using test::read_csv;

std::pair<int, int> png_size(const fs::path& path) {
    const test::Png png = test::read_png(path);
    return {png.width, png.height};
}

class GridOutputs : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::temp_dir("grids");
        result_ = test::bake(scene_);
        app::write_outputs(dir_.string(), scene_, result_, false);
    }
    void TearDown() override { fs::remove_all(dir_); }

    Scene scene_ = lit_floor();
    app::BakeResult result_;
    fs::path dir_;
};

TEST_F(GridOutputs, SensorsCsvHoldsTheGridPointsAfterTheOthers) {
    const auto rows = read_csv(dir_ / "sensors.csv");
    ASSERT_EQ(rows.size(), 1u + 1 + 77);
    const std::vector<std::string> header{"name",
                                          "x",
                                          "y",
                                          "z",
                                          "nx",
                                          "ny",
                                          "nz",
                                          "direct_r_w_m2",
                                          "direct_g_w_m2",
                                          "direct_b_w_m2",
                                          "total_r_w_m2",
                                          "total_g_w_m2",
                                          "total_b_w_m2",
                                          "illuminance_direct_lx",
                                          "illuminance_total_lx"};
    EXPECT_EQ(rows[0], header); // no daylight_factor_pct: the scene has no sky
    EXPECT_EQ(rows[2][0], "wp:0:0");
    EXPECT_EQ(rows.back()[0], "wp:10:6");
    for (std::size_t i = 2; i < rows.size(); ++i) {
        const Vec3 p{std::stod(rows[i][1]), std::stod(rows[i][2]), std::stod(rows[i][3])};
        EXPECT_NEAR(std::stod(rows[i][14]), lambert_lx(p), 1e-3 * lambert_lx(p)) << rows[i][0];
    }
}

// E_avg, E_min, E_max and E_min / E_avg against Lambert's law at the 77 points.
TEST_F(GridOutputs, GridsCsvStatisticsAreLambertsLawAtThePoints) {
    std::vector<double> expected;
    for (int r = 0; r < 11; ++r)
        for (int c = 0; c < 7; ++c)
            expected.push_back(lambert_lx({0.5 + 0.5 * c, 0.5 + 0.5 * r, 0.85}));
    double sum = 0;
    for (double e : expected)
        sum += e;
    const double avg = sum / 77;
    const double min = *std::min_element(expected.begin(), expected.end());
    const double max = *std::max_element(expected.begin(), expected.end());
    const auto rows = read_csv(dir_ / "grids.csv");
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[0], (std::vector<std::string>{"grid", "kind", "points", "illuminance_avg_lx",
                                                 "illuminance_min_lx", "illuminance_max_lx",
                                                 "uniformity_min_avg"}));
    EXPECT_EQ(rows[1][0], "wp");
    EXPECT_EQ(rows[1][1], "work_plane");
    EXPECT_EQ(rows[1][2], "77");
    EXPECT_NEAR(std::stod(rows[1][3]), avg, 1e-3 * avg);
    EXPECT_NEAR(std::stod(rows[1][4]), min, 1e-3 * min);
    EXPECT_NEAR(std::stod(rows[1][5]), max, 1e-3 * max);
    EXPECT_NEAR(std::stod(rows[1][6]), min / avg, 2e-3 * min / avg);
}

TEST_F(GridOutputs, PlanAndPointsBesideTheMesh) {
    const app::PlanLayout layout = app::PlanLayout::of(scene_.grids[0]);
    EXPECT_EQ(png_size(dir_ / "grid_wp.png"), std::pair(layout.width, layout.height));
    EXPECT_EQ(layout.height, 64 + 480 + 16); // the 6 m side spans 480 px
    EXPECT_TRUE(fs::exists(dir_ / "grid_wp.vtp"));
    EXPECT_TRUE(fs::exists(dir_ / "mesh.vtu"));
}

// A bake whose grid has another name removes the earlier grid's files; one without grids
// removes grids.csv too. Other files of the folder stay.
TEST_F(GridOutputs, RebakeRemovesTheFilesOfGridsItNoLongerHas) {
    std::ofstream(dir_ / "grid_notes.txt") << "mine";
    const Scene renamed = lit_floor("desk");
    app::write_outputs(dir_.string(), renamed, test::bake(renamed), false);
    EXPECT_FALSE(fs::exists(dir_ / "grid_wp.png"));
    EXPECT_FALSE(fs::exists(dir_ / "grid_wp.vtp"));
    EXPECT_TRUE(fs::exists(dir_ / "grid_desk.png"));
    EXPECT_TRUE(fs::exists(dir_ / "grids.csv"));
    Scene without = renamed;
    without.grids.clear();
    app::write_outputs(dir_.string(), without, test::bake(without), false);
    EXPECT_FALSE(fs::exists(dir_ / "grid_desk.png"));
    EXPECT_FALSE(fs::exists(dir_ / "grids.csv"));
    EXPECT_TRUE(fs::exists(dir_ / "grid_notes.txt"));
}

// The daylight factor is 100 E / E_h, E_h the sky's unobstructed horizontal illuminance: π L
// for a uniform sky of luminance L (Radiance's 179 lm/W: L = 179 × the zenith radiance), here
// 10 000 lx. The readings are set by hand (the sky's light at the points is the solver's); the
// tolerance, 1e-4, allows for E_h found by quadrature.
TEST(DaylightFactor, SensorsAndGridsAgainstAUniformSky) {
    Scene scene = lit_floor();
    Sky sky;
    sky.model = UniformSky{};
    sky.zenith_radiance = 10000 / k_pi / 179;
    scene.sky = sky;
    app::BakeResult result;
    for (std::size_t i = 0; i < scene.sensors.size(); ++i) {
        const double lx = 100 + 10.0 * double(i);
        result.sensors.push_back({Rgb(), Rgb(), lx, lx});
    }
    std::stringstream sensors(app::sensors_csv(scene, result));
    std::string line;
    std::getline(sensors, line);
    EXPECT_TRUE(line.ends_with(",illuminance_direct_lx,illuminance_total_lx,daylight_factor_pct"))
        << line;
    for (std::size_t i = 0; std::getline(sensors, line); ++i) {
        const double df = std::stod(line.substr(line.rfind(',') + 1));
        const double expected = (100 + 10.0 * double(i)) / 100;
        EXPECT_NEAR(df, expected, 1e-4 * expected) << line;
    }
    // The grid's points are sensors 1 … 77: E from 110 to 870 lx, mean 490 lx.
    std::stringstream grids(app::grids_csv(scene, result));
    std::getline(grids, line);
    EXPECT_TRUE(
        line.ends_with(",uniformity_min_avg,daylight_factor_avg_pct,daylight_factor_min_pct"))
        << line;
    std::getline(grids, line);
    double avg = 0, min = 0, max = 0, uniformity = 0, df_avg = 0, df_min = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "wp,work_plane,77,%lf,%lf,%lf,%lf,%lf,%lf", &avg, &min,
                          &max, &uniformity, &df_avg, &df_min),
              6)
        << line;
    EXPECT_DOUBLE_EQ(avg, 490);
    EXPECT_NEAR(df_avg, 4.9, 1e-4 * 4.9);
    EXPECT_NEAR(df_min, 1.1, 1e-4 * 1.1);
    EXPECT_EQ(app::plan_quantity(app::daylight_reference_lx(scene)).unit, "%");
}

} // namespace
} // namespace penumbra
