// Hierarchical radiosity (Hanrahan, Salzman & Aupperle 1991). Every mesh element is the root
// of a 1-to-4 hierarchy; links between nodes are refined by the BF oracle (the irradiance a
// link brings, F_qp B_p, against ε × the brightest source's exitance, partly occluded links
// counted double) down to a minimum area; a Jacobi gathering sweep over the links is followed by
// push-pull over the hierarchy (irradiance gathered at a node applies to all its descendants;
// radiosity is pulled up as the area mean). Reflectors have no radiosity before the first solve, so
// refinement and solving alternate until refinement changes nothing, or next to nothing.
//
// Deviations: form factors are receiver-side quadratures of the analytic point-to-triangle
// form factor (4 points, 64 for near pairs) times ray visibility, rather than Hanrahan's
// disc approximation; front and back sides subdivide together so that leaves stay twins; a
// link's irradiance is pushed to the leaves of its receiver, and its source's radiosity pulled
// from the leaves of its source, by each leaf's own form factors to the link's far ends rather
// than evenly (hierarchy/leaf_weights.h), so that a closed box of uniform radiosity stays uniform
// and power is not lost where radiosity varies over a coarse source.

#include "hierarchical.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <optional>

#include "core/error.h"
#include "core/parallel.h"
#include "hierarchy/hierarchy.h"
#include "hierarchy/leaf_mesh.h"
#include "hierarchy/leaf_weights.h"
#include "iteration/cluster_transport.h"
#include "iteration/transport.h"
#include "links/link_set.h"
#include "output/vertex_values.h"
#include "state/solver_state.h"

namespace penumbra::solver {

namespace {

constexpr int k_max_cycles = 12;
/// Refine → solve cycles stop once a refinement grows the links and the nodes by less than
/// this fraction. On the 2x2 office floor of tessellation 5 the fourth and fifth refinements
/// grew the links by 0.26 % and 0.01 % (the fifth, with its sweep, changed the solution by
/// 3e-4 of the emitted power): at 1e-3 both ran, at 5e-3 the fourth is the last.
constexpr double k_settled_growth = 5e-3;

/// A cycle whose refinement is not the last sweeps to this many times solver.residual: the
/// next refinement asks its radiosities for no more than the oracle's error estimates. On the
/// 2x2 office floor of tessellation 5 at 1 / 4 / 10: 27 / 22 / 20 sweeps, 975 315 / 974 714 /
/// 973 182 links, the roots' radiosities 1.008 / 1.022 / 1.030 % off a solve at ε = 1e-4
/// (area-weighted), their mean 0.99707 / 0.99671 / 0.99652 of its.
constexpr double k_intermediate_residual = 4.0;

bool settled(std::size_t before, std::size_t after) {
    return double(after) <= double(before) * (1.0 + k_settled_growth);
}

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}
/// A refinement running longer than this logs its progress at every pass this long after
/// the last.
constexpr double k_refine_report_s = 10.0;
/// solver.clustering "auto" clusters meshes with more elements than this.
constexpr std::size_t k_clustering_auto_roots = 3000;
/// Quadrature level of near element pairs that do not touch (16 points; touching ones, and
/// rows of the other methods, take 64). A hierarchical pair is computed once, from its
/// smaller end, and its other link follows by reciprocity, so the fine rule is not needed to
/// keep the two reciprocal as in rows; what it resolves is the steep part of the form factor
/// by a common edge. Against 64: the lamp room's power error 0.097 -> 0.077 %, the Cornell
/// box's against the matrix solve 0.0279 -> 0.0281 at eps 1e-3, the closed 3x3 office floor
/// with contact splitting +0.39 -> +0.43 % of its power in 9.9 s instead of 12.8, the 1M
/// proxy 107 -> 98 s. All near pairs at 16 points fail the furnace (0.59-0.68 %).
constexpr int k_apart_level = 2;

double emitted_power_max(const Hierarchy& h, const std::vector<PointLight>& lights) {
    double total = 0;
    for (std::size_t n = 0; n < h.root_count; ++n)
        total += double(h.emission[n].max_component()) * h.area[n];
    for (const PointLight& l : lights)
        total += l.power().max_component();
    return total;
}

// The radiosity scale ε is relative to: the brightest emitter's exitance, or the brightest
// irradiance a point light brings to a root.
double radiosity_scale(const Hierarchy& h, const LinkSet& links) {
    double scale = 0;
    for (std::size_t n = 0; n < h.root_count; ++n)
        scale = std::max(scale, double(h.emission[n].max_component()));
    for (const LightLink& l : links.light_links())
        scale = std::max(scale, double(l.irradiance.max_component()));
    return scale;
}

} // namespace

