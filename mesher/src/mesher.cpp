// Mesher v2 (issue #5): scene polygons → planar surfaces (near-contacts closed) → contact
// lines, covers and hidden regions → discontinuity segments of every source → one CGAL
// constrained Delaunay triangulation per surface, refined to the size and angle bound →
// patches (one per side) with vertices split along contact lines. If the element count
// exceeds the budget, the size bound grows and the refinement runs again.

#include "mesher/mesher.h"

#include <sys/resource.h>

#include <chrono>
#include <cmath>

#include "contacts.h"
#include "core/error.h"
#include "core/memory.h"
#include "core/parallel.h"
#include "discontinuity.h"
#include "mesh_assembly.h"
#include "surface_bvh.h"
#include "surface_regions.h"
#include "surfaces.h"

namespace penumbra::mesher {

MeshParams resolve_params(const Scene& scene) {
    const MesherSettings& m = scene.mesher;
    MeshParams p;
    p.diagonal = scene.bounds().diagonal();
    p.max_edge = m.max_edge_length > 0 ? m.max_edge_length : p.diagonal / 20.0;
    if (!(p.max_edge > 0) || !std::isfinite(p.max_edge))
        throw InputError(scene.file, "mesher.max_edge_length", "scene has no extent to mesh");
    p.contact_tol = m.contact_tolerance.value_or(std::min(0.002, 1e-3 * p.diagonal));
    p.snap = 2e-7 * p.diagonal;
    p.nudge = 1e-6 * p.diagonal;
    p.min_edge = std::max(p.contact_tol, 0.05 * p.max_edge);
    p.merge = std::max({p.snap, 0.5 * p.contact_tol, 0.01 * p.max_edge});
    p.split_contacts = m.split_contacts;
    p.max_order = m.discontinuity.enabled ? m.discontinuity.max_order : -1;
    p.budget = m.element_budget;
    return p;
}

namespace {

// max_edge_length is the element size: no edge is longer than the diagonal of a square of
// that side, as in mesher v1's structured grids, so element counts stay comparable.
RefineSettings refine_settings(const Surface& s, const PreparedSurface& prepared,
                               const MeshParams& p, double max_edge) {
    RefineSettings r;
    r.max_edge = std::sqrt(2.0) * max_edge;
    r.near_factor = 0.5;
    r.min_edge = std::min(p.min_edge, 0.5 * max_edge);
    r.snap = p.snap;
    r.nudge = p.nudge;
    r.two_sided = s.two_sided;
    const double expected = s.area / (0.3 * r.max_edge * r.max_edge);
    r.max_steps = std::size_t(10 * expected) + 200 * prepared.extra.size() + 10000;
    return r;
}

// Refines every surface; with \p last, each surface's triangulator is freed once it is
// refined (the region triangulations of half a million surfaces take gigabytes). Surfaces
// without one (no contact splitting) get theirs built here and dropped at once.
std::vector<SurfaceTriangulation> triangulate_all(const std::vector<Surface>& surfaces,
                                                  std::vector<PreparedSurface>& prepared,
                                                  const MeshParams& params, double max_edge,
                                                  bool last, const Context& ctx) {
    std::vector<SurfaceTriangulation> out(surfaces.size());
    run_in_arena(ctx, [&] {
        parallel_for_index(surfaces.size(), 1, [&](std::size_t i) {
            const RefineSettings rs = refine_settings(surfaces[i], prepared[i], params, max_edge);
            try {
                std::unique_ptr<SurfaceTriangulator> own;
                const SurfaceTriangulator* triangulator = prepared[i].triangulator.get();
                if (!triangulator) {
                    own = std::make_unique<SurfaceTriangulator>(surfaces[i].outline2d,
                                                                prepared[i].cuts, params.merge);
                    triangulator = own.get();
                }
                out[i] = triangulator->refine(prepared[i].extra, rs);
            } catch (const ExternalError& e) {
                throw InputError(
                    "", "",
                    fmt::format("cannot triangulate surface {}: {}", surfaces[i].name, e.what()));
            }
            if (last)
                prepared[i].triangulator.reset();
        });
    });
    for (std::size_t i = 0; i < surfaces.size(); ++i)
        if (out[i].face_count == 0)
            ctx.warn("mesh: surface {} is thinner than {:.3g} m everywhere; it gets no elements",
                     surfaces[i].name, params.snap);
    for (std::size_t i = 0; i < surfaces.size(); ++i)
        if (out[i].capped)
            ctx.warn("mesh: surface {}: quality refinement stopped after {} insertions "
                     "(constraints nearly touch); some elements keep small angles",
                     surfaces[i].name,
                     refine_settings(surfaces[i], prepared[i], params, max_edge).max_steps);
    return out;
}

std::size_t element_count(const std::vector<SurfaceTriangulation>& tris) {
    std::size_t n = 0;
    for (const SurfaceTriangulation& t : tris)
        n += t.sides[0].triangles.size() + t.sides[1].triangles.size();
    return n;
}

/// A size bound whose estimated element count exceeds the budget this many times is refused
/// (a typo, not a wish); above twice the budget it is grown before meshing.
constexpr double k_budget_refused = 100.0;
constexpr double k_budget_grown = 2.0;

// The size bound to mesh with, decided before meshing: meshing first took minutes and
// gigabytes (--max-edge 1e-6) before the budget was looked at. Near the budget,
// refine_within_budget grows it further if the mesh comes out over.
double size_within_budget(const std::vector<Surface>& surfaces, const MeshParams& params,
                          const std::string& scene_file, const Context& ctx) {
    const double estimate = estimated_elements(surfaces, params.max_edge);
    if (params.budget <= 0 || estimate <= k_budget_grown * double(params.budget))
        return params.max_edge;
    const double fits = params.max_edge * std::sqrt(estimate / double(params.budget));
    if (estimate > k_budget_refused * double(params.budget))
        throw ConfigError(fmt::format(
            "{}: elements of {:.4g} m would make about {:.3g} elements, over {:g} times the "
            "budget of {} (mesher.element_budget): use --max-edge {:.2g} or more, or a larger "
            "budget",
            scene_file, params.max_edge, estimate, k_budget_refused, params.budget, fits));
    ctx.warn("mesh: elements of {:.4g} m would make about {:.3g} elements, over the budget of {} "
             "(mesher.element_budget): meshing with elements of {:.4g} m",
             params.max_edge, estimate, params.budget, fits);
    return fits;
}

// A point light on a surface (within the contact tolerance of it) loses the light it sends
// into that surface's plane, and half of it or all to the surface itself, without a word
// (a relative imbalance of 0.93 was measured): it is an input error naming the light.
// The mesh's memory, estimated before meshing (docs/memory.md): with mesher.element_budget
// 0 nothing else bounds the elements of a tiny --max-edge.
void check_mesh_memory(const std::vector<Surface>& surfaces, double max_edge,
                       const std::string& scene_file, const Context& ctx) {
    const double elements = k_elements_per_estimate * estimated_elements(surfaces, max_edge);
    const double bytes =
        elements * double(k_mesh_bytes_per_element + k_triangulation_bytes_per_element);
    if (ctx.max_memory_bytes == 0 || bytes <= double(ctx.max_memory_bytes))
        return;
    const double fits = max_edge * std::sqrt(bytes / double(ctx.max_memory_bytes));
    check_memory(ctx,
                 fmt::format("{}: meshing with elements of {:.4g} m (up to {:.3g} elements)",
                             scene_file, max_edge, elements),
                 bytes,
                 fmt::format("use --max-edge {:.2g} or more (mesher.max_edge_length)", fits));
}

void check_point_lights_off_surfaces(const Scene& scene, const std::vector<Surface>& surfaces,
                                     const MeshParams& params) {
    for (std::size_t i = 0; i < scene.point_lights.size(); ++i) {
        const PointLight& light = scene.point_lights[i];
        for (const Surface& s : surfaces) {
            if (std::abs(s.distance(light.position)) > params.contact_tol ||
                !s.contains(light.position))
                continue;
            throw InputError(
                scene.file, fmt::format("point_lights[{}].position", i),
                fmt::format("point light '{}' lies on surface {} (within mesher.contact_tolerance, "
                            "{:.3g} m): move it off the surface",
                            light.name, s.name, params.contact_tol));
        }
    }
}

// Refines every surface; grows the size bound while the element budget is exceeded. The
// triangulators are freed by the attempt that is certainly the last.
std::vector<SurfaceTriangulation> refine_within_budget(const std::vector<Surface>& surfaces,
                                                       std::vector<PreparedSurface>& prepared,
                                                       const MeshParams& params, double& max_edge,
                                                       const Context& ctx) {
    std::vector<SurfaceTriangulation> tris;
    for (int attempt = 0;; ++attempt) {
        const bool last = params.budget <= 0 || attempt == 3;
        tris = triangulate_all(surfaces, prepared, params, max_edge, last, ctx);
        const std::size_t n = element_count(tris);
        if (params.budget <= 0 || n <= std::size_t(params.budget))
            return tris;
        if (attempt == 3) {
            ctx.warn("mesh: {} elements exceed the budget of {} (mesher.element_budget) even "
                     "with elements of {:.4g} m; keeping them",
                     n, params.budget, max_edge);
            return tris;
        }
        const double grow = std::sqrt(double(n) / double(params.budget)) * 1.05;
        ctx.warn("mesh: {} elements exceed the budget of {} (mesher.element_budget); "
                 "remeshing with elements of {:.4g} m instead of {:.4g} m",
                 n, params.budget, max_edge * grow, max_edge);
        max_edge *= grow;
    }
}

void record_discontinuities(RadiosityMesh& mesh, const std::vector<Surface>& surfaces,
                            const std::vector<std::vector<ReceiverSegment>>& discontinuities) {
    for (std::size_t s = 0; s < surfaces.size(); ++s)
        for (const ReceiverSegment& d : discontinuities[s])
            mesh.discontinuities.push_back({surfaces[s].to_3d(d.segment.a),
                                            surfaces[s].to_3d(d.segment.b), std::uint32_t(s),
                                            d.source, d.order});
}

/// Logs (debug) the seconds of each meshing stage and the peak RSS so far, for profiling at
/// scale.
class StageTimer {
public:
    explicit StageTimer(const Context& ctx) : ctx_(ctx), last_(std::chrono::steady_clock::now()) {}
    void lap(const char* stage) {
        const auto now = std::chrono::steady_clock::now();
        rusage usage{};
        ::getrusage(RUSAGE_SELF, &usage);
        ctx_.debug("mesh: {} {:.2f} s (peak RSS {} MiB)", stage,
                   std::chrono::duration<double>(now - last_).count(), usage.ru_maxrss / 1024);
        last_ = now;
    }

private:
    const Context& ctx_;
    std::chrono::steady_clock::time_point last_;
};

void log_summary(const Context& ctx, const Scene& scene, const RadiosityMesh& mesh,
                 const std::vector<SurfaceContacts>& contacts, double max_edge, double seconds) {
    std::size_t cuts = 0;
    for (const SurfaceContacts& c : contacts)
        cuts += c.cuts.size() + c.covers.size();
    double hidden = 0;
    for (const SurfaceInfo& s : mesh.surfaces)
        hidden += s.hidden_front_m2 + s.hidden_back_m2;
    std::size_t by_order[3] = {0, 0, 0};
    for (const DiscontinuitySegment& d : mesh.discontinuities)
        ++by_order[std::clamp(d.order, 0, 2)];
    ctx.info("mesh: {} polygons -> {} surfaces, {} contacts, {:.4g} m2 hidden, discontinuities "
             "D0/D1/D2 {}/{}/{}, {} patches, {} elements, {} vertices (max edge {:.4g} m, "
             "{:.2f} s)",
             scene.polygons.size(), mesh.surfaces.size(), cuts, hidden, by_order[0], by_order[1],
             by_order[2], mesh.patches.size(), mesh.element_count(), mesh.vertex_count(), max_edge,
             seconds);
}

} // namespace

RadiosityMesh build_mesh(const Scene& scene, const Context& ctx) {
    const auto start = std::chrono::steady_clock::now();
    StageTimer timer(ctx);
    const MeshParams params = resolve_params(scene);
    const std::vector<Surface> surfaces = build_surfaces(scene, params, ctx);
    check_point_lights_off_surfaces(scene, surfaces, params);
    double max_edge = size_within_budget(surfaces, params, scene.file, ctx);
    check_mesh_memory(surfaces, max_edge, scene.file, ctx);
    timer.lap("surfaces");
    const SurfaceBvh bvh(surfaces);
    timer.lap("surface bvh");
    const std::vector<SurfaceContacts> contacts = find_contacts(surfaces, bvh, params, ctx);
    timer.lap("contacts");
    const std::vector<std::vector<ReceiverSegment>> discontinuities =
        find_discontinuities(scene, surfaces, bvh, params, ctx);
    timer.lap("discontinuities");
    std::vector<PreparedSurface> prepared =
        prepare_surfaces(scene, surfaces, bvh, contacts, discontinuities, params, ctx);
    timer.lap("regions");
    const std::vector<SurfaceTriangulation> tris =
        refine_within_budget(surfaces, prepared, params, max_edge, ctx);
    prepared = std::vector<PreparedSurface>(); // the triangulators are done with
    timer.lap("refinement");

    RadiosityMesh mesh;
    mesh.scene_diagonal = params.diagonal;
    append_surfaces(mesh, scene, surfaces, tris, ctx);
    record_discontinuities(mesh, surfaces, discontinuities);
    timer.lap("assembly");
    check_patches(mesh, ctx);
    timer.lap("manifold check");
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    log_summary(ctx, scene, mesh, contacts, max_edge, seconds);
    return mesh;
}

} // namespace penumbra::mesher
