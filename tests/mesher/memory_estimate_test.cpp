// The mesher's element estimate, which the memory check counts before meshing (issue #32,
// docs/memory.md), against the elements meshing makes: within k_elements_per_estimate of
// them either way, on the Cornell box, whose shadow boundaries add the most elements.

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "core/scene_io.h"
#include "mesher/mesher.h"
#include "surfaces.h"

namespace penumbra {
namespace {

TEST(MemoryEstimate, ElementEstimateBoundsTheMesh) {
    Scene scene = load_scene(test::source_path("data/cornell/scene.json"));
    scene.mesher.element_budget = 0;
    const Context ctx = test::quiet_context();
    for (double edge : {0.1, 0.05, 0.025}) {
        scene.mesher.max_edge_length = edge;
        const mesher::MeshParams params = mesher::resolve_params(scene);
        const double estimate =
            mesher::estimated_elements(mesher::build_surfaces(scene, params, ctx), edge);
        const double elements = double(mesher::build_mesh(scene, ctx).element_count());
        EXPECT_LE(elements, mesher::k_elements_per_estimate * estimate) << edge;
        EXPECT_GE(elements * mesher::k_elements_per_estimate, estimate) << edge;
    }
}

} // namespace
} // namespace penumbra
