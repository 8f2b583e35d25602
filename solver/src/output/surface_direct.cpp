// Direct light at arbitrary surface points (lightmap texel samples): the sensors' gather
// (output/point_gather.h) at each point, with a random stream named by the point itself.

#include "solver/solver.h"

#include <bit>
#include <utility>

#include "core/error.h"
#include "core/parallel.h"
#include "output/point_gather.h"
#include "output/vertex_values.h"

namespace penumbra::solver {

namespace {

std::uint64_t bits_of(double x) {
    return std::bit_cast<std::uint64_t>(x);
}

// Names a point's random stream by its coordinates and normal: the same point draws the same
// rays whichever call, batch or thread gathers it.
std::uint64_t point_stream_id(const Vec3& p, const Vec3& n) {
    return hash_words(
        {bits_of(p.x), bits_of(p.y), bits_of(p.z), bits_of(n.x), bits_of(n.y), bits_of(n.z)});
}

// Removes from \p sources those \p options leaves out: emitting elements (by their polygon),
// point lights, the sun and the sky.
void leave_out(GatherSources& sources, const RadiosityMesh& mesh,
               const DirectLightOptions& options) {
    if (!options.include)
        return;
    std::erase_if(sources.emitters, [&](std::uint32_t e) {
        return !options.include(AreaSource{mesh.patch_of(e).polygon});
    });
    std::vector<PointLight> lights;
    for (std::size_t i = 0; i < sources.lights.size(); ++i)
        if (options.include(PointSource{std::uint32_t(i)}))
            lights.push_back(sources.lights[i]);
    sources.lights = std::move(lights);
    if (sources.sun && !options.include(SunSource{}))
        sources.sun.reset();
    if (sources.sky && !options.include(SkySource{}))
        sources.sky.reset();
}

} // namespace

std::vector<Rgb> direct_irradiance_at(const Scene& scene, const RadiosityMesh& mesh,
                                      const VisibilityQuery& visibility,
                                      std::span<const Vec3> points, std::span<const Vec3> normals,
                                      const Context& ctx, const DirectLightOptions& options) {
    if (points.size() != normals.size())
        throw InternalError("direct_irradiance_at: points and normals differ in number");
    if (!options.list_of_point.empty() && options.list_of_point.size() != points.size())
        throw InternalError(
            "direct_irradiance_at: points and their emitter lists differ in number");
    std::vector<Rgb> out(points.size());
    if (out.empty())
        return out;
    return run_in_arena(ctx, [&] {
        const ElementGeometry geo(mesh);
        std::vector<Rgb> emission(mesh.element_count());
        for (std::size_t e = 0; e < mesh.element_count(); ++e)
            emission[e] = mesh.patch_of(std::uint32_t(e)).emission;
        GatherSources sources = direct_sources(scene, emission);
        leave_out(sources, mesh, options);
        const int rays = scene.solver.visibility_rays;
        parallel_for_index(points.size(), 16, [&](std::size_t i) {
            const GatherPoint p{points[i], normals[i], point_stream_id(points[i], normals[i]),
                                RngPurpose::texel_visibility};
            const std::vector<std::uint32_t>* emitters =
                options.list_of_point.empty() ? nullptr
                                              : &options.emitter_lists[options.list_of_point[i]];
            out[i] = gather_direct(geo, sources, visibility, p, rays, ctx.seed, emitters);
        });
        return out;
    });
}

} // namespace penumbra::solver
