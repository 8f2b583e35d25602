// Directional lightmaps (issue #29): the L1 atlases against a furnace's hemisphere of uniform
// radiance, against a point light's exact direction, the irradiance they give at the surface
// normal, the same bits for any thread count, and the files of `--directional`.

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/lightmap.h"
#include "common/bake_util.h"
#include "common/test_util.h"
#include "lightmap/sh.h"
#include "lightmap/texels.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using test::add_material;
using test::add_rect;

app::LightmapResult directional_lightmaps(const Scene& scene, double texels_per_metre, int size,
                                          int threads = 0) {
    app::LightmapOptions options;
    options.atlas.texels_per_metre = texels_per_metre;
    options.atlas.size = size;
    options.directional = true;
    return app::bake_lightmaps(scene, options, test::quiet_context(threads));
}

// Coefficient k (0 = L00, 1..3 = L1−1, L10, L11) of texel \p t, green channel.
double coefficient(const app::LightmapResult& r, std::size_t atlas, const lightmap::Texel& t,
                   std::size_t k) {
    return r.directional[atlas][k].at(t.x, t.y).g;
}

// Band 1 as a vector in (x, y, z): (L11, L1−1, L10).
Vec3 band1(const app::LightmapResult& r, std::size_t atlas, const lightmap::Texel& t) {
    return {coefficient(r, atlas, t, 3), coefficient(r, atlas, t, 1), coefficient(r, atlas, t, 2)};
}

// E(n) = π L00 Y00 + (2π/3) Σ L1m Y1m(n), the documented reconstruction.
double irradiance_at(const app::LightmapResult& r, std::size_t atlas, const lightmap::Texel& t,
                     const Vec3& n) {
    const auto y = lightmap::sh_basis_l2(n);
    return k_pi * coefficient(r, atlas, t, 0) * y[0] +
           2 * k_pi / 3 *
               (coefficient(r, atlas, t, 1) * y[1] + coefficient(r, atlas, t, 2) * y[2] +
                coefficient(r, atlas, t, 3) * y[3]);
}

// ---- A furnace: a closed box of B = E / (1 − ρ) everywhere. A texel sees the uniform
// radiance L = B/π over its hemisphere (none from behind its surface): L00 = √π L and band 1
// = (√(3π)/2) L n along its normal n (∫ over the hemisphere of L Y00 and of L Y1m); the
// reconstruction gives π L = B at n. (Over the whole sphere, as a probe sees it, L00 = 2√π L
// and band 1 vanishes: tests/lightmap/sh_test.cpp.) ----

TEST(LightmapDirectional, FurnaceTexelsHoldTheHemisphereOfUniformRadiance) {
    const float rho = 0.5f, exitance = 1.0f;
    Scene scene = test::furnace_room(rho, exitance);
    const app::LightmapResult r = directional_lightmaps(scene, 12, 64);
    ASSERT_EQ(r.directional.size(), r.atlases.size());
    const double b = exitance / (1 - rho), l = b / k_pi;
    double worst_l1 = 0, worst_e = 0;
    Vec3 bias; // the mean relative error vector: 0 if the estimate is unbiased
    std::size_t texels = 0;
    for (std::size_t a = 0; a < r.texels.size(); ++a)
        for (const lightmap::Texel& t : r.texels[a].texels) {
            const Vec3 n = t.centre.normal;
            const Vec3 expected = n * (std::sqrt(3 * k_pi) / 2 * l);
            const Vec3 error = (band1(r, a, t) - expected) / length(expected);
            worst_l1 = std::max(worst_l1, length(error));
            bias += error;
            worst_e = std::max(worst_e, std::abs(irradiance_at(r, a, t, n) - b) / b);
            ++texels;
        }
    bias = bias / double(texels);
    EXPECT_GT(texels, 400u);
    // 72 gather rays and 72 light samples per texel: Monte Carlo noise, largest (measured
    // 35 %) at edge texels, where the next wall is near; 90 % of the texels within 15 %.
    EXPECT_LT(worst_l1, 0.5);
    EXPECT_LT(length(bias), 0.02);
    EXPECT_LT(worst_e, 0.005);
}

// ---- A point light of intensity I over a black floor: band 1 of each floor texel is the mean
// over its samples of (I/d²) Y1(d0), d0 the direction to the light: per sample a vector along
// d0 of length √(3/4π) I/d². At the floor's normal the reconstruction equals the irradiance
// atlas. ----

