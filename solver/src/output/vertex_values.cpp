#include "output/vertex_values.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

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
    sources.sky = scene.sky;
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

/// Elements around each vertex (CSR: vertex v's are element[first[v], first[v + 1])).
struct VertexElements {
    std::vector<std::uint32_t> first, element;
    std::span<const std::uint32_t> of(std::size_t v) const {
        return std::span<const std::uint32_t>(element).subspan(first[v], first[v + 1] - first[v]);
    }
};

VertexElements vertex_elements(const RadiosityMesh& mesh) {
    VertexElements out;
    out.first.assign(mesh.vertex_count() + 1, 0);
    for (const auto& t : mesh.triangles)
        for (std::uint32_t v : t)
            ++out.first[v + 1];
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
        out.first[v + 1] += out.first[v];
    out.element.resize(out.first.back());
    std::vector<std::uint32_t> at(out.first.begin(), out.first.end() - 1);
    for (std::size_t e = 0; e < mesh.element_count(); ++e)
        for (std::uint32_t v : mesh.triangles[e])
            out.element[at[v]++] = std::uint32_t(e);
    return out;
}

// Whether an edge from v belongs to only one of v's elements: v is on its surface's boundary.
bool on_boundary(const RadiosityMesh& mesh, std::uint32_t v,
                 std::span<const std::uint32_t> elements) {
    thread_local std::vector<std::uint32_t> ends;
    ends.clear();
    for (std::uint32_t e : elements)
        for (std::uint32_t w : mesh.triangles[e])
            if (w != v)
                ends.push_back(w);
    std::sort(ends.begin(), ends.end());
    for (std::size_t i = 0; i < ends.size();) {
        std::size_t j = i;
        while (j < ends.size() && ends[j] == ends[i])
            ++j;
        if (j - i == 1)
            return true;
        i = j;
    }
    return false;
}

// Where vertex v gathers direct light from. A vertex on its surface's boundary may lie on
// another surface that meets it there (a contact line, a room's corner): the rays from it
// would start on that surface, or be lifted behind it, and it would be seen edge-on (form
// factor 0 instead of the limit the surface's own points tend to). The vertex's value is that
// limit, so it gathers from a point \p inset (at most half way to its elements' centroids)
// into its elements.
Vec3 gather_position(const RadiosityMesh& mesh, std::uint32_t v,
                     std::span<const std::uint32_t> elements, const Vec3& normal, double inset) {
    const Vec3 p = mesh.vertex(v);
    if (!on_boundary(mesh, v, elements))
        return p;
    Vec3 inward{0, 0, 0};
    double nearest = std::numeric_limits<double>::infinity();
    for (std::uint32_t e : elements) {
        const Vec3 to_centroid = mesh.centroid(e) - p;
        const double d = length(to_centroid);
        if (d <= 0)
            continue;
        inward += to_centroid / d;
        nearest = std::min(nearest, d);
    }
    inward -= normal * dot(inward, normal);
    const double len = length(inward);
    if (len <= 0)
        return p;
    return p + inward * (std::min(inset, 0.5 * nearest) / len);
}

// The inset of boundary vertices' gathers, in ray offsets: the inset point's rays, lifted
// by at most two offsets, stay clear of a surface meeting the vertex's at any but a grazing
// angle.
constexpr double k_inset_offsets = 10.0;

// Each vertex's counterpart on the other side of its surface: the twin element's corner at
// the same place (twins share their corners' positions). -1 where the side has no twin.
std::vector<std::int32_t> twin_vertices(const RadiosityMesh& mesh) {
    std::vector<std::int32_t> out(mesh.vertex_count(), -1);
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
        const std::int32_t t = mesh.element_twin[e];
        if (t < 0)
            continue;
        for (std::uint32_t v : mesh.triangles[e]) {
            double nearest = std::numeric_limits<double>::infinity();
            for (std::uint32_t w : mesh.triangles[std::size_t(t)]) {
                const double d = length(mesh.vertex(w) - mesh.vertex(v));
                if (d < nearest) {
                    nearest = d;
                    out[v] = std::int32_t(w);
                }
            }
        }
    }
    return out;
}

bool any_diffuse_transmittance(const RadiosityMesh& mesh) {
    return std::any_of(mesh.patches.begin(), mesh.patches.end(),
                       [](const Patch& p) { return !p.diffuse_transmittance.is_black(); });
}

// A side of a diffusely transmitting surface sends on τ times the irradiance of the other
// side's vertex, once every vertex's own irradiance is known.
void add_transmitted(const RadiosityMesh& mesh, Solution& sol) {
    if (!any_diffuse_transmittance(mesh))
        return;
    const std::vector<std::int32_t> twin = twin_vertices(mesh);
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        const Patch& patch = mesh.patches[mesh.vertex_patch[v]];
        if (twin[v] < 0 || patch.diffuse_transmittance.is_black())
            continue;
        const auto t = std::size_t(twin[v]);
        sol.vertex_radiosity[v] +=
            patch.diffuse_transmittance *
            (sol.vertex_irradiance_direct[t] + sol.vertex_irradiance_indirect[t]);
    }
}

} // namespace

std::vector<Vec3> vertex_gather_positions(const RadiosityMesh& mesh, double ray_offset) {
    const VertexElements around = vertex_elements(mesh);
    std::vector<Vec3> out(mesh.vertex_count());
    for (std::size_t v = 0; v < out.size(); ++v)
        out[v] = gather_position(mesh, std::uint32_t(v), around.of(v),
                                 mesh.patches[mesh.vertex_patch[v]].normal,
                                 k_inset_offsets * ray_offset);
    return out;
}

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
    const std::vector<Rgb> vertex_far =
        split ? area_weighted_vertex_mean(mesh, *emitters->far) : std::vector<Rgb>{};
    const VertexElements around = vertex_elements(mesh);
    const double inset = k_inset_offsets * geo.offset;
    sol.vertex_irradiance_direct.resize(nv);
    sol.vertex_radiosity.resize(nv);
    ProgressStage progress(ctx, "vertex values");
    const std::size_t block = 4096;
    for (std::size_t begin = 0; begin < nv; begin += block) {
        const std::size_t end = std::min(nv, begin + block);
        parallel_for_index(end - begin, 16, [&](std::size_t k) {
            const std::size_t v = begin + k;
            const Patch& patch = mesh.patches[mesh.vertex_patch[v]];
            GatherPoint p{
                gather_position(mesh, std::uint32_t(v), around.of(v), patch.normal, inset),
                patch.normal, v, RngPurpose::vertex_visibility};
            if (split) {
                std::vector<std::uint32_t> near;
                for (std::uint32_t e : around.of(v)) {
                    const auto mine = emitters->near->of(e);
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
            if (emitters && emitters->sky)
                sol.vertex_irradiance_direct[v] += (*emitters->sky)[v];
            Rgb h = sol.vertex_irradiance_direct[v] + sol.vertex_irradiance_indirect[v];
            sol.vertex_radiosity[v] = patch.emission + patch.reflectance * h;
        });
        progress.update(double(end) / double(nv));
    }
    add_transmitted(mesh, sol);
    return sol;
}

} // namespace penumbra::solver
