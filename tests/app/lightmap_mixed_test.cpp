// Issue #29's remaining fill features through the whole pipeline: mixed lighting (a light
// baked indirect only), the re-bake from a stored solver state, and `--gather` (the final
// gather per texel sample); their CLI flags and scene keys.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/lightmap.h"
#include "common/bake_util.h"
#include "common/test_util.h"
#include "core/scene_io.h"

namespace penumbra {
namespace {

using test::add_material;
using test::add_rect;

app::LightmapOptions atlas_options(double texels_per_metre, int size) {
    app::LightmapOptions options;
    options.atlas.texels_per_metre = texels_per_metre;
    options.atlas.size = size;
    return options;
}

// ---- Mixed lighting: a 100 cd point light 1 m over a 2 m × 2 m floor. ----

constexpr double k_intensity_w_sr = 1.0;
const Vec3 k_light_position{1.0, 1.0, 1.0};

// The floor, and with \p wall_reflectance > 0 a wall at x = 2 facing the light; every other
// reflectance \p floor_reflectance.
Scene lamp_over_floor(LightmapMode mode, float floor_reflectance, float wall_reflectance) {
    Scene s;
    const auto floor = add_material(s, "floor", Rgb(floor_reflectance));
    add_rect(s, "floor", floor, {0, 0, 0}, {2, 0, 0}, {0, 2, 0});
    if (wall_reflectance > 0) {
        const auto wall = add_material(s, "wall", Rgb(wall_reflectance));
        add_rect(s, "wall", wall, {2, 0, 0}, {0, 0, 1.5}, {0, 2, 0});
    }
    PointLight light;
    light.name = "bulb";
    light.position = k_light_position;
    light.intensity = Rgb(float(k_intensity_w_sr));
    light.lightmap_mode = mode;
    s.point_lights.push_back(light);
    s.mesher.max_edge_length = 0.25;
    s.solver.method = SolverMethod::shooting; // fixed elements: a fast solve
    s.solver.residual = 1e-6;
    return s;
}

// The point light's irradiance at floor point \p p, facing +z: I cos θ / d².
double analytic_direct(const Vec3& p) {
    const Vec3 d = k_light_position - p;
    const double d2 = dot(d, d);
    return k_intensity_w_sr * (d.z / std::sqrt(d2)) / d2;
}

// Calls \p fn(texel value, texel) for every covered texel of the chart of \p object.
void each_texel(const app::LightmapResult& r, const std::string& object,
                const std::function<void(const Rgb&, const lightmap::Texel&)>& fn) {
    for (std::size_t a = 0; a < r.texels.size(); ++a)
        for (const lightmap::Texel& t : r.texels[a].texels)
            if (r.charts.charts[t.chart].object == object)
                fn(r.atlases[a].at(t.x, t.y), t);
}

// The mean of \p value(position) over the texel's footprint samples, as the fill samples it.
double texel_mean(const app::LightmapResult& r, std::size_t atlas, const lightmap::Texel& t,
                  const std::function<double(const Vec3&)>& value) {
    const auto samples = lightmap::texel_samples(r.charts.charts[t.chart],
                                                 r.layout.placements[t.chart], r.texels[atlas], t,
                                                 int(std::lround(std::sqrt(r.samples_per_texel))));
    double sum = 0;
    for (const lightmap::SurfacePoint& s : samples)
        sum += value(s.position);
    return sum / double(samples.size());
}

double analytic_texel(const app::LightmapResult& r, std::size_t atlas, const lightmap::Texel& t) {
    return texel_mean(r, atlas, t, analytic_direct);
}

// Every texel of the irradiance atlases and of the directional ones.
TEST(LightmapMixed, IndirectOnlyLightOverABlackFloorLeavesEveryTexelZero) {
    const Scene scene = lamp_over_floor(LightmapMode::indirect, 0.0f, 0.0f);
    app::LightmapOptions options = atlas_options(20, 64);
    options.directional = true;
    const app::LightmapResult r = app::bake_lightmaps(scene, options, test::quiet_context());
    std::vector<const Image*> images;
    for (const Image& atlas : r.atlases)
        images.push_back(&atlas);
    for (const auto& sh : r.directional)
        for (const Image& image : sh)
            images.push_back(&image);
    ASSERT_EQ(images.size(), 5 * r.atlases.size());
    for (const Image* image : images)
        for (const Rgb& h : image->pixels) {
            ASSERT_EQ(h.r, 0.0f);
            ASSERT_EQ(h.g, 0.0f);
            ASSERT_EQ(h.b, 0.0f);
        }
    EXPECT_GT(r.counts.texels, 1500u); // 40 × 40 floor texels
}

// Mode all over a black floor: each texel is the analytic direct irradiance averaged over
// its footprint samples. The gather point lies 10 ray offsets (10⁻⁴ × the 2.8 m diagonal)
// inside its element: a relative change of about 10⁻⁴ at most; tolerance 10⁻³.
TEST(LightmapMixed, BakedLightMatchesTheInverseSquareCosineLaw) {
    const Scene scene = lamp_over_floor(LightmapMode::all, 0.0f, 0.0f);
    const app::LightmapResult r =
        app::bake_lightmaps(scene, atlas_options(20, 64), test::quiet_context());
    double worst = 0;
    std::size_t count = 0;
    for (std::size_t a = 0; a < r.texels.size(); ++a)
        for (const lightmap::Texel& t : r.texels[a].texels) {
            const double expected = analytic_texel(r, a, t);
            worst = std::max(worst, std::abs(r.atlases[a].at(t.x, t.y).g - expected) / expected);
            ++count;
        }
    EXPECT_GT(count, 1500u);
    EXPECT_LT(worst, 1e-3);
}

// The solution's indirect irradiance at floor point \p p (facing +z): vertex values of the
// element under it, interpolated linearly, as the fill reads them.
Rgb solution_indirect_at(const app::BakeResult& bake, const Vec3& p) {
    const RadiosityMesh& mesh = bake.mesh;
    for (std::uint32_t e = 0; e < mesh.element_count(); ++e) {
        if (mesh.patch_of(e).normal.z < 0.99)
            continue;
        const auto& tri = mesh.triangles[e];
        const Vec3 a = mesh.vertex(tri[0]), b = mesh.vertex(tri[1]), c = mesh.vertex(tri[2]);
        const double area = cross(b - a, c - a).z;
        const double wb = cross(p - a, c - a).z / area, wc = cross(b - a, p - a).z / area;
        if (wb < -1e-9 || wc < -1e-9 || wb + wc > 1 + 1e-9)
            continue;
        const auto& h = bake.solution.vertex_irradiance_indirect;
        return h[tri[0]] * float(1 - wb - wc) + h[tri[1]] * float(wb) + h[tri[2]] * float(wc);
    }
    ADD_FAILURE() << "no floor element under " << p.x << ", " << p.y;
    return {};
}

// A reflecting floor and wall: with the light indirect only, each floor texel is the
// solution's indirect irradiance interpolated at its samples (found here by a search of the
// floor's elements, there by a ray: 10⁻⁴ of the floor's brightest indirect value); with mode
// all, the analytic direct light on top (the same solution: 10⁻³ of the direct).
TEST(LightmapMixed, IndirectOnlyTexelsAreTheSolutionsIndirectLight) {
    const Scene indirect = lamp_over_floor(LightmapMode::indirect, 0.5f, 0.8f);
    const Scene all = lamp_over_floor(LightmapMode::all, 0.5f, 0.8f);
    const Context ctx = test::quiet_context();
    app::LightmapResult r = app::plan_lightmaps(indirect, atlas_options(10, 64), ctx);
    const app::BakeResult bake = app::bake(indirect, app::lightmap_bake_options(), ctx);
    app::fill_lightmaps(indirect, bake, r, ctx);
    const app::LightmapResult r_all =
        app::bake_lightmaps(all, atlas_options(10, 64), test::quiet_context());
    double brightest = 0;
    each_texel(r, "floor", [&](const Rgb& h, const lightmap::Texel&) {
        brightest = std::max(brightest, double(h.g));
    });
    ASSERT_GT(brightest, 0.01); // the wall's reflection
    std::size_t count = 0;
    for (std::size_t a = 0; a < r.texels.size(); ++a)
        for (const lightmap::Texel& t : r.texels[a].texels) {
            if (r.charts.charts[t.chart].object != "floor")
                continue;
            const Rgb h = r.atlases[a].at(t.x, t.y);
            const double indirect = texel_mean(
                r, a, t, [&](const Vec3& p) { return double(solution_indirect_at(bake, p).g); });
            EXPECT_NEAR(h.g, indirect, 1e-4 * brightest);
            const double direct = analytic_texel(r, a, t);
            EXPECT_NEAR(r_all.atlases[a].at(t.x, t.y).g - h.g, direct, 1e-3 * direct);
            ++count;
        }
    EXPECT_GT(count, 350u);
}

// With `--gather` the indirect-only light's direct part is subtracted: the gather finds a
// point light's exactly (a delta, one shadow ray), as the direct gather does, so the black
// floor reads 0 up to float rounding (10⁻⁵ of the light's 1 W/m² under it).
TEST(LightmapMixed, GatherLeavesOutTheIndirectOnlyLight) {
    const Scene scene = lamp_over_floor(LightmapMode::indirect, 0.0f, 0.0f);
    app::LightmapOptions options = atlas_options(20, 64);
    options.gather_samples = 4;
    const app::LightmapResult r = app::bake_lightmaps(scene, options, test::quiet_context());
    float largest = 0;
    for (const Image& atlas : r.atlases)
        for (const Rgb& h : atlas.pixels)
            largest = std::max({largest, h.r, h.g, h.b});
    EXPECT_LT(largest, 1e-5f);
    EXPECT_GT(r.counts.texels, 1500u);
}

TEST(LightmapMixed, SceneKeyReadsEveryLightsModeAndRefusesAnUnknownOne) {
    const std::string dir = test::temp_dir("lightmap-mode");
    const auto write = [&](const std::string& mode) {
        std::ofstream(dir + "/scene.json") << R"({
  "materials": {"lamp": {"emission": [1, 1, 1], "lightmap_mode": "indirect"}},
  "polygons": [{"name": "lamp", "material": "lamp", "vertices": [[0,0,1],[0,1,1],[1,1,1]]}],
  "point_lights": [{"name": "bulb", "position": [0, 0, 2], "intensity_cd": 100,
                    "lightmap_mode": ")" + mode + R"("}],
  "sun": {"direction": [0, 0, 1], "irradiance_w_m2": 100, "lightmap_mode": "indirect"},
  "sky": {"model": "uniform", "horizontal_illuminance_lx": 1000, "lightmap_mode": "all"},
  "lightmap": {"gather": 8}
})";
        return dir + "/scene.json";
    };
    const Scene scene = load_scene(write("indirect"));
    EXPECT_EQ(scene.materials.at(0).lightmap_mode, LightmapMode::indirect);
    EXPECT_EQ(scene.point_lights.at(0).lightmap_mode, LightmapMode::indirect);
    EXPECT_EQ(scene.sun->lightmap_mode, LightmapMode::indirect);
    EXPECT_EQ(scene.sky->lightmap_mode, LightmapMode::all);
    EXPECT_EQ(scene.lightmap->gather, 8);
    test::expect_one_line_input_error([&] { load_scene(write("mixed")); },
                                      {"lightmap_mode", "unknown lightmap mode 'mixed'"},
                                      "a bad lightmap_mode");
    std::filesystem::remove_all(dir);
}

