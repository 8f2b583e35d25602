// Light probes (issue #29) through the whole pipeline: a furnace box of known radiosity, a
// single point light against its closed-form L2 projection, shadowing, the same bits on 1 and
// 2 threads, the scene key and the files the CLI writes.

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/probes.h"
#include "common/bake_util.h"
#include "common/test_util.h"
#include "core/error.h"
#include "core/scene_io.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using test::add_material;
using test::add_rect;

app::ProbeResult probes_of(const Scene& scene, int threads = 0) {
    const app::BakeResult baked = test::bake(scene, threads);
    return app::compute_probes(scene, *scene.probes, baked, test::quiet_context(threads));
}

std::vector<Vec3> test_normals() {
    std::vector<Vec3> out{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int k = 0; k < 12; ++k) {
        const double z = -0.9 + 0.15 * k, phi = 2.39996 * k;
        const double r = std::sqrt(1 - z * z);
        out.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
    }
    return out;
}

// ---- A furnace: a closed box whose every surface emits E with reflectance ρ has
// B = E / (1 − ρ) everywhere, so every probe inside sees the uniform radiance B/π: E(n) = B
// for every n, and bands 1 and 2 vanish. ----

TEST(Probes, FurnaceBoxGivesUniformIrradianceAndBandZeroOnly) {
    const float rho = 0.5f, exitance = 1.0f;
    Scene scene = test::furnace_room(rho, exitance);
    scene.probes = ProbeSettings{};
    scene.probes->points = {{0.5, 0.35, 0.25}, {0.05, 0.05, 0.05}, {0.9, 0.6, 0.45}};
    scene.probes->rays = 512;
    const app::ProbeResult r = probes_of(scene);
    ASSERT_EQ(r.probes.size(), 3u);
    const double b = exitance / (1 - rho);
    for (const app::Probe& p : r.probes) {
        for (const Vec3& n : test_normals())
            EXPECT_NEAR(p.irradiance.evaluate(n).g, b, 0.01 * b) << "normal " << n.x << ", " << n.y;
        for (std::size_t k = 1; k < 9; ++k)
            EXPECT_LT(std::abs(p.irradiance.c[k].g), 0.01 * p.irradiance.c[0].g) << k;
    }
}

// ---- A point light of intensity I over a black floor: the only light at a probe is the
// delta I/d² from the light's direction d0, so the band-0 term is exact, E(d0) is L2's
// 1.0625 I/d² and E(n) stays within its ringing of 3I/(32 d²) of I cos γ / d² on the facing
// hemisphere (tests/lightmap/sh_test.cpp derives both). A probe under a black plate is dark. ----

Scene point_light_over_floor() {
    Scene scene;
    const auto black = add_material(scene, "black", Rgb(0.0f));
    add_rect(scene, "floor", black, {-2, -2, 0}, {4, 0, 0}, {0, 4, 0});
    add_rect(scene, "plate", black, {1, 1, 0.3}, {0.5, 0, 0}, {0, 0.5, 0}); // faces up
    PointLight light;
    light.position = {0, 0, 1};
    light.intensity = Rgb(2.0f);
    scene.point_lights.push_back(light);
    scene.mesher.max_edge_length = 0.5;
    scene.probes = ProbeSettings{};
    scene.probes->points = {{0.3, 0.2, 0.5}, {1.25, 1.25, 0.15}};
    scene.probes->rays = 128;
    return scene;
}

TEST(Probes, PointLightIsExactInBandZeroAndWithinL2Ringing) {
    const Scene scene = point_light_over_floor();
    const app::ProbeResult r = probes_of(scene);
    const app::Probe& lit = r.probes[0];
    const Vec3 to_light = scene.point_lights[0].position - lit.position;
    const double d2 = dot(to_light, to_light), e = 2.0 / d2;
    const Vec3 d0 = normalize(to_light);
    const double y00 = lightmap::sh_basis_l2(d0)[0];
    EXPECT_NEAR(lit.irradiance.c[0].g * y00, e / 4, 1e-6 * e); // the mean of E(n): I/(4d²)
    EXPECT_NEAR(lit.irradiance.evaluate(d0).g, 1.0625 * e, 1e-6 * e);
    for (const Vec3& n : test_normals()) {
        const double c = dot(n, d0);
        if (c >= 0) {
            EXPECT_LE(std::abs(lit.irradiance.evaluate(n).g - e * c), 3.0 / 32.0 * e + 1e-6 * e);
        }
    }
    for (const RgbD& c : r.probes[1].irradiance.c)
        EXPECT_EQ(c.g, 0.0) << "the probe under the plate sees the light";
}

// ---- The Cornell box: a grid of probes, the same bits for 1 and 2 threads. ----

