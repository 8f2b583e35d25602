#include "common/bake_util.h"

#include <cmath>
#include <map>

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

namespace {

// Per patch: Σ A B (summed over the channels) and Σ A.
std::map<std::uint32_t, std::pair<double, double>> patch_sums(const app::BakeResult& r) {
    std::map<std::uint32_t, std::pair<double, double>> sums;
    for (std::size_t e = 0; e < r.mesh.element_count(); ++e) {
        auto& s = sums[r.mesh.element_patch[e]];
        s.first += r.mesh.element_area[e] * double(r.solution.radiosity[e].sum());
        s.second += r.mesh.element_area[e];
    }
    return sums;
}

} // namespace

double relative_patch_l1(const app::BakeResult& r, const app::BakeResult& ref,
                         std::optional<std::uint32_t> skip_material) {
    const auto a = patch_sums(r), b = patch_sums(ref);
    double diff = 0, norm = 0;
    for (const auto& [patch, s] : b) {
        if (skip_material && ref.mesh.patches[patch].material == *skip_material)
            continue;
        const auto it = a.find(patch);
        if (it == a.end())
            return 1.0;
        diff += std::abs(it->second.first / it->second.second * s.second - s.first);
        norm += s.first;
    }
    return diff / norm;
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