// ---- Re-bake: radiosity is linear in emission, so the re-solve of the Cornell box's stored
// links with its lamp twice as bright gives twice the lightmaps of their re-solve with the lamp
// as it was: the refinement oracle scales with the radiosities (ε is relative to the brightest
// exitance), so both refine the same links. Both solves stop at a residual of 10⁻⁶ of the
// emitted power: 10⁻⁴ of the brightest texel. The full bake of the changed scene stops
// refining once a cycle adds under 0.5 % to its links (k_settled_growth), where the re-solve
// runs one more refinement (9 links here, 0.05 % of the brightest texel): 10⁻³. ----

Scene with_brighter_lamp(Scene scene, float factor) {
    for (Material& m : scene.materials)
        m.emission = m.emission * factor;
    return scene;
}

float brightest(const std::vector<Image>& atlases) {
    float out = 0;
    for (const Image& atlas : atlases)
        for (const Rgb& h : atlas.pixels)
            out = std::max({out, h.r, h.g, h.b});
    return out;
}

// The largest channel difference between a × \p scale_a and b over every texel.
float largest_difference(const std::vector<Image>& a, float scale_a, const std::vector<Image>& b) {
    float out = 0;
    for (std::size_t k = 0; k < a.size(); ++k)
        for (std::size_t i = 0; i < a[k].pixels.size(); ++i)
            for (int c = 0; c < 3; ++c)
                out = std::max(out, std::abs(a[k].pixels[i][c] * scale_a - b[k].pixels[i][c]));
    return out;
}