TEST(Probes, SameBitsForAnyThreadCount) {
    Scene scene = test::cornell_box(0.3);
    scene.solver.method = SolverMethod::shooting; // fast; the solution's accuracy is not tested
    scene.probes = ProbeSettings{};
    const BBox box = scene.bounds();
    scene.probes->grid =
        ProbeGrid{box.lo + Vec3(0.05, 0.05, 0.05), box.hi - Vec3(0.05, 0.05, 0.05), 0.15};
    scene.probes->rays = 64;
    const app::BakeResult baked = test::bake(scene);
    const app::ProbeResult one =
        app::compute_probes(scene, *scene.probes, baked, test::quiet_context(1));
    const app::ProbeResult two =
        app::compute_probes(scene, *scene.probes, baked, test::quiet_context(2));
    ASSERT_EQ(one.probes.size(), two.probes.size());
    ASSERT_GE(one.probes.size(), 27u);
    std::size_t lit = 0; // probes inside a block see only its faces' backs: dark
    for (std::size_t i = 0; i < one.probes.size(); ++i) {
        EXPECT_EQ(std::memcmp(&one.probes[i], &two.probes[i], sizeof(app::Probe)), 0) << i;
        lit += one.probes[i].irradiance.c[0].g > 0;
    }
    EXPECT_GT(lit, one.probes.size() * 2 / 3);
}

// ---- The scene key: points and a grid in the file's units, bad values one-line errors. ----

TEST(Probes, SceneKeyGivesPointsAndACentredGrid) {
    const std::string head = R"({"units": "cm", "materials": {"lamp": {"emission": 1}},
      "polygons": [{"material": "lamp", "vertices": [[0,0,0],[100,0,0],[100,100,0]]}],
      "probes": )";
    const Scene scene = parse_scene(
        head + R"({"points": [[10, 20, 30]], "grid": {"min": [0,0,0], "max": [100, 50, 0],
        "spacing": 40}, "rays": 256}})",
        "probes.json", ".");
    ASSERT_TRUE(scene.probes);
    EXPECT_EQ(scene.probes->rays, 256);
    const std::vector<Vec3> p = scene.probes->positions();
    ASSERT_EQ(p.size(), 1u + 3 * 2 * 1);
    EXPECT_NEAR(p[0].z, 0.3, 1e-12);
    EXPECT_NEAR(p[1].x, 0.1, 1e-12); // 3 points 0.4 m apart centred in 1 m: 0.1, 0.5, 0.9
    EXPECT_NEAR(p[1].y, 0.05, 1e-12);
    EXPECT_NEAR(p[6].x, 0.9, 1e-12);
    EXPECT_NEAR(p[6].y, 0.45, 1e-12);
    for (const char* bad : {R"({})", R"({"grid": {"min": [0,0,0], "max": [1,1,1]}})",
                            R"({"points": [[0,0,0]], "rays": 4})",
                            R"({"grid": {"min": [0,0,0], "max": [-1,1,1], "spacing": 1}})",
                            R"({"grid": {"min": [0,0,0], "max": [100,100,100], "spacing": 0.1}})"})
        EXPECT_THROW(parse_scene(head + bad + "}", "probes.json", "."), InputError) << bad;
}

// ---- The CLI: `penumbra lightmap` and `bake` write probes.json and probes.vtp for the scene's
// key. ----

TEST(Probes, CliWritesProbesJsonAndVtp) {
    const fs::path dir = test::temp_dir("probes-cli");
    std::ofstream(dir / "scene.json") << R"({
      "materials": {"lamp": {"emission": [1, 1, 1], "reflectance": 0},
                    "floor": {"reflectance": 0.5}},
      "polygons": [
        {"name": "lamp", "material": "lamp", "vertices": [[0,0,1],[0,1,1],[1,1,1],[1,0,1]]},
        {"name": "floor", "material": "floor", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}],
      "mesher": {"max_edge_length": 0.5},
      "probes": {"points": [[0.5, 0.5, 0.5]], "rays": 64}
    })";
    const test::RunResult r = test::run_cli("lightmap " + (dir / "scene.json").string() + " -o " +
                                            (dir / "out").string() + " -q --atlas 32");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / "out" / "probes.vtp"));
    const auto j = nlohmann::json::parse(std::ifstream(dir / "out" / "probes.json"));
    ASSERT_EQ(j["probes"].size(), 1u);
    EXPECT_EQ(j["probes"][0]["sh"].size(), 9u);
    EXPECT_EQ(j["rays_per_probe"], 72);
    EXPECT_NE(j["convention"].get<std::string>().find("Y1-1"), std::string::npos);
    EXPECT_GT(j["probes"][0]["sh"][0][1].get<double>(), 0.0); // lit: a positive mean
    // `bake` writes them too.
    const test::RunResult baked = test::run_cli("bake " + (dir / "scene.json").string() + " -o " +
                                                (dir / "baked").string() + " -q --no-render");
    ASSERT_EQ(baked.exit_code, 0) << baked.err;
    EXPECT_TRUE(fs::exists(dir / "baked" / "probes.json"));
    EXPECT_TRUE(fs::exists(dir / "baked" / "probes.vtp"));
    fs::remove_all(dir);
}

} // namespace
} // namespace penumbra