TEST(LightmapDirectional, PointLightGivesBandOneAlongItsDirection) {
    Scene scene;
    const auto black = add_material(scene, "black", Rgb(0.0f));
    add_rect(scene, "floor", black, {-1, -1, 0}, {2, 0, 0}, {0, 2, 0});
    PointLight light;
    light.position = {0.2, -0.1, 0.8};
    light.intensity = Rgb(1.0f);
    scene.point_lights.push_back(light);
    scene.mesher.max_edge_length = 0.5;
    const app::LightmapResult r = directional_lightmaps(scene, 10, 64);
    std::size_t texels = 0;
    for (std::size_t a = 0; a < r.texels.size(); ++a)
        for (const lightmap::Texel& t : r.texels[a].texels) {
            const auto samples = lightmap::texel_samples(
                r.charts.charts[t.chart], r.layout.placements[t.chart], r.texels[a], t, 3);
            Vec3 expected;
            for (const lightmap::SurfacePoint& s : samples) {
                const Vec3 to = light.position - s.position;
                expected += normalize(to) * (std::sqrt(3 / (4 * k_pi)) / dot(to, to));
            }
            expected = expected / double(samples.size());
            EXPECT_LT(length(band1(r, a, t) - expected), 1e-3 * length(expected))
                << "texel " << t.x << ", " << t.y;
            const double e = r.atlases[a].at(t.x, t.y).g;
            EXPECT_NEAR(irradiance_at(r, a, t, t.centre.normal), e, 1e-5 * e + 1e-9);
            ++texels;
        }
    EXPECT_GT(texels, 300u);
}

// ---- The Cornell box: the same bits on 1 and 2 threads (one bake, filled twice). ----

TEST(LightmapDirectional, SameBitsForAnyThreadCount) {
    Scene scene = test::cornell_box(0.3);
    scene.solver.method = SolverMethod::shooting; // fast; the solution's accuracy is not tested
    app::LightmapOptions options;
    options.atlas.texels_per_metre = 40;
    options.atlas.size = 128;
    options.directional = true;
    app::LightmapResult one = app::plan_lightmaps(scene, options, test::quiet_context());
    app::LightmapResult two = one;
    const app::BakeResult baked =
        app::bake(scene, app::lightmap_bake_options(), test::quiet_context());
    app::fill_lightmaps(scene, baked, one, test::quiet_context(1));
    app::fill_lightmaps(scene, baked, two, test::quiet_context(2));
    ASSERT_EQ(one.directional.size(), two.directional.size());
    for (std::size_t a = 0; a < one.directional.size(); ++a)
        for (std::size_t k = 0; k < 4; ++k) {
            const auto& p1 = one.directional[a][k].pixels;
            const auto& p2 = two.directional[a][k].pixels;
            ASSERT_EQ(p1.size(), p2.size());
            EXPECT_EQ(std::memcmp(p1.data(), p2.data(), p1.size() * sizeof(Rgb)), 0)
                << "atlas " << a << ", coefficient " << k;
        }
}

// ---- `penumbra lightmap --directional` writes four more EXRs per atlas and says so. ----

TEST(LightmapDirectional, CliWritesTheShAtlases) {
    const fs::path dir = test::temp_dir("directional-cli");
    std::ofstream(dir / "scene.json") << R"({
      "materials": {"lamp": {"emission": [1, 1, 1], "reflectance": 0},
                    "floor": {"reflectance": 0.5}},
      "polygons": [
        {"name": "lamp", "material": "lamp", "vertices": [[0,0,1],[0,1,1],[1,1,1],[1,0,1]]},
        {"name": "floor", "material": "floor", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}],
      "mesher": {"max_edge_length": 0.5}
    })";
    const test::RunResult r =
        test::run_cli("lightmap " + (dir / "scene.json").string() + " -o " +
                      (dir / "out").string() + " -q --atlas 32 --directional");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* f :
         {"lightmap_0_L00.exr", "lightmap_0_L1m1.exr", "lightmap_0_L10.exr", "lightmap_0_L11.exr"})
        EXPECT_TRUE(fs::exists(dir / "out" / f)) << f;
    const auto j = nlohmann::json::parse(std::ifstream(dir / "out" / "lightmaps.json"));
    EXPECT_EQ(j["atlases"][0]["sh_exr"].size(), 4u);
    EXPECT_TRUE(j.contains("directional"));
    fs::remove_all(dir);
}

} // namespace
} // namespace penumbra
