// The final gather's sampling (issue #28, docs/rendering.md): splitting at the camera path's
// first non-delta surface (render.light_samples, render.gather_rays) keeps the white furnace
// exact and lowers its noise; edge refinement brings a tilted lamp's rim pixels to their exact
// covered share; both are bitwise the same for 1, 2 and 4 threads.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "app/pipeline.h"
#include "common/bake_util.h"
#include "common/pixel_coverage.h"
#include "common/reference_tiles.h"
#include "common/test_util.h"
#include "core/image.h"
#include "raytrace/raytrace.h"

namespace penumbra {
namespace {

using raytrace::GatherMode;
using raytrace::RenderOptions;

Image render(const app::BakeResult& baked, const Scene& scene, GatherMode mode, int spp,
             const Context& ctx) {
    const raytrace::EmbreeScene rt(baked.mesh);
    RenderOptions options;
    options.spp = spp;
    options.gather = mode;
    return raytrace::render_final_gather(rt, scene, baked.solution, *scene.camera, options, ctx);
}

// ---- Splitting in the white furnace: L = E / (π (1 − ρ)) at every pixel ----

Scene furnace_with_camera(float rho, float exitance) {
    Scene scene = test::furnace_room(rho, exitance);
    scene.render.max_bounces = 64; // ρ^65 of the answer left out: below 1e-10
    // A corner: three walls, two edges.
    scene.camera = test::square_camera({0.2, 0.2, 0.25}, {0.9, 0.6, 0.3}, {0, 0, 1}, 70, 24);
    return scene;
}

// The mean within 4 standard errors of the pixels' scatter (all pixels share the expectation);
// four light samples and four gather rays per camera sample must leave the mean there and
// take a quarter or more off the per-pixel spread of one of each at the same spp.
TEST(RenderSplitting, FurnaceStaysExactAndGetsQuieter) {
    const float rho = 0.6f, exitance = 1.5f;
    Scene scene = furnace_with_camera(rho, exitance);
    const app::BakeResult baked = test::bake(scene);
    const double expected = exitance / (k_pi * (1 - rho));
    for (GatherMode mode : {GatherMode::final_gather, GatherMode::none}) {
        scene.render.light_samples = scene.render.gather_rays = 1;
        const test::ImageMoments plain =
            test::green_moments(render(baked, scene, mode, 4, test::quiet_context()));
        scene.render.light_samples = scene.render.gather_rays = 4;
        const test::ImageMoments split =
            test::green_moments(render(baked, scene, mode, 4, test::quiet_context()));
        const double se = split.sd / std::sqrt(24.0 * 24.0);
        EXPECT_NEAR(split.mean, expected, 4 * se + 1e-6 * expected) << enum_name(mode);
        EXPECT_LT(split.sd, 0.75 * plain.sd) << enum_name(mode);
        std::printf("%s: mean %.5f (expected %.5f); pixel sd %.5f split, %.5f plain\n",
                    std::string(enum_name(mode)).c_str(), split.mean, expected, split.sd, plain.sd);
    }
}

TEST(RenderSplitting, BitwiseIdenticalForOneTwoAndFourThreads) {
    Scene scene = test::cornell_box(0.1);
    scene.camera->width = scene.camera->height = 24;
    scene.render.light_samples = 3;
    scene.render.gather_rays = 4;
    const app::BakeResult baked = test::bake(scene);
    for (GatherMode mode : {GatherMode::final_gather, GatherMode::none}) {
        const Image one = render(baked, scene, mode, 4, test::quiet_context(1));
        for (int threads : {2, 4}) {
            const Image other = render(baked, scene, mode, 4, test::quiet_context(threads));
            EXPECT_TRUE(std::equal(one.pixels.begin(), one.pixels.end(), other.pixels.begin()))
                << enum_name(mode) << ", " << threads << " threads";
        }
    }
}

// ---- Edge refinement: a lamp of radiance 17 turned 3° from the pixel grid, seen straight on ----

// Each pixel the rim crosses must read 17 × the exact share of its footprint the lamp covers.
// The camera's 16 jittered samples alone place the rim to about 1/16 of the pixel (an error up
// to ~1); refined pixels take 64² multi-jittered rays, whose error's standard deviation is
// about 17 × √(200 / 6) / 4096 ≈ 0.024 (the rim crosses ~200 of the 4096 fine strata), as the
// lightmap preview's test derives (tests/raytrace/embree_scene_test.cpp).
TEST(RenderEdges, RimPixelsConvergeToTheirExactCoverage) {
    const double turn = 3 * k_pi / 180, c = std::cos(turn), s = std::sin(turn);
    Scene scene;
    const float radiance = 17;
    const auto m = test::add_material(scene, "lamp", Rgb(0.0f), Rgb(radiance), false);
    Polygon lamp;
    lamp.material = m;
    lamp.name = "lamp";
    for (const auto& [x, y] : std::vector<std::pair<double, double>>{
             {-0.61, -0.43}, {0.57, -0.43}, {0.57, 0.52}, {-0.61, 0.52}})
        lamp.vertices.emplace_back(c * x - s * y, s * x + c * y, 0); // faces +z, the camera
    scene.polygons.push_back(lamp);
    const Camera camera = test::square_camera({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40, 24);
    scene.camera = camera;
    const app::BakeResult baked = test::bake(scene);

    for (GatherMode mode : {GatherMode::final_gather, GatherMode::none}) {
        scene.render.edge_tolerance = 0;
        const Image plain = render(baked, scene, mode, 16, test::quiet_context(2));
        scene.render.edge_tolerance = 0.004;
        const Image refined = render(baked, scene, mode, 16, test::quiet_context(2));
        const Image one_thread = render(baked, scene, mode, 16, test::quiet_context(1));
        EXPECT_TRUE(
            std::equal(refined.pixels.begin(), refined.pixels.end(), one_thread.pixels.begin()));
        const test::RimErrors e = test::rim_errors(camera, plain, refined, lamp.vertices, radiance);
        ASSERT_GT(e.pixels, 30);
        EXPECT_LT(e.rms_refined, 0.03) << enum_name(mode);
        EXPECT_LT(e.worst_refined, 0.08) << enum_name(mode);
        EXPECT_GT(e.worst_plain, 0.5) << enum_name(mode);
        std::printf("%s: rim pixels %d: worst error %.4f with 16 samples; refined %.4f, RMS "
                    "%.4f\n",
                    std::string(enum_name(mode)).c_str(), e.pixels, e.worst_plain, e.worst_refined,
                    e.rms_refined);
    }
}

} // namespace
} // namespace penumbra
