// Hierarchical radiosity (Hanrahan, Salzman & Aupperle 1991). Every mesh element is the root
// of a 1-to-4 hierarchy; links between nodes are refined by the oracle of solver.oracle
// (oracle/oracle.h; by default "variation": ΔF·B_p + F_qp·ΔB_p, the spread of the form factor
// over the receiver times the source's radiosity plus the form factor times the range of
// radiosity over the source; "bf": F_qp B_p, the irradiance the link brings) against ε × the
// brightest source's exitance, partly occluded links counted double, down to a minimum area;
// a Jacobi gathering sweep over the links is followed by push-pull over the hierarchy
// (irradiance gathered at a node applies to all its descendants; radiosity is pulled up as the
// area mean). Reflectors have no radiosity before the first solve, so refinement and solving
// alternate until refinement changes nothing, or next to nothing.
//
// Deviations: form factors are receiver-side quadratures of the analytic point-to-triangle
// form factor (4 points, up to 64 for near pairs) times ray visibility, rather than Hanrahan's
// disc approximation; front and back sides subdivide together so that leaves stay twins; a
// link's irradiance is pushed to the leaves of its receiver, and its source's radiosity pulled
// from the leaves of its source, by each leaf's own form factors to the link's far ends rather
// than evenly (hierarchy/leaf_weights.h), so that a closed box of uniform radiosity stays uniform
// and power is not lost where radiosity varies over a coarse source.

#include "hierarchical.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>

#include "core/error.h"
#include "core/parallel.h"
#include "hierarchical_system.h"
#include "hierarchy/hierarchy.h"
#include "hierarchy/leaf_mesh.h"
#include "iteration/cluster_transport.h"
#include "iteration/transport.h"
#include "output/sky_vertices.h"
#include "output/vertex_values.h"
#include "state/solver_state.h"

namespace penumbra::solver {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
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

// The direct light that cluster links bring, per node and pushed down to each root.
// Overwrites \p clusters' gathered and pushed values (the solve is done with them): a copy
// took 0.3 GB on the 1M floor, at the solve's peak.
struct ClusterDirect {
    std::vector<Rgb> node, root;
};

ClusterDirect cluster_direct(const Hierarchy& h, const LinkStore& links, Clusters& clusters,
                             const std::vector<Rgb>& b) {
    ClusterDirect out;
    out.node.resize(h.size());
    std::vector<Rgb> unused(h.size());
    if (clusters.enabled) { // the direct part alone
        ClusterValues& cv = clusters.values;
        gather_cluster_links(h, *clusters.tables, links, b, cv, out.node, unused, false, false);
        push_clusters(clusters.tree, h, cv);
        out.root = std::move(cv.root_direct);
    }
    return out;
}

// The emitting roots a leaf's vertices gather exactly: those that element links reach it or
// its ancestors from, and the emitters of exact links (left out of the direct light of the
// cluster links), which reach a leaf through its element ancestors and the face clusters
// above its root.
class LeafEmitters {
public:
    LeafEmitters(const Hierarchy& h, const LinkStore& links, const Clusters& clusters)
        : h_(h), links_(links), clusters_(clusters), root_of_(h.root_of_nodes()) {
        if (!clusters.enabled)
            return;
        // Per cluster, whether any exact link from an emitter ends there, and each root's
        // leaf cluster.
        const ClusterTree& tree = clusters.tree;
        const auto& cl = links.cluster_links();
        const auto& by_cluster = links.cluster_offsets_clusters();
        lit_exactly_.assign(tree.size(), 0);
        root_cluster_.assign(h.root_count, -1);
        parallel_for_index(tree.size(), 256, [&](std::size_t c) {
            for (std::uint32_t k = by_cluster[c]; k < by_cluster[c + 1] && !lit_exactly_[c]; ++k)
                lit_exactly_[c] = exact_emitter(cl[k]);
            for (std::uint32_t k = tree.child_begin[c]; k < tree.child_begin[c + 1]; ++k)
                if (!is_cluster(tree.children[k]))
                    root_cluster_[tree.children[k]] = std::int32_t(c);
        });
    }

    const std::vector<std::uint32_t>& root_of() const { return root_of_; }

    /// A leaf's emitting roots, sorted and unique, into \p near.
    void of(std::uint32_t leaf, std::vector<std::uint32_t>& near) const {
        const auto& offsets = links_.receiver_offsets();
        const auto& by_element = links_.cluster_offsets_elements();
        const auto& by_cluster = links_.cluster_offsets_clusters();
        near.clear();
        for (std::int32_t a = std::int32_t(leaf); a >= 0; a = h_.parent[std::size_t(a)]) {
            for (std::uint32_t k = offsets[std::size_t(a)]; k < offsets[std::size_t(a) + 1]; ++k) {
                const std::uint32_t source = links_.links()[k].source;
                if (!h_.emission[source].is_black())
                    near.push_back(root_of_[source]);
            }
            if (clusters_.enabled)
                add_exact_emitters(by_element[std::size_t(a)], by_element[std::size_t(a) + 1],
                                   near);
        }
        if (clusters_.enabled)
            for (std::int32_t c = root_cluster_[root_of_[leaf]];
                 c >= 0 && clusters_.tree.planar[std::size_t(c)];
                 c = clusters_.tree.parent[std::size_t(c)])
                if (lit_exactly_[std::size_t(c)])
                    add_exact_emitters(by_cluster[std::size_t(c)], by_cluster[std::size_t(c) + 1],
                                       near);
        std::sort(near.begin(), near.end());
        near.erase(std::unique(near.begin(), near.end()), near.end());
    }

private:
    bool exact_emitter(const ClusterLink& l) const {
        return l.exact && clusters_.tables->emits(l.source);
    }

