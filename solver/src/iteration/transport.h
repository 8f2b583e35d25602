#pragma once
// Light transport over a fixed set of hierarchical links, and the iterations that solve it:
// Jacobi sweeps, Gauss–Seidel sweeps by blocks of roots, and progressive shooting
// (Southwell) on the hierarchy (issue #4). Every sweep gathers over the links, grouped by
// receiver, then pushes irradiance down and pulls radiosity up each root's tree (Hanrahan et
// al. 1991); shooting sends each root tree's unshot radiosity through the links it is the
// source of, and lets receivers collect it lazily.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "hierarchy/cluster_tree.h"
#include "hierarchy/hierarchy.h"
#include "hierarchy/leaf_weights.h"
#include "iteration/cluster_transport.h"
#include "links/cluster_tables.h"
#include "links/link_store.h"
#include "solver/solver.h"

namespace penumbra::solver {

/// How the radiosities of one set of links are solved (SolverSettings::iteration).
using Iteration = SolverIteration;

struct NodeValues {
    std::vector<Rgb> b, gathered_direct, gathered_indirect, h_direct, h_indirect;
    std::vector<float> b_lo, b_hi; ///< range of the leaves' radiosity (largest channel)
    std::vector<float> b_range;    ///< b_hi − b_lo
    /// Irradiance gathered through element links alone: what the leaf weights spread.
    std::vector<Rgb> link_direct, link_indirect;
    /// Irradiance of light links and cluster links to element receivers, spread evenly.
    std::vector<Rgb> extra_direct, extra_indirect;
    /// Per root (empty: none), W/m²: light that reaches it through specular surfaces (issue
    /// #28), added to extra_indirect every sweep: the sources' part (specular_fixed) and
    /// what the roots' reflected light of the last sweep passes on (specular_transfers).
    std::vector<Rgb> specular, specular_fixed;
    std::span<const SpecularLight::Transfer> specular_transfers;
    /// What each node sends through its element links: its leaves' radiosities by their emit
    /// weights (the leaf's own radiosity for a leaf).
    std::vector<Rgb> b_emit;
    /// Per leaf, τ times its twin's irradiance of the last sweep (empty when no surface
    /// transmits diffusely).
    std::vector<Rgb> transmitted;
    LeafWeights weights;
};

/// Frees what only the sweeps use, keeping b, h_direct, h_indirect and the weights.
void release_sweep_values(NodeValues& v);

/// The cluster tree and its values, when clustering.
struct Clusters {
    ClusterTree tree;
    ClusterValues values;
    bool enabled = false;
    /// Of tree and values, from the first links to the last gather.
    std::unique_ptr<ClusterTables> tables;
};

/// Where sweeps and shots are reported: the residual history and the observer's snapshots
/// (on the roots, i.e. the input mesh's elements).
struct SweepLog {
    const RadiosityMesh& mesh;
    const SolveObserver* observer;
    SolveStats* stats;
    std::int64_t total = 0; ///< sweeps, or shots when shooting
};

struct Solved {
    int sweeps = 0;         ///< sweeps (shooting: shots)
    double relative = 1;    ///< last change (shooting: unshot power) over the emitted power
    bool limit_hit = false; ///< stopped by solver.max_sweeps or max_shots, not the residual
};

/// NodeValues::b_emit afresh from the leaves' radiosities, once the weights have changed.
void pull_emit(const Hierarchy& h, NodeValues& v);

/// \brief Solves the radiosities of the current links with \p iteration until the relative
///        change (or unshot power) falls below settings.residual. \p emitted: W, the largest
///        channel of the emitted power.
Solved solve_links(const Hierarchy& h, const LinkStore& links, NodeValues& v, Clusters& clusters,
                   const SolverSettings& settings, Iteration iteration, double emitted,
                   SweepLog& log);

// Building blocks, shared by the iterations (iteration/transport.cpp,
// iteration/hierarchical_shooting.cpp).

/// One Jacobi sweep over every link and tree; returns Σ A |ΔB| over the leaves / emitted.
double sweep_jacobi(const Hierarchy& h, const LinkStore& links, NodeValues& v, Clusters& clusters,
                    double emitted);
/// Progressive shooting on the hierarchy (iteration/hierarchical_shooting.cpp): one Jacobi sweep
/// for the direct light, then Southwell shots of the change, then a last sweep.
Solved shoot_links(const Hierarchy& h, const LinkStore& links, NodeValues& v, Clusters& clusters,
                   const SolverSettings& settings, double emitted, SweepLog& log);
/// The nodes of every root's tree, depth first, parents before children (CSR by root).
struct TreeNodes {
    std::vector<std::uint32_t> start, nodes;
};
TreeNodes tree_nodes(const Hierarchy& h);
/// Counts a sweep or shot in \p log, adds \p relative to the residual history if \p history,
/// and hands the observer a snapshot when one is due.
void record_pass(const Hierarchy& h, const NodeValues& v, SweepLog& log, double relative,
                 bool history);
/// Node \p n's reflected exitance B − E in \p b, each channel at least 0 (W/m²): what the
/// specular transfers are linear in, and their photons' sources are drawn by.
Rgb reflected_exitance(const Hierarchy& h, const std::vector<Rgb>& b, std::uint32_t n);
/// Σ A |ΔB| over the leaves and channels between \p before and \p after, over 3 × \p emitted:
/// the change by which every sweep, and the rounds that re-weigh the leaves, stop.
double relative_leaf_change(const Hierarchy& h, const std::vector<Rgb>& before,
                            const std::vector<Rgb>& after, double emitted);
/// Recomputes the inner nodes' radiosities, ranges and b_emit from the leaves.
void pull_all(const Hierarchy& h, NodeValues& v);
/// The roots' radiosities and irradiances as a solution on the input mesh.
Solution root_snapshot(const RadiosityMesh& mesh, const Hierarchy& h, const NodeValues& v);

} // namespace penumbra::solver
