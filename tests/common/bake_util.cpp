#include "common/bake_util.h"

#include <cmath>

#include "common/test_util.h"
#include "core/scene_io.h"

namespace penumbra::test {

app::BakeResult bake(const Scene& scene, int threads, const solver::HierarchicalState* reuse) {
    app::BakeOptions options;
    options.render = false;
    options.reuse = reuse;
    return app::bake(scene, options, quiet_context(threads));
}

Scene cornell_box(double max_edge) {
    Scene scene = load_scene(source_path("data/cornell/scene.json"));
    scene.sensors.clear();
    scene.mesher.max_edge_length = max_edge;
    return scene;
}

double relative_l1(const std::vector<Rgb>& b, const std::vector<Rgb>& ref,
                   const std::vector<double>& area) {
    double diff = 0, norm = 0;
    for (std::size_t e = 0; e < ref.size(); ++e) {
        diff += area[e] * std::abs(double((b[e] - ref[e]).sum()));
        norm += area[e] * double(ref[e].sum());
    }
    return diff / norm;
}

} // namespace penumbra::test