namespace {

// A re-solve: the saved hierarchy with the new scene's reflectances, emissions and opacity.
Hierarchy reused_hierarchy(const RadiosityMesh& mesh, const HierarchicalState& state) {
    if (state.mesh_hash != mesh_geometry_hash(mesh) ||
        state.hierarchy.root_count != mesh.element_count())
        throw ConfigError("the reused solver state is of another geometry (the mesh differs): "
                          "only reflectances and emissions may change; bake without --reuse");
    Hierarchy h = state.hierarchy;
    for (std::size_t n = 0; n < h.size(); ++n) {
        const Patch& p = mesh.patches[h.patch[n]];
        h.emission[n] = p.emission;
        h.reflectance[n] = p.reflectance;
        h.opaque[n] = p.opaque ? 1 : 0;
    }
    return h;
}

} // namespace

namespace {

// Where each leaf's direct light comes from, for the vertices' gathers (DirectEmitters): the
// emitting roots that element links reach it or its ancestors from, which its vertices gather
// exactly, and the direct irradiance that cluster links bring it (emitters seen as part of a
// cluster), which they take as the leaves' mean.
struct LeafDirect {
    EmitterLists near;    ///< per leaf element: emitting roots
    std::vector<Rgb> far; ///< per leaf element, W/m²
};

// Overwrites \p clusters' gathered and pushed values (the solve is done with them): a copy
// took 0.3 GB on the 1M floor, at the solve's peak.
LeafDirect leaf_direct(const Hierarchy& h, const LinkSet& links, Clusters& clusters,
                       const std::vector<Rgb>& b, const std::vector<std::uint32_t>& leaf_node) {
    const std::vector<std::uint32_t> root_of = h.root_of_nodes();
    std::vector<Rgb> cluster_direct(h.size()), unused(h.size());
    std::vector<Rgb> root_direct;
    if (clusters.enabled) { // the direct part alone
        ClusterValues& cv = clusters.values;
        gather_cluster_links(h, clusters.tree, links, b, cv, cluster_direct, unused, false, false);
        push_clusters(clusters.tree, h, cv);
        root_direct = std::move(cv.root_direct);
    }
    unused = {};
    LeafDirect out;
    out.far.resize(leaf_node.size());
    const auto& offsets = links.receiver_offsets();
    // Exact links from emitters (left out of the direct light above) reach a leaf through
    // its element ancestors and the face clusters above its root: per cluster, whether any
    // such link ends there, and each root's leaf cluster.
    const auto& cl = links.cluster_links();
    const auto& by_element = links.cluster_offsets_elements();
    const auto& by_cluster = links.cluster_offsets_clusters();
    auto exact_emitter = [&](const ClusterLink& l) { return l.exact && links.emits(l.source); };
    std::vector<std::uint8_t> lit_exactly;
    std::vector<std::int32_t> root_cluster;
    if (clusters.enabled) {
        const ClusterTree& tree = clusters.tree;
        lit_exactly.assign(tree.size(), 0);
        root_cluster.assign(h.root_count, -1);
        parallel_for_index(tree.size(), 256, [&](std::size_t c) {
            for (std::uint32_t k = by_cluster[c]; k < by_cluster[c + 1] && !lit_exactly[c]; ++k)
                lit_exactly[c] = exact_emitter(cl[k]);
            for (std::uint32_t k = tree.child_begin[c]; k < tree.child_begin[c + 1]; ++k)
                if (!is_cluster(tree.children[k]))
                    root_cluster[tree.children[k]] = std::int32_t(c);
        });
    }
    auto add_exact_emitters = [&](std::uint32_t first, std::uint32_t end,
                                  std::vector<std::uint32_t>& near) {
        for (std::uint32_t k = first; k < end; ++k) {
            if (!exact_emitter(cl[k]))
                continue;
            const NodeRef p = cl[k].source;
            if (!is_cluster(p)) {
                near.push_back(root_of[p]);
                continue;
            }
            const auto roots = links.cluster_roots(cluster_index(p));
            near.insert(near.end(), roots.begin(), roots.end());
        }
    };
    // A leaf's emitting roots, sorted and unique, into \p near.
    auto emitters_of = [&](std::uint32_t leaf, std::vector<std::uint32_t>& near) {
        near.clear();
        for (std::int32_t a = std::int32_t(leaf); a >= 0; a = h.parent[std::size_t(a)]) {
            for (std::uint32_t k = offsets[std::size_t(a)]; k < offsets[std::size_t(a) + 1]; ++k) {
                const std::uint32_t source = links.links()[k].source;
                if (!h.emission[source].is_black())
                    near.push_back(root_of[source]);
            }
            if (clusters.enabled)
                add_exact_emitters(by_element[std::size_t(a)], by_element[std::size_t(a) + 1],
                                   near);
        }
        if (clusters.enabled)
            for (std::int32_t c = root_cluster[root_of[leaf]];
                 c >= 0 && clusters.tree.planar[std::size_t(c)];
                 c = clusters.tree.parent[std::size_t(c)])
                if (lit_exactly[std::size_t(c)])
                    add_exact_emitters(by_cluster[std::size_t(c)], by_cluster[std::size_t(c) + 1],
                                       near);
        std::sort(near.begin(), near.end());
        near.erase(std::unique(near.begin(), near.end()), near.end());
    };
    // Counted, then written (CSR: a vector per leaf took 4 times the memory).
    std::vector<std::uint32_t>& first = out.near.first;
    first.assign(leaf_node.size() + 1, 0);
    parallel_for_index(leaf_node.size(), 256, [&](std::size_t e) {
        thread_local std::vector<std::uint32_t> near;
        emitters_of(leaf_node[e], near);
        first[e + 1] = std::uint32_t(near.size());
        Rgb far = clusters.enabled ? root_direct[root_of[leaf_node[e]]] : Rgb{};
        for (std::int32_t a = std::int32_t(leaf_node[e]); a >= 0; a = h.parent[std::size_t(a)])
            far += cluster_direct[std::size_t(a)];
        out.far[e] = far;
    });
    for (std::size_t e = 0; e < leaf_node.size(); ++e)
        first[e + 1] += first[e];
    out.near.roots.resize(first.back());
    parallel_for_index(leaf_node.size(), 256, [&](std::size_t e) {
        thread_local std::vector<std::uint32_t> near;
        emitters_of(leaf_node[e], near);
        std::copy(near.begin(), near.end(), out.near.roots.begin() + first[e]);
    });
    return out;
}

} // namespace

