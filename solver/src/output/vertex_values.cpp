#include "output/vertex_values.h"

#include <algorithm>

#include "core/parallel.h"

namespace penumbra::solver {

GatherSources direct_sources(const Scene& scene, const std::vector<Rgb>& element_emission) {
    GatherSources sources;
    sources.emission = element_emission;
    for (std::size_t e = 0; e < element_emission.size(); ++e)
        if (!element_emission[e].is_black())
            sources.emitters.push_back(std::uint32_t(e));
    sources.lights = scene.point_lights;
    sources.sun = scene.sun;
    return sources;
}

namespace {

std::vector<Rgb> area_weighted_vertex_mean(const RadiosityMesh& mesh,
                                           const std::vector<Rgb>& element_values) {
    std::vector<RgbD> sum(mesh.vertex_count());
    std::vector<double> weight(mesh.vertex_count(), 0.0);
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
        for (std::uint32_t v : mesh.triangles[e]) {
            sum[v] += RgbD(element_values[e]) * mesh.element_area[e];
            weight[v] += mesh.element_area[e];
        }
    }
    std::vector<Rgb> out(mesh.vertex_count());
    for (std::size_t v = 0; v < out.size(); ++v)
        if (weight[v] > 0)
            out[v] = Rgb(float(sum[v].r / weight[v]), float(sum[v].g / weight[v]),
                         float(sum[v].b / weight[v]));
    return out;
}

} // namespace

Solution snapshot_solution(const RadiosityMesh& mesh, const ElementResult& result) {
    Solution sol;
    sol.radiosity = result.radiosity;
    sol.irradiance_direct = result.h_direct;
    sol.irradiance_indirect = result.h_indirect;
    sol.vertex_radiosity = area_weighted_vertex_mean(mesh, result.radiosity);
    sol.vertex_irradiance_direct = area_weighted_vertex_mean(mesh, result.h_direct);
    sol.vertex_irradiance_indirect = area_weighted_vertex_mean(mesh, result.h_indirect);
    return sol;
}

Solution make_solution(const Scene& scene, const RadiosityMesh& mesh, const ElementGeometry& geo,
                       ElementResult result, const VisibilityQuery& visibility,
                       const RowSettings& settings, const Context& ctx,
                       const DirectEmitters* emitters) {
    Solution sol;
    sol.vertex_irradiance_indirect = area_weighted_vertex_mean(mesh, result.h_indirect);
    sol.radiosity = std::move(result.radiosity);
    sol.irradiance_direct = std::move(result.h_direct);
    sol.irradiance_indirect = std::move(result.h_indirect);
    std::vector<Rgb> emission(mesh.element_count());
    for (std::size_t e = 0; e < emission.size(); ++e)
        emission[e] = mesh.patch_of(std::uint32_t(e)).emission;
    const GatherSources own = emitters ? GatherSources{} : direct_sources(scene, emission);
    const GatherSources& sources = emitters ? emitters->sources : own;
    const ElementGeometry& source_geo = emitters ? emitters->geo : geo;
    const std::size_t nv = mesh.vertex_count();
    const bool split = emitters && emitters->near && emitters->far;
    std::vector<Rgb> vertex_far;
    std::vector<std::uint32_t> first, adjacent; // elements around each vertex (CSR)
    if (split) {
        vertex_far = area_weighted_vertex_mean(mesh, *emitters->far);
        first.assign(nv + 1, 0);
        for (const auto& t : mesh.triangles)
            for (std::uint32_t v : t)
                ++first[v + 1];
        for (std::size_t v = 0; v < nv; ++v)
            first[v + 1] += first[v];
        adjacent.resize(first.back());
        std::vector<std::uint32_t> at(first.begin(), first.end() - 1);
        for (std::size_t e = 0; e < mesh.element_count(); ++e)
            for (std::uint32_t v : mesh.triangles[e])
                adjacent[at[v]++] = std::uint32_t(e);
    }
    sol.vertex_irradiance_direct.resize(nv);
    sol.vertex_radiosity.resize(nv);
    ProgressStage progress(ctx, "vertex values");
    const std::size_t block = 4096;
    for (std::size_t begin = 0; begin < nv; begin += block) {
        const std::size_t end = std::min(nv, begin + block);
        parallel_for_index(end - begin, 16, [&](std::size_t k) {
            const std::size_t v = begin + k;
            const Patch& patch = mesh.patches[mesh.vertex_patch[v]];
            GatherPoint p{mesh.vertex(std::uint32_t(v)), patch.normal, v,
                          RngPurpose::vertex_visibility};
            if (split) {
                std::vector<std::uint32_t> near;
                for (std::uint32_t k = first[v]; k < first[v + 1]; ++k) {
                    const auto mine = emitters->near->of(adjacent[k]);
                    near.insert(near.end(), mine.begin(), mine.end());
                }
                std::sort(near.begin(), near.end());
                near.erase(std::unique(near.begin(), near.end()), near.end());
                sol.vertex_irradiance_direct[v] =
                    gather_direct(source_geo, sources, visibility, p, settings.visibility_rays,
                                  ctx.seed, &near) +
                    vertex_far[v];
            } else {
                sol.vertex_irradiance_direct[v] = gather_direct(source_geo, sources, visibility, p,
                                                                settings.visibility_rays, ctx.seed);
            }
            Rgb h = sol.vertex_irradiance_direct[v] + sol.vertex_irradiance_indirect[v];
            sol.vertex_radiosity[v] = patch.emission + patch.reflectance * h;
        });
        progress.update(double(end) / double(nv));
    }
    return sol;
}

} // namespace penumbra::solver
