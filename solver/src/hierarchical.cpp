// Hierarchical radiosity (Hanrahan, Salzman & Aupperle 1991). Every mesh element is the root
// of a 1-to-4 hierarchy; links between nodes are refined by the BF oracle (the irradiance a
// link brings, F_qp B_p, against ε × the brightest source's exitance, partly occluded links
// counted double) down to a minimum area; a Jacobi gathering sweep over the links is followed by push-pull over the
// hierarchy (irradiance gathered at a node applies to all its descendants; radiosity is pulled
// up as the area mean). Reflectors have no radiosity before the first solve, so refinement
// and solving alternate until refinement changes nothing.
//
// Deviations: form factors are receiver-side quadratures of the analytic point-to-triangle
// form factor (4 points, 64 for near pairs) times ray visibility, rather than Hanrahan's
// disc approximation; front and back sides subdivide together so that leaves stay twins; a
// link's irradiance is pushed to the leaves of its receiver, and its source's radiosity pulled
// from the leaves of its source, by each leaf's own form factors to the link's far ends rather
// than evenly (hr_weights.h), so that a closed box of uniform radiosity stays uniform and
// power is not lost where radiosity varies over a coarse source.

#include "hierarchical.h"

#include <chrono>
#include <cmath>

#include "cluster_transport.h"
#include "core/error.h"
#include "core/parallel.h"
#include "hierarchy.h"
#include "hr_links.h"
#include "hr_state.h"
#include "hr_weights.h"
#include "leaf_mesh.h"
#include "vertex_values.h"