TEST(LightmapRebake, DoubledLampReusingTheLinksEqualsTheFullBake) {
    Scene scene = test::cornell_box(0.15);
    scene.solver.residual = 1e-6;
    const Scene doubled = with_brighter_lamp(scene, 2.0f);
    const Context ctx = test::quiet_context();
    const app::LightmapOptions options = atlas_options(60, 256);
    app::BakeOptions keep = app::lightmap_bake_options();
    keep.keep_state = true;
    const app::BakeResult first = app::bake(scene, keep, ctx);
    ASSERT_TRUE(first.solver_state);
    app::LightmapResult original = app::plan_lightmaps(scene, options, ctx);
    app::fill_lightmaps(scene, first, original, ctx);

    app::BakeOptions reuse = app::lightmap_bake_options();
    reuse.reuse = first.solver_state.get();
    auto rebake = [&](const Scene& changed) {
        app::LightmapResult r = app::plan_lightmaps(changed, options, ctx);
        app::fill_lightmaps(changed, app::bake(changed, reuse, ctx), r, ctx);
        return r;
    };
    const app::LightmapResult same = rebake(scene), rebaked = rebake(doubled);
    const app::LightmapResult full = app::bake_lightmaps(doubled, options, ctx);

    const float top = brightest(full.atlases);
    ASSERT_GT(top, 0.0f);
    ASSERT_EQ(rebaked.atlases.size(), full.atlases.size());
    EXPECT_LT(largest_difference(same.atlases, 2.0f, rebaked.atlases), 1e-4f * top);
    EXPECT_LT(largest_difference(rebaked.atlases, 1.0f, full.atlases), 1e-3f * top);
    EXPECT_LT(largest_difference(original.atlases, 2.0f, rebaked.atlases), 1e-3f * top);
}

