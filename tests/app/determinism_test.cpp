// Results must not depend on the thread count (core/parallel.h, core/rng.h): the Cornell box
// baked with 1, 2 and 4 threads gives bitwise identical arrays.

#include <cstring>

#include <gtest/gtest.h>

#include "app/pipeline.h"
#include "common/test_util.h"
#include "core/scene_io.h"

namespace penumbra {
namespace {

template <typename T> bool bitwise_equal(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

TEST(Determinism, CornellBoxIdenticalFor1And2And4Threads) {
    Scene scene = load_scene(test::source_path("data/cornell/scene.json"));
    scene.mesher.max_edge_length = 0.1;
    scene.solver.residual = 1e-2;
    scene.solver.method =
        SolverMethod::shooting; // the hierarchical solver has its own (hierarchical_test)
    scene.camera->width = 48;
    scene.camera->height = 48;
    scene.camera->samples_per_pixel = 4;
    scene.sensors.push_back({"floor", {0.28, 0.0, 0.28}, {0, 1, 0}});
    scene.sensors.push_back({"back", {0.28, 0.27, 0.5592}, {0, 0, -1}});
    std::vector<app::BakeResult> results;
    for (int threads : {1, 2, 4}) {
        Context ctx = test::quiet_context(threads);
        ctx.seed = 7;
        results.push_back(app::bake(scene, app::BakeOptions{}, ctx));
    }
    const app::BakeResult& ref = results[0];
    ASSERT_GT(ref.mesh.element_count(), 100u);
    for (std::size_t i = 1; i < results.size(); ++i) {
        const app::BakeResult& r = results[i];
        EXPECT_TRUE(bitwise_equal(r.solution.radiosity, ref.solution.radiosity));
        EXPECT_TRUE(bitwise_equal(r.solution.irradiance_direct, ref.solution.irradiance_direct));
        EXPECT_TRUE(
            bitwise_equal(r.solution.irradiance_indirect, ref.solution.irradiance_indirect));
        EXPECT_TRUE(bitwise_equal(r.solution.vertex_radiosity, ref.solution.vertex_radiosity));
        EXPECT_TRUE(bitwise_equal(r.render->pixels, ref.render->pixels));
        ASSERT_EQ(r.sensors.size(), ref.sensors.size());
        for (std::size_t s = 0; s < r.sensors.size(); ++s)
            EXPECT_EQ(r.sensors[s].illuminance_total_lx, ref.sensors[s].illuminance_total_lx);
        EXPECT_EQ(r.stats.shots, ref.stats.shots);
        EXPECT_EQ(r.rays, ref.rays);
    }
    // Sanity: the solve did something (lit floor, dark outside of the box).
    EXPECT_GT(ref.sensors[0].illuminance_total_lx, 1.0);
}

} // namespace
} // namespace penumbra