    void add_exact_emitters(std::uint32_t first, std::uint32_t end,
                            std::vector<std::uint32_t>& near) const {
        const auto& cl = links_.cluster_links();
        for (std::uint32_t k = first; k < end; ++k) {
            if (!exact_emitter(cl[k]))
                continue;
            const NodeRef p = cl[k].source;
            if (!is_cluster(p)) {
                near.push_back(root_of_[p]);
                continue;
            }
            const auto roots = clusters_.tables->cluster_roots(cluster_index(p));
            near.insert(near.end(), roots.begin(), roots.end());
        }
    }

    const Hierarchy& h_;
    const LinkStore& links_;
    const Clusters& clusters_;
    const std::vector<std::uint32_t> root_of_;
    std::vector<std::uint8_t> lit_exactly_;
    std::vector<std::int32_t> root_cluster_;
};

LeafDirect leaf_direct(const Hierarchy& h, const LinkStore& links, Clusters& clusters,
                       const std::vector<Rgb>& b, const std::vector<std::uint32_t>& leaf_node) {
    const ClusterDirect direct = cluster_direct(h, links, clusters, b);
    const LeafEmitters emitters(h, links, clusters);
    const std::vector<std::uint32_t>& root_of = emitters.root_of();
    LeafDirect out;
    out.far.resize(leaf_node.size());
    // Counted, then written (CSR: a vector per leaf took 4 times the memory).
    std::vector<std::uint32_t>& first = out.near.first;
    first.assign(leaf_node.size() + 1, 0);
    parallel_for_index(leaf_node.size(), 256, [&](std::size_t e) {
        thread_local std::vector<std::uint32_t> near;
        emitters.of(leaf_node[e], near);
        first[e + 1] = std::uint32_t(near.size());
        Rgb far = clusters.enabled ? direct.root[root_of[leaf_node[e]]] : Rgb{};
        for (std::int32_t a = std::int32_t(leaf_node[e]); a >= 0; a = h.parent[std::size_t(a)])
            far += direct.node[std::size_t(a)];
        out.far[e] = far;
    });
    for (std::size_t e = 0; e < leaf_node.size(); ++e)
        first[e + 1] += first[e];
    out.near.roots.resize(first.back());
    parallel_for_index(leaf_node.size(), 256, [&](std::size_t e) {
        thread_local std::vector<std::uint32_t> near;
        emitters.of(leaf_node[e], near);
        std::copy(near.begin(), near.end(), out.near.roots.begin() + first[e]);
    });
    return out;
}

} // namespace