// ---- `--gather`: the furnace (every wall emits E, reflectance ρ) receives E / (1 − ρ)
// everywhere; the final gather finds it from light samples on the emitting walls and paths
// that read ρ E / (1 − ρ) / π one bounce away. ----

app::LightmapResult furnace_gathered(int samples, int threads) {
    const Scene scene = test::furnace_room(0.5f, 1.0f);
    app::LightmapOptions options = atlas_options(12, 64);
    options.gather_samples = samples;
    return app::bake_lightmaps(scene, options, test::quiet_context(threads));
}

// The texels' relative errors against E / (1 − ρ): their mean, root mean square and largest.
struct GatherError {
    double mean = 0, rms = 0, worst = 0;
    std::size_t texels = 0;
};

GatherError furnace_error(const app::LightmapResult& r) {
    const double expected = 1.0 / (1 - 0.5);
    GatherError e;
    for (std::size_t a = 0; a < r.texels.size(); ++a)
        for (const lightmap::Texel& t : r.texels[a].texels) {
            const double d = (r.atlases[a].at(t.x, t.y).g - expected) / expected;
            e.mean += d;
            e.rms += d * d;
            e.worst = std::max(e.worst, std::abs(d));
            ++e.texels;
        }
    e.mean /= double(e.texels);
    e.rms = std::sqrt(e.rms / double(e.texels));
    return e;
}

