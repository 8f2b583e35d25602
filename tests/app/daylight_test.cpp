// The sky as a light source through the whole pipeline (issue #30): CIE 171:2006 test 5.9
// (sky component through a roof opening), a pane under a uniform sky, and the power balance
// of a glazed room.

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/bake_util.h"
#include "common/test_util.h"
#include "core/mesh.h"
#include "core/scene.h"
#include "core/scene_io.h"

namespace penumbra {
namespace {

using test::add_material;
using test::add_rect;

/// A CIE standard overcast sky (sharp horizon, no ground) of unobstructed horizontal
/// illuminance \p lx: E_h = (7π/9) L_z (the closed form, /work/shared/validation/README.md).
Sky overcast_sky(double lx) {
    Sky sky;
    sky.model = CieOvercastSky{};
    sky.horizon = Horizon::sharp;
    sky.zenith_radiance = lx / (7.0 * k_pi / 9.0) / k_luminous_efficacy_lm_per_w;
    return sky;
}

// ---- CIE 171 5.9: sky component through an unglazed 1 × 1 m roof opening ----

/// The black 4 × 4 × 3 m room of CIE 171's test 5.9 with its opening centred in the ceiling.
Scene roof_opening_room() {
    Scene scene;
    auto black = add_material(scene, "black", Rgb(0), {}, false);
    const double H = 3;
    test::add_cie171_room_without_ceiling(scene, black);
    // Ceiling in four pieces around the opening (x, y in [1.5, 2.5]), facing down.
    add_rect(scene, "ceiling_s", black, {0, 0, H}, {0, 1.5, 0}, {4, 0, 0});
    add_rect(scene, "ceiling_n", black, {0, 2.5, H}, {0, 1.5, 0}, {4, 0, 0});
    add_rect(scene, "ceiling_w", black, {0, 1.5, H}, {0, 1, 0}, {1.5, 0, 0});
    add_rect(scene, "ceiling_e", black, {2.5, 1.5, H}, {0, 1, 0}, {1.5, 0, 0});
    scene.sky = overcast_sky(1e4);
    scene.mesher.max_edge_length = 0.25;
    return scene;
}

TEST(Cie171SkyComponent, RoofOpeningUnderOvercastSky) {
    Scene scene = roof_opening_room();
    const std::vector<double> sky_component_pct = test::add_cie171_59_sensors(scene);
    const app::BakeResult r = test::bake(scene);
    ASSERT_EQ(r.sensors.size(), 14u);
    for (std::size_t i = 0; i < 14; ++i) {
        const double exact = sky_component_pct[i];
        const double sc = r.sensors[i].illuminance_total_lx / 1e4 * 100;
        // The tolerance: every point within 1 %.
        EXPECT_NEAR(sc, exact, 0.01 * exact) << scene.sensors[i].name << " sensor " << i;
        const Sensor& s = scene.sensors[i];
        const auto mesh_value =
            interpolate_at(r.mesh, r.solution.vertex_irradiance_direct, s.position, s.normal, 1e-6);
        ASSERT_TRUE(mesh_value.has_value()) << "sensor " << i << " not on the mesh";
        // The mesh interpolates vertex values linearly over elements of 0.25 m: 3 %.
        EXPECT_NEAR(to_photometric(*mesh_value) / 1e4 * 100, exact, 0.03 * exact)
            << "mesh, sensor " << i;
    }
}

// ---- A pane over a sensor under a uniform sky: the pane's hemispherical transmittance ----

TEST(GlazingUnderSky, PaneScalesAUniformSkyByItsHemisphericalTransmittance) {
    const double radiance = 10.0; // W/(sr·m²)
    Scene scene;
    auto black = add_material(scene, "black", Rgb(0), {}, false);
    const auto glass_id = test::add_clear_glass(scene); // 0.620 hemispherically
    const ThinGlass pane = *glazing_of(scene.materials[glass_id]);
    add_rect(scene, "floor", black, {-1, -1, 0}, {2, 0, 0}, {0, 2, 0});
    add_rect(scene, "pane", glass_id, {-10, -10, 0.05}, {20, 0, 0}, {0, 20, 0});
    scene.sky = Sky{};
    scene.sky->model = UniformSky{};
    scene.sky->zenith_radiance = radiance;
    scene.sensors.push_back({"under the pane", {0, 0, 0}, {0, 0, 1}});
    scene.mesher.max_edge_length = 1.0;
    const app::BakeResult r = test::bake(scene);
    ASSERT_EQ(r.sensors.size(), 1u);
    const double ratio = double(r.sensors[0].irradiance_total.g) / (k_pi * radiance);
    // The pane misses the sky within 0.3° of the horizon (projected solid angle 3e-5 of π).
    EXPECT_NEAR(ratio, pane.hemispherical_transmittance().g, 2e-3);
    EXPECT_NEAR(ratio, 0.620, 2e-3); // /work/shared/scenes/README.md, printed to 3 digits
}

// ---- A glazed room under an overcast sky: the power balance closes with glazing ----

TEST(GlazingUnderSky, GlazedRoomPowerBalances) {
    Scene scene;
    auto grey = add_material(scene, "grey", Rgb(0.5f));
    const auto glass_id = test::add_clear_glass(scene);
    // A 4 × 3 × 2.5 m room, window 1 × 1 m in the wall y = 0 (x 1.5–2.5, z 0.8–1.8).
    test::add_side_lit_room(scene, grey, glass_id, 1.5, 2.5);
    scene.sky = overcast_sky(1e4);
    scene.sky->ground_radiance = 0.2 * 1e4 / k_pi / k_luminous_efficacy_lm_per_w;
    scene.mesher.max_edge_length = 0.5;
    scene.solver.residual = 1e-4;
    const app::BakeResult r = test::bake(scene);
    const solver::PowerBalance& pb = r.stats.power;
    std::printf("glazed room: emitted %.6g lm, absorbed %.6g, escaped %.6g, glazing %.6g, "
                "unshot %.6g, imbalance %.2e\n",
                to_photometric(pb.emitted), to_photometric(pb.absorbed), to_photometric(pb.escaped),
                to_photometric(pb.glazing), to_photometric(pb.residual), pb.relative_imbalance());
    EXPECT_GT(to_photometric(pb.glazing), 0.0);
    EXPECT_GT(to_photometric(pb.escaped), 0.0);
    // Escape by rays and the panes' hemispherical transmittance for their share: 1 %.
    EXPECT_LT(std::abs(pb.relative_imbalance()), 1e-2);
}

// ---- The side-lit office against Radiance (data/reference/office, issue #30) ----

/// The illuminances (lx) of a Radiance reference CSV (x,y,z,illuminance_lx), in file order.
std::vector<double> radiance_reference(const std::string& file) {
    std::ifstream in(test::source_path(file));
    std::vector<double> out;
    std::string line;
    std::getline(in, line); // header
    while (std::getline(in, line)) {
        std::istringstream row(line);
        std::string cell;
        for (int column = 0; column < 4 && std::getline(row, cell, ','); ++column)
            if (column == 3)
                out.push_back(std::stod(cell));
    }
    return out;
}

class OfficeAgainstRadiance : public ::testing::TestWithParam<const char*> {};

TEST_P(OfficeAgainstRadiance, MeanRelativeDifferenceWithinTwoPercent) {
    const std::string name = GetParam();
    const Scene scene = load_scene(test::source_path("data/office/" + name + ".json"));
    const std::vector<double> ref =
        radiance_reference("data/reference/office/radiance_" + name + ".csv");
    ASSERT_EQ(ref.size(), 77u);
    const app::BakeResult r = test::bake(scene);
    ASSERT_GE(r.sensors.size(), ref.size()); // the .pts file's sensors first, then the grid's
    double sum = 0, sum_abs = 0;
    int n = 0;
    for (std::size_t i = 0; i < ref.size(); ++i) {
        // B's row y = 2 m lies on the edge of the sun patch, where Radiance's point sun
        // (-dj 0) and Penumbra's 0.5° disc differ by about 10 % (data/reference/office).
        if (name == "B" && std::abs(scene.sensors[i].position.y - 2.0) < 1e-6)
            continue;
        const double d = (r.sensors[i].illuminance_total_lx - ref[i]) / ref[i];
        sum += d;
        sum_abs += std::abs(d);
        ++n;
    }
    std::printf("office %s: %d sensors, mean relative difference %+.4f, mean |.| %.4f\n",
                name.c_str(), n, sum / n, sum_abs / n);
    // The goal: 2 % in the mean of per-sensor relative differences (Radiance's own
    // noise is 0.5–1 %, data/reference/office/README.md).
    EXPECT_LT(std::abs(sum / n), 0.02);
    EXPECT_LT(sum_abs / n, 0.02);
}

INSTANTIATE_TEST_SUITE_P(Cases, OfficeAgainstRadiance, ::testing::Values("A", "A-open", "B"),
                         [](const auto& info) { return test::case_name(info.param); });

} // namespace
} // namespace penumbra