namespace penumbra::solver {

namespace {

constexpr int k_max_cycles = 12;
/// solver.clustering "auto" clusters meshes with more elements than this.
constexpr std::size_t k_clustering_auto_roots = 3000;

struct NodeValues {
    std::vector<Rgb> b, gathered_direct, gathered_indirect, h_direct, h_indirect;
    std::vector<float> b_lo, b_hi; ///< range of the leaves' radiosity (largest channel)
    std::vector<float> b_range;    ///< b_hi − b_lo
    /// Irradiance gathered through element links alone: what the leaf weights spread.
    std::vector<Rgb> link_direct, link_indirect;
    /// What each node sends through its element links: its leaves' radiosities by their emit
    /// weights (the leaf's own radiosity for a leaf).
    std::vector<Rgb> b_emit;
    LeafWeights weights;
};

double emitted_power_max(const Hierarchy& h, const std::vector<PointLight>& lights) {
    double total = 0;
    for (std::size_t n = 0; n < h.root_count; ++n)
        total += double(h.emission[n].max_component()) * h.area[n];
    for (const PointLight& l : lights)
        total += 4.0 * k_pi * double(l.intensity.max_component());
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

void gather(const Hierarchy& h, const LinkSet& links, NodeValues& v) {
    const std::size_t n = h.size();
    v.gathered_direct.assign(n, Rgb{});
    v.gathered_indirect.assign(n, Rgb{});
    const auto& offsets = links.receiver_offsets();
    const auto& all = links.links();
    const std::vector<Rgb>& b_source = v.b_emit.size() == n ? v.b_emit : v.b;
    parallel_for_index(n, 256, [&](std::size_t q) {
        RgbD direct, indirect;
        for (std::uint32_t k = offsets[q]; k < offsets[q + 1]; ++k) {
            const Link& l = all[k];
            direct += RgbD(h.emission[l.source]) * l.ff;
            indirect += RgbD(b_source[l.source] - h.emission[l.source]) * l.ff;
        }
        v.gathered_direct[q] = Rgb(float(direct.r), float(direct.g), float(direct.b));
        v.gathered_indirect[q] = Rgb(float(indirect.r), float(indirect.g), float(indirect.b));
    });
    v.link_direct = v.gathered_direct;
    v.link_indirect = v.gathered_indirect;
    for (const LightLink& l : links.light_links()) // few; serial keeps the order fixed
        v.gathered_direct[l.receiver] += l.irradiance;
}

// Leaf x's radiosity \p b as it is sent: by x itself and, by its emit weights, as its share
// of what each ancestor sends (whose b_emit the caller has zeroed).
void add_emit_shares(const Hierarchy& h, NodeValues& v, std::uint32_t x, const Rgb& b) {
    v.b_emit[x] = b;
    for (std::int32_t a = h.parent[x]; a >= 0; a = h.parent[a])
        v.b_emit[a] +=
            b * float(h.area[x] / h.area[a] * v.weights.emit[v.weights.at(x, h.level[a])]);
}

// NodeValues::b_emit afresh from the leaves' radiosities, once the weights have changed.
void pull_emit(const Hierarchy& h, NodeValues& v) {
    v.b_emit.assign(h.size(), Rgb{});
    parallel_for_index(h.root_count, 16, [&](std::size_t r) {
        std::vector<std::uint32_t> stack{std::uint32_t(r)};
        while (!stack.empty()) {
            const std::uint32_t n = stack.back();
            stack.pop_back();
            if (h.is_leaf(n)) {
                add_emit_shares(h, v, n, v.b[n]);
                continue;
            }
            for (int c = 3; c >= 0; --c)
                stack.push_back(std::uint32_t(h.first_child[n] + c));
        }
    });
}

// Push irradiance down and pull radiosity up in one tree; returns the node's new radiosity
// and adds Σ A |ΔB| over the leaves to \p change.
Rgb push_pull(const Hierarchy& h, NodeValues& v, std::uint32_t node, const Rgb& down_direct,
              const Rgb& down_indirect, double& change) {
    Rgb hd = down_direct + v.gathered_direct[node];
    Rgb hi = down_indirect + v.gathered_indirect[node];
    const bool weighted = !v.weights.empty();
    Rgb b;
    if (h.is_leaf(node)) {
        // The ancestors' element links by this leaf's receive weights rather than evenly.
        for (std::int32_t a = weighted ? h.parent[node] : -1; a >= 0; a = h.parent[a]) {
            const float extra = v.weights.receive[v.weights.at(node, h.level[a])] - 1.0f;
            hd += v.link_direct[a] * extra;
            hi += v.link_indirect[a] * extra;
        }
        b = h.emission[node] + h.reflectance[node] * (hd + hi);
        if (weighted)
            add_emit_shares(h, v, node, b);
        v.h_direct[node] = hd;
        v.h_indirect[node] = hi;
        v.b_lo[node] = v.b_hi[node] = b.max_component();
        change += double((b - v.b[node]).sum() >= 0 ? (b - v.b[node]).sum()
                                                    : -(b - v.b[node]).sum()) *
                  h.area[node];
    } else {
        Rgb sum_b, sum_hd, sum_hi;
        if (weighted)
            v.b_emit[node] = Rgb{}; // the leaves below add their shares
        v.b_lo[node] = 1e30f;
        v.b_hi[node] = 0;
        for (int c = 0; c < 4; ++c) {
            const auto child = std::uint32_t(h.first_child[node] + c);
            sum_b += push_pull(h, v, child, hd, hi, change);
            sum_hd += v.h_direct[child];
            sum_hi += v.h_indirect[child];
            v.b_lo[node] = std::min(v.b_lo[node], v.b_lo[child]);
            v.b_hi[node] = std::max(v.b_hi[node], v.b_hi[child]);
        }
        b = sum_b * 0.25f; // children have equal areas
        v.h_direct[node] = sum_hd * 0.25f;
        v.h_indirect[node] = sum_hi * 0.25f;
    }
    v.b[node] = b;
    v.b_range[node] = v.b_hi[node] - v.b_lo[node];
    return b;
}

/// The cluster tree and its values, when clustering.
struct Clusters {
    ClusterTree tree;
    ClusterValues values;
    bool enabled = false;
};

double sweep(const Hierarchy& h, const LinkSet& links, NodeValues& v, Clusters& clusters,
             double emitted) {
    gather(h, links, v);
    if (clusters.enabled) {
        gather_cluster_links(h, clusters.tree, links, v.b, clusters.values, v.gathered_direct,
                             v.gathered_indirect);
        push_clusters(clusters.tree, h, clusters.values);
    }
    v.h_direct.resize(h.size());
    v.h_indirect.resize(h.size());
    v.b_lo.resize(h.size());
    v.b_hi.resize(h.size());
    std::vector<double> change(h.root_count, 0.0);
    parallel_for_index(h.root_count, 16, [&](std::size_t r) {
        const bool c = clusters.enabled;
        push_pull(h, v, std::uint32_t(r), c ? clusters.values.root_direct[r] : Rgb{},
                  c ? clusters.values.root_indirect[r] : Rgb{}, change[r]);
    });
    if (clusters.enabled)
        pull_clusters(clusters.tree, h, v.b, clusters.values);
    double total = 0;
    for (double c : change)
        total += c;
    return total / std::max(emitted * 3.0, 1e-300); // change is summed over 3 channels
}

struct Solved {
    int sweeps = 0;
    double relative = 1;
};

// The roots are the input mesh's elements: their pulled values are a snapshot on it.
Solution root_snapshot(const RadiosityMesh& mesh, const Hierarchy& h, const NodeValues& v) {
    ElementResult er;
    for (std::size_t r = 0; r < h.root_count; ++r) {
        er.radiosity.push_back(v.b[r]);
        er.h_direct.push_back(r < v.h_direct.size() ? v.h_direct[r] : Rgb{});
        er.h_indirect.push_back(r < v.h_indirect.size() ? v.h_indirect[r] : Rgb{});
    }
    return snapshot_solution(mesh, er);
}

struct SweepLog {
    const RadiosityMesh& mesh;
    const SolveObserver* observer;
    SolveStats* stats;
    std::int64_t total = 0;
};

Solved solve_links(const Hierarchy& h, const LinkSet& links, NodeValues& v, Clusters& clusters,
                   const SolverSettings& settings, double emitted, SweepLog& log) {
    Solved s;
    while (s.sweeps < settings.max_sweeps && s.relative > settings.residual) {
        s.relative = sweep(h, links, v, clusters, emitted);
        ++s.sweeps;
        ++log.total;
        if (log.stats)
            log.stats->residual_history.push_back(s.relative);
        const SolveObserver* o = log.observer;
        if (o && o->on_pass && o->every_shots > 0 && log.total % o->every_shots == 0)
            o->on_pass(root_snapshot(log.mesh, h, v), log.total, s.relative, false);
    }
    return s;
}

} // namespace

namespace {

// A re-solve: the saved hierarchy with the new scene's reflectances and emissions.
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
    }
    return h;
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
    rs.offset = 1e-5 * std::max(mesh.scene_diagonal, 1e-3);
    const double emitted = emitted_power_max(h, scene.point_lights);
    rs.min_area = scene.solver.min_area > 0 ? scene.solver.min_area
                                            : std::pow(mesh.scene_diagonal / 200.0, 2);
    LinkSet links(h, twin, visibility, scene.point_lights, rs);
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
        if (reuse)
            links.attach_clusters(clusters.tree, clusters.values.exitance, clusters.values.peak);
        else
            links.link_clusters(clusters.tree, clusters.values.exitance, clusters.values.peak);
        ctx.info("hierarchical: {} clusters over {} elements", clusters.tree.size(),
                 h.root_count);
    }
    if (reuse) {
        links.restore(reuse->links, reuse->cluster_links);
        ctx.info("hierarchical: reusing {} nodes and {} links", h.size(), links.link_count());
    } else if (!clusters.enabled) {
        links.link_roots();
    }
    links.set_threshold(scene.solver.epsilon * radiosity_scale(h, links));
    if (clusters.enabled)
        links.set_cluster_threshold(scene.solver.epsilon * emitted / clusters.tree.area[0]);
    SweepLog log{mesh, observer, stats};
    if (reuse) // the oracle should see the new materials' radiosities
        solve_links(h, links, v, clusters, scene.solver, emitted, log);
    for (int cycle = 0; cycle < k_max_cycles; ++cycle) {
        const bool changed = links.refine(v.b, v.b_range);
        if (changed || v.weights.empty()) {
            v.weights = leaf_weights(h, links, v.weights);
            pull_emit(h, v);
        }
        Solved s = solve_links(h, links, v, clusters, scene.solver, emitted, log);
        ctx.info("hierarchical: cycle {}: {} nodes, {} links, {} sweeps, change {:.2e}", cycle,
                 h.size(), links.link_count(), s.sweeps,
                 s.relative);
        progress.update(double(cycle + 1) / k_max_cycles);
        if (!changed && cycle > 0)
            break;
    }
    LeafMesh leaf = build_leaf_mesh(mesh, h, twin);
    ElementResult er;
    for (std::uint32_t node : leaf.element_node) {
        er.radiosity.push_back(v.b[node]);
        er.h_direct.push_back(v.h_direct[node]);
        er.h_indirect.push_back(v.h_indirect[node]);
    }
    ElementGeometry geo(leaf.mesh);
    RowSettings row_settings = rs.rows;
    SolveResult result;
    result.solution = make_solution(scene, leaf.mesh, geo, er, visibility, row_settings, ctx);
    if (stats) {
        stats->shots = log.total;
        stats->links = links.link_count();
        stats->power = hierarchical_balance(scene, leaf.mesh, geo, result.solution, visibility,
                                            row_settings, stats->residual_history.empty()
                                                              ? 0.0
                                                              : stats->residual_history.back());
    }
    if (observer && observer->on_pass)
        observer->on_pass(root_snapshot(mesh, h, v), log.total, 0.0, true);
    auto state = std::make_shared<HierarchicalState>();
    state->mesh_hash = mesh_geometry_hash(mesh);
    state->clustered = clusters.enabled;
    state->twin = twin;
    state->links = links.links();
    state->cluster_links = links.cluster_links();
    state->radiosity = v.b;
    state->hierarchy = std::move(h);
    result.state = std::move(state);
    result.refined_mesh = std::move(leaf.mesh);
    return result;
}

} // namespace penumbra::solver