namespace {

// The leaves of the built system as elements (none where no root was subdivided: the input
// mesh is the leaf mesh, and the caller traces on the BVH it has) and the leaves' values.
struct LeafElements {
    LeafMesh leaf;
    ElementResult er;
};

LeafElements leaves_with_values(const HierarchicalSystem& sys, const RadiosityMesh& mesh) {
    const NodeValues& v = sys.values;
    LeafElements out;
    out.leaf = leaf_elements(mesh, sys.h);
    const LeafMesh& leaf = out.leaf;
    ElementResult& er = out.er;
    for (std::vector<Rgb>* a : {&er.radiosity, &er.h_direct, &er.h_indirect})
        a->reserve(leaf.element_node.size());
    for (std::uint32_t node : leaf.element_node) {
        er.radiosity.push_back(v.b[node]);
        er.h_direct.push_back(v.h_direct[node]);
        er.h_indirect.push_back(v.h_indirect[node]);
    }
    return out;
}

// The root of each leaf element's node.
std::vector<std::uint32_t> leaf_roots(const Hierarchy& h,
                                      const std::vector<std::uint32_t>& element_node) {
    std::vector<std::uint32_t> out(element_node.size());
    for (std::size_t e = 0; e < out.size(); ++e) {
        std::uint32_t n = element_node[e];
        while (h.parent[n] >= 0)
            n = std::uint32_t(h.parent[n]);
        out[e] = n;
    }
    return out;
}

// The vertices' values and the sensors on the leaf mesh \p geo. Frees the refinement's and
// the clusters' tables once the leaves' direct sources are known: the vertices, the balance
// and the caller's output stage peaked the 1M floor's memory on top of them.
Solution leaf_solution(HierarchicalSystem& sys, const Scene& scene, const RadiosityMesh& mesh,
                       const ElementGeometry& geo, LeafElements& leaves,
                       const VisibilityQuery& visibility, const Context& ctx) {
    // Vertices gather direct light from the emitting roots: the same surfaces as the emitting
    // leaves, in fewer triangles (the same ones where no root was subdivided).
    std::optional<ElementGeometry> own_root_geo;
    if (leaves.leaf.subdivided)
        own_root_geo.emplace(mesh);
    const ElementGeometry& root_geo = own_root_geo ? *own_root_geo : geo;
    std::vector<Rgb> root_emission(mesh.element_count());
    for (std::size_t e = 0; e < root_emission.size(); ++e)
        root_emission[e] = mesh.patch_of(std::uint32_t(e)).emission;
    const LeafDirect sources =
        leaf_direct(sys.h, sys.links, sys.clusters, sys.values.b, leaves.leaf.element_node);
    const RadiosityMesh& out_mesh = leaves.leaf.of(mesh);
    const std::vector<Rgb> sky =
        scene.sky
            ? sky_at_vertices(*scene.sky, mesh, root_geo, out_mesh,
                              leaf_roots(sys.h, leaves.leaf.element_node), visibility, ctx.seed)
            : std::vector<Rgb>{};
    leaves.leaf.element_node = {};
    sys.clusters = Clusters{}; // and the cluster links' tables
    DirectEmitters emitters{root_geo, direct_sources(scene, root_emission), &sources.near,
                            &sources.far};
    if (scene.sky) {
        emitters.sources.sky.reset();
        emitters.sky = &sky;
    }
    return make_solution(scene, out_mesh, geo, std::move(leaves.er), visibility, sys.settings.rows,
                         ctx, &emitters);
}

// What a re-solve starts from. Moved, not copied: a big scene's links are most of the
// solve's memory.
std::shared_ptr<HierarchicalState> saved_state(HierarchicalSystem& sys, const RadiosityMesh& mesh,
                                               bool clustered) {
    auto state = std::make_shared<HierarchicalState>();
    state->mesh_hash = mesh_geometry_hash(mesh);
    state->clustered = clustered;
    state->links = sys.links.take_links();
    state->cluster_links = sys.links.take_cluster_links();
    state->radiosity = sys.values.b;
    state->weights = std::move(sys.values.weights);
    state->hierarchy = std::move(sys.h);
    return state;
}

// The output stage: the leaf mesh, its vertex values and sensors, the power balance, the
// final snapshot and the state a re-solve starts from.
SolveResult output_stage(HierarchicalSystem& sys, const Scene& scene, const RadiosityMesh& mesh,
                         const VisibilityQuery& visibility, const Context& ctx, SolveStats* stats,
                         const SolveObserver* observer, const SweepLog& log) {
    auto t0 = Clock::now();
    release_sweep_values(sys.values);
    LeafElements leaves = leaves_with_values(sys, mesh);
    const RadiosityMesh& out_mesh = leaves.leaf.of(mesh);
    const ElementGeometry geo(out_mesh);
    const bool clustered = sys.clusters.enabled;
    SolveResult result;
    result.solution = leaf_solution(sys, scene, mesh, geo, leaves, visibility, ctx);
    ctx.debug("hierarchical: leaf mesh, vertices and sensors {:.2f} s", seconds_since(t0));
    t0 = Clock::now();
    if (stats) {
        stats->shots = log.total;
        stats->links = sys.links.link_count();
        stats->power = hierarchical_balance(
            scene, out_mesh, geo, result.solution, visibility, sys.settings.rows,
            stats->residual_history.empty() ? 0.0 : stats->residual_history.back(),
            sys.distant_power() + sys.specular_power());
        ctx.debug("hierarchical: power balance {:.2f} s", seconds_since(t0));
    }
    // The last pass is the solution itself where it lives on the roots.
    if (observer && observer->on_pass)
        observer->on_pass(leaves.leaf.subdivided ? root_snapshot(mesh, sys.h, sys.values)
                                                 : result.solution,
                          log.total, 0.0, true);
    result.state = saved_state(sys, mesh, clustered);
    if (leaves.leaf.subdivided)
        result.refined_mesh = std::move(leaves.leaf.mesh);
    return result;
}

} // namespace

SolveResult solve_hierarchical(const Scene& scene, const RadiosityMesh& mesh,
                               const VisibilityQuery& visibility, const Context& ctx,
                               SolveStats* stats, const SolveObserver* observer,
                               const HierarchicalState* reuse, const SpecularLight* specular) {
    if (reuse)
        check_reusable(mesh, *reuse);
    ProgressStage progress(ctx, "hierarchical");
    SweepLog log{mesh, observer, stats};
    const std::unique_ptr<HierarchicalSystem> system =
        build_hierarchical(scene, mesh, visibility, ctx, progress, log, reuse, specular);
    return output_stage(*system, scene, mesh, visibility, ctx, stats, observer, log);
}

} // namespace penumbra::solver
