// Direct light at arbitrary surface points (lightmap texel samples): the sensors' gather
// (output/point_gather.h) at each point, with a random stream named by the point itself.

#include "solver/solver.h"

#include <bit>

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

} // namespace

std::vector<Rgb> direct_irradiance_at(const Scene& scene, const RadiosityMesh& mesh,
                                      const VisibilityQuery& visibility,
                                      std::span<const Vec3> points, std::span<const Vec3> normals,
                                      const Context& ctx) {
    return direct_irradiance_at(scene, mesh, visibility, points, normals, {}, {}, ctx);
}

std::vector<Rgb> direct_irradiance_at(const Scene& scene, const RadiosityMesh& mesh,
                                      const VisibilityQuery& visibility,
                                      std::span<const Vec3> points, std::span<const Vec3> normals,
                                      std::span<const std::uint32_t> list_of_point,
                                      std::span<const std::vector<std::uint32_t>> emitter_lists,
                                      const Context& ctx) {
    if (points.size() != normals.size())
        throw InternalError("direct_irradiance_at: points and normals differ in number");
    if (!list_of_point.empty() && list_of_point.size() != points.size())
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
        const GatherSources sources = direct_sources(scene, emission);
        const int rays = scene.solver.visibility_rays;
        parallel_for_index(points.size(), 16, [&](std::size_t i) {
            const GatherPoint p{points[i], normals[i], point_stream_id(points[i], normals[i]),
                                RngPurpose::texel_visibility};
            const std::vector<std::uint32_t>* emitters =
                list_of_point.empty() ? nullptr : &emitter_lists[list_of_point[i]];
            out[i] = gather_direct(geo, sources, visibility, p, rays, ctx.seed, emitters);
        });
        return out;
    });
}

} // namespace penumbra::solver
