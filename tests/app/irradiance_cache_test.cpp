// The final gather's irradiance cache (issue #28; docs/rendering.md): the white furnace
// against its analytic radiance, the Cornell box per tile against the plain final gather,
// thread-count independence, and bad values of the option.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "app/pipeline.h"
#include "common/bake_util.h"
#include "common/reference_tiles.h"
#include "common/test_util.h"
#include "core/image.h"
#include "raytrace/raytrace.h"

namespace penumbra {
namespace {

using raytrace::RenderOptions;

RenderOptions cached(int spp) {
    RenderOptions options;
    options.spp = spp;
    options.irradiance_cache = IrradianceCacheSettings{};
    return options;
}

Image render(const raytrace::EmbreeScene& rt, const app::BakeResult& baked, const Scene& scene,
             const RenderOptions& options, const Context& ctx) {
    return raytrace::render_final_gather(rt, scene, baked.solution, *scene.camera, options, ctx);
}

double mean_green(const Image& image) {
    double sum = 0;
    for (const Rgb& p : image.pixels)
        sum += p.g;
    return sum / double(image.pixels.size());
}

/// A closed room whose every wall emits E and reflects ρ reads L = E / (π (1 − ρ)) at every
/// pixel: emitted E/π, direct light sampled per camera sample, and ρ/π times the cached
/// indirect irradiance. The image's mean within 0.5 %.
TEST(IrradianceCache, FurnaceReadsTheGeometricSeries) {
    const float rho = 0.5f, exitance = 1.0f;
    Scene scene = test::furnace_room(rho, exitance);
    scene.render.max_bounces = 64; // ρ^65 of the answer left out
    // A corner: three walls, two edges.
    scene.camera = test::square_camera({0.2, 0.2, 0.2}, {0.9, 0.6, 0.4}, {0, 0, 1}, 70, 32);
    const app::BakeResult baked = test::bake(scene);
    const raytrace::EmbreeScene rt(baked.mesh);
    const double expected = exitance / (k_pi * (1 - rho));
    const double mean = mean_green(render(rt, baked, scene, cached(64), test::quiet_context()));
    EXPECT_NEAR(mean, expected, 0.005 * expected);
}

/// Cornell box, 64², per 16 × 16 tile: the cache's mean over eight seeds against the plain
/// final gather's within 3 standard errors (both) + 0.5 %. Interpolation must not move any
/// tile, wall junctions and the blocks' contact shadows included.
TEST(IrradianceCache, CornellTilesAgreeWithThePlainGather) {
    Scene scene = test::cornell_box(0.05);
    scene.camera->width = scene.camera->height = 64;
    const app::BakeResult baked = test::bake(scene);
    const raytrace::EmbreeScene rt(baked.mesh);
    std::vector<Image> with_cache, plain;
    for (int k = 0; k < 8; ++k) {
        Context ctx = test::quiet_context();
        ctx.seed = std::uint64_t(k + 101);
        with_cache.push_back(render(rt, baked, scene, cached(16), ctx));
        RenderOptions options;
        options.spp = 16;
        plain.push_back(render(rt, baked, scene, options, ctx));
    }
    const test::TileStats ic = test::tile_stats(with_cache), fg = test::tile_stats(plain);
    int failures = 0;
    for (std::size_t t = 0; t < ic.mean.size(); ++t) {
        const double se = std::hypot(ic.standard_error[t], fg.standard_error[t]);
        if (std::abs(ic.mean[t] - fg.mean[t]) > 3 * se + 0.005 * fg.mean[t]) {
            ++failures;
            ADD_FAILURE() << "tile " << t << ": cached " << ic.mean[t] << ", plain gather "
                          << fg.mean[t] << " ± " << se;
        }
    }
    EXPECT_EQ(failures, 0);
}

TEST(IrradianceCache, BitwiseIdenticalForOneAndTwoThreads) {
    Scene scene = test::cornell_box(0.1);
    scene.camera->width = scene.camera->height = 48;
    const app::BakeResult baked = test::bake(scene);
    const raytrace::EmbreeScene rt(baked.mesh);
    const Image one = render(rt, baked, scene, cached(4), test::quiet_context(1));
    const Image two = render(rt, baked, scene, cached(4), test::quiet_context(2));
    ASSERT_EQ(one.pixels.size(), two.pixels.size());
    EXPECT_TRUE(std::equal(one.pixels.begin(), one.pixels.end(), two.pixels.begin()));
}

/// The Cornell box's scene with \p render_key as its `render` object, beside a copy of its
/// geometry in \p dir; returns the scene file's path.
std::string cornell_with_render(const std::string& dir, const std::string& render_key) {
    namespace fs = std::filesystem;
    for (const char* file : {"cornell.obj", "cornell.mtl"})
        fs::copy_file(test::source_path(std::string("data/cornell/") + file), fs::path(dir) / file,
                      fs::copy_options::overwrite_existing);
    const std::string path = (fs::path(dir) / "scene.json").string();
    std::ofstream(path) << R"({"units": "mm", "up": [0, 1, 0], "geometry": "cornell.obj",
  "camera": {"eye": [278, 273, -800], "look_at": [278, 273, 0], "fov_deg": 39.3},
  "image": {"width": 16, "height": 16}, "render": )"
                        << render_key << "}\n";
    return path;
}

TEST(IrradianceCache, BadValuesAreOneLineErrors) {
    const std::string dir = test::temp_dir("irradiance_cache_bad");
    for (const std::string key :
         {R"({"irradiance_cache": "yes"})", R"({"irradiance_cache": {"error": 0}})",
          R"({"irradiance_cache": {"rays": 4}})", R"({"irradiance_cache": {"records": 9}})"}) {
        const std::string scene = cornell_with_render(dir, key);
        const test::RunResult r = test::run_cli("render " + scene + " -o " + dir + "/out");
        EXPECT_EQ(r.exit_code, 2) << key << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << key << ": " << r.err;
        EXPECT_NE(r.err.find("render.irradiance_cache"), std::string::npos) << r.err;
    }
    const std::string scene = cornell_with_render(dir, "{}");
    const test::RunResult r =
        test::run_cli("render " + scene + " -o " + dir + "/out --irradiance-cache maybe");
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

} // namespace
} // namespace penumbra