SolveResult solve_hierarchical(const Scene& scene, const RadiosityMesh& mesh,
                               const VisibilityQuery& visibility, const Context& ctx,
                               SolveStats* stats, const SolveObserver* observer,
                               const HierarchicalState* reuse) {
    Hierarchy h = reuse ? reused_hierarchy(mesh, *reuse) : Hierarchy(mesh);
    std::vector<std::int32_t> twin = reuse ? reuse->twin : mesh.element_twin;
    RefineSettings rs;
    rs.oracle = scene.solver.oracle == "bf" ? Oracle::bf : Oracle::variation;
    rs.rows.visibility_rays = scene.solver.visibility_rays;
    rs.rows.seed = ctx.seed;
    rs.rows.apart_quadrature_level = k_apart_level;
    rs.offset = 1e-5 * std::max(mesh.scene_diagonal, 1e-3);
    double emitted = emitted_power_max(h, scene.point_lights); // and the sun's, once linked
    rs.min_area = scene.solver.min_area > 0 ? scene.solver.min_area
                                            : std::pow(mesh.scene_diagonal / 200.0, 2);
    LinkSet links(h, twin, visibility, scene.point_lights, scene.sun ? &*scene.sun : nullptr, rs);
    NodeValues v;
    v.b = reuse ? reuse->radiosity : h.emission;
    v.b_range.assign(h.size(), 0.0f);
    ProgressStage progress(ctx, "hierarchical");
    Clusters clusters;
    clusters.enabled =
        reuse ? reuse->clustered
              : scene.solver.clustering == "on" ||
                    (scene.solver.clustering == "auto" && h.root_count > k_clustering_auto_roots);
    if (clusters.enabled) {
        clusters.tree = build_cluster_tree(h);
        init_cluster_values(clusters.tree, h, v.b, clusters.values);
        const ClusterValues& cv = clusters.values;
        if (reuse)
            links.attach_clusters(clusters.tree, cv.exitance, cv.exitance_emitted, cv.peak,
                                  cv.departure);
        else
            links.link_clusters(clusters.tree, cv.exitance, cv.exitance_emitted, cv.peak,
                                cv.departure);
        ctx.info("hierarchical: {} clusters over {} elements", clusters.tree.size(), h.root_count);
    }
    if (reuse) {
        links.restore(reuse->links.span(), reuse->cluster_links.span());
        ctx.info("hierarchical: reusing {} nodes and {} links", h.size(), links.link_count());
    } else if (!clusters.enabled) {
        links.link_roots();
    }
    links.set_threshold(scene.solver.epsilon * radiosity_scale(h, links));
    emitted += links.sun_power().max_component(); // what the sun's direct light delivers
    if (clusters.enabled)
        links.set_cluster_threshold(scene.solver.epsilon * emitted / clusters.tree.area[0]);
    SweepLog log{mesh, observer, stats};
    const Iteration iteration = parse_iteration(scene.solver.iteration);
    if (reuse && !reuse->weights.empty()) { // of the same links: geometry only
        v.weights = reuse->weights;
        pull_emit(h, v);
    }
    if (reuse) // the oracle should see the new materials' radiosities
        solve_links(h, links, v, clusters, scene.solver, iteration, emitted, log);
    const char* passes = iteration == Iteration::shooting ? "shots" : "sweeps";
    for (int cycle = 0; cycle < k_max_cycles; ++cycle) {
        auto t0 = Clock::now();
        const std::size_t links_before = links.link_count(), nodes_before = h.size();
        // The number of cycles is not known ahead (refinement stops when the radiosities stop
        // asking for it, usually after 3–6): half the bar for the first, which links and
        // refines the most, and half of what is left for each one after it. Within a cycle,
        // the bar moves half way to the cycle's end per refinement pass (their number is not
        // known ahead either), and a long refinement says where it is every
        // k_refine_report_s.
        const double cycle_start = 1.0 - std::pow(0.5, cycle);
        const double cycle_share = std::pow(0.5, cycle + 1);
        auto last_report = t0;
        auto on_pass = [&](const RefinePass& p) {
            progress.update(cycle_start + cycle_share * (1.0 - std::pow(0.5, p.pass)));
            if (seconds_since(last_report) < k_refine_report_s)
                return;
            last_report = Clock::now();
            ctx.info("hierarchical: cycle {}: refining, pass {} ({} links): {} nodes, {} "
                     "element, {} cluster and {} light links after {:.0f} s",
                     cycle, p.pass, p.kind, p.nodes, p.element_links, p.cluster_links,
                     p.light_links, seconds_since(t0));
        };
        if (clusters.enabled)
            weigh_departures(clusters.tree, h, v.b, clusters.values);
        const bool changed = links.refine(v.b, v.b_range, on_pass);
        const double refine_s = seconds_since(t0);
        t0 = Clock::now();
        if (changed || v.weights.empty()) {
            v.weights = leaf_weights(h, links, v.weights);
            pull_emit(h, v);
        }
        const double weights_s = seconds_since(t0);
        t0 = Clock::now();
        // A refinement that changed nothing, or added next to nothing, is the last: the
        // solution after it stays where the next one would leave it (on the 128k office
        // floor, cycles 5 to 11 took 26–40 s each for 0.01 % more links). The cycles before
        // it sweep to a looser residual.
        const bool last = cycle + 1 == k_max_cycles ||
                          (cycle > 0 && (!changed || (settled(links_before, links.link_count()) &&
                                                      settled(nodes_before, h.size()))));
        SolverSettings sweeps = scene.solver;
        if (!last)
            sweeps.residual *= k_intermediate_residual;
        Solved s = solve_links(h, links, v, clusters, sweeps, iteration, emitted, log);
        ctx.debug("hierarchical: cycle {}: refine {:.2f} s, leaf weights {:.2f} s, {} {:.2f} s",
                  cycle, refine_s, weights_s, passes, seconds_since(t0));
        if (s.limit_hit)
            ctx.warn("hierarchical: cycle {} stopped at {} {} (solver.{}) with a change of "
                     "{:.3g} of the emitted power, above its residual {:.3g}",
                     cycle, s.sweeps, passes,
                     iteration == Iteration::shooting ? "max_shots" : "max_sweeps", s.relative,
                     sweeps.residual);
        ctx.info("hierarchical: cycle {}: {} nodes, {} links ({} element, {} cluster, {} "
                 "light), {} {}, change {:.2e}",
                 cycle, h.size(), links.link_count(), links.links().size(),
                 links.cluster_links().size(), links.light_links().size(), s.sweeps, passes,
                 s.relative);
        progress.update(cycle_start + cycle_share);
        if (last)
            break;
    }
    auto t0 = Clock::now();
    release_sweep_values(v);
    // Where no root was subdivided the leaf mesh is the input mesh: no copy, and the caller
    // traces on the BVH it has.
    const bool subdivided = h.size() > h.root_count;
    LeafMesh leaf;
    if (subdivided) {
        leaf = build_leaf_mesh(mesh, h, twin);
    } else {
        leaf.element_node.resize(h.root_count);
        std::iota(leaf.element_node.begin(), leaf.element_node.end(), 0u);
    }
    const RadiosityMesh& out_mesh = subdivided ? leaf.mesh : mesh;
    ElementResult er;
    for (std::vector<Rgb>* a : {&er.radiosity, &er.h_direct, &er.h_indirect})
        a->reserve(leaf.element_node.size());
    for (std::uint32_t node : leaf.element_node) {
        er.radiosity.push_back(v.b[node]);
        er.h_direct.push_back(v.h_direct[node]);
        er.h_indirect.push_back(v.h_indirect[node]);
    }
    const ElementGeometry geo(out_mesh);
    RowSettings row_settings = rs.rows;
    SolveResult result;
    // Vertices gather direct light from the emitting roots: the same surfaces as the emitting
    // leaves, in fewer triangles (the same ones where no root was subdivided).
    std::optional<ElementGeometry> own_root_geo;
    if (subdivided)
        own_root_geo.emplace(mesh);
    const ElementGeometry& root_geo = own_root_geo ? *own_root_geo : geo;
    std::vector<Rgb> root_emission(mesh.element_count());
    for (std::size_t e = 0; e < root_emission.size(); ++e)
        root_emission[e] = mesh.patch_of(std::uint32_t(e)).emission;
    const LeafDirect sources = leaf_direct(h, links, clusters, v.b, leaf.element_node);
    leaf.element_node = {};
    // The refinement's and the clusters' tables are done with: the vertices, the balance and
    // the caller's output stage peaked the 1M floor's memory on top of them.
    const bool clustered = clusters.enabled;
    clusters = Clusters{};
    links.release_refinement_tables();
    const DirectEmitters emitters{root_geo, direct_sources(scene, root_emission), &sources.near,
                                  &sources.far};
    result.solution = make_solution(scene, out_mesh, geo, std::move(er), visibility, row_settings,
                                    ctx, &emitters);
    ctx.debug("hierarchical: leaf mesh, vertices and sensors {:.2f} s", seconds_since(t0));
    t0 = Clock::now();
    if (stats) {
        stats->shots = log.total;
        stats->links = links.link_count();
        stats->power = hierarchical_balance(
            scene, out_mesh, geo, result.solution, visibility, row_settings,
            stats->residual_history.empty() ? 0.0 : stats->residual_history.back(),
            links.sun_power());
        ctx.debug("hierarchical: power balance {:.2f} s", seconds_since(t0));
    }
    // The last pass is the solution itself where it lives on the roots.
    if (observer && observer->on_pass)
        observer->on_pass(subdivided ? root_snapshot(mesh, h, v) : result.solution, log.total, 0.0,
                          true);
    auto state = std::make_shared<HierarchicalState>();
    state->mesh_hash = mesh_geometry_hash(mesh);
    state->clustered = clustered;
    state->twin = twin;
    // Moved, not copied: a big scene's links are most of the solve's memory.
    state->links = links.take_links();
    state->cluster_links = links.take_cluster_links();
    state->radiosity = v.b;
    state->weights = std::move(v.weights);
    state->hierarchy = std::move(h);
    result.state = std::move(state);
    if (subdivided)
        result.refined_mesh = std::move(leaf.mesh);
    return result;
}

} // namespace penumbra::solver