// Unbiased: the mean over all texels within 0.5 %. The noise falls as 1/√paths: the RMS error
// at 16 paths per sample is twice that at 64 (within [1.6, 2.5]).
TEST(LightmapGather, FurnaceTexelsReceiveEOverOneMinusRho) {
    const GatherError e16 = furnace_error(furnace_gathered(16, 0));
    const GatherError e64 = furnace_error(furnace_gathered(64, 0));
    std::printf("gather furnace: 16 paths: mean %.5f rms %.5f worst %.5f; 64 paths: mean %.5f "
                "rms %.5f worst %.5f (%zu texels)\n",
                e16.mean, e16.rms, e16.worst, e64.mean, e64.rms, e64.worst, e16.texels);
    ASSERT_GT(e16.texels, 400u);
    EXPECT_LT(std::abs(e16.mean), 0.005);
    EXPECT_LT(std::abs(e64.mean), 0.005);
    EXPECT_GT(e16.rms / e64.rms, 1.6);
    EXPECT_LT(e16.rms / e64.rms, 2.5);
    EXPECT_LT(e64.rms, 0.05);
}

TEST(LightmapGather, SameBitsForOneAndTwoThreads) {
    const app::LightmapResult one = furnace_gathered(4, 1);
    const app::LightmapResult two = furnace_gathered(4, 2);
    ASSERT_EQ(one.atlases.size(), two.atlases.size());
    for (std::size_t a = 0; a < one.atlases.size(); ++a) {
        const auto& p1 = one.atlases[a].pixels;
        const auto& p2 = two.atlases[a].pixels;
        ASSERT_EQ(p1.size(), p2.size());
        EXPECT_EQ(std::memcmp(p1.data(), p2.data(), p1.size() * sizeof(Rgb)), 0);
    }
}

// ---- The CLI: bake, then re-bake the lightmaps with `--reuse` and `--gather`; one-line
// errors for bad values before anything is written. ----

const char* k_cli_scene = R"({
  "materials": {"lamp": {"emission": [1, 1, 1], "reflectance": 0}, "floor": {"reflectance": 0.5}},
  "polygons": [
    {"name": "lamp", "material": "lamp", "vertices": [[0,0,1],[0,1,1],[1,1,1],[1,0,1]]},
    {"name": "floor", "material": "floor", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}
  ],
  "point_lights": [{"name": "bulb", "position": [0.5, 0.5, 0.5], "intensity_cd": 10,
                    "lightmap_mode": "indirect"}],
  "mesher": {"max_edge_length": 0.5},
  "solver": {"min_area": 0.01}
})";

TEST(LightmapMixedCli, RebakesFromABakesStateAndListsTheModes) {
    const std::filesystem::path dir = test::temp_dir("lightmap-rebake");
    std::ofstream(dir / "scene.json") << k_cli_scene;
    const std::string scene = (dir / "scene.json").string();
    test::RunResult r = test::run_cli("bake " + scene + " -o " + (dir / "bake").string() + " -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = test::run_cli("lightmap " + scene + " -o " + (dir / "out").string() + " --reuse " +
                      (dir / "bake").string() + " --gather 4 --texels-per-metre 16 --atlas 64 -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto manifest = nlohmann::json::parse(std::ifstream(dir / "out" / "lightmaps.json"));
    ASSERT_EQ(manifest["lights"].size(), 2u);
    EXPECT_EQ(manifest["lights"][0]["name"], "bulb");
    EXPECT_EQ(manifest["lights"][0]["mode"], "indirect");
    EXPECT_EQ(manifest["lights"][1]["kind"], "material");
    EXPECT_EQ(manifest["lights"][1]["mode"], "all");
    // Bad flags exit 3, a missing state (bad input) 2, as bake --reuse.
    const std::vector<std::pair<std::string, int>> bad{
        {"--gather -1", 3}, {"--gather many", 3}, {"--reuse " + (dir / "nothing").string(), 2}};
    for (const auto& [flags, code] : bad) {
        r = test::run_cli("lightmap " + scene + " -o " + (dir / "bad").string() + " -q " + flags);
        EXPECT_EQ(r.exit_code, code) << flags << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << flags << ": " << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir / "bad" / "lightmaps.json")) << flags;
    }
    std::filesystem::remove_all(dir);
}

} // namespace
} // namespace penumbra
