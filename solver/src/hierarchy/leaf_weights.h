#pragma once
// How hierarchical links spread over the leaves of their receiver and of their source.
//
// Hanrahan et al.'s push-pull gives every leaf of a link's receiver the same irradiance and
// takes the same share of radiosity from every leaf of its source. Where the form factor
// varies over a node the same way for many links, their errors add up instead of cancelling:
// next to a corner every far surface is seen at a flatter angle than on average over the
// node, so in a closed box of uniform radiosity the form factors a corner leaf inherited
// summed to up to 1.5 (its radiosity up to 30 % high), and coarse links took the bright
// middle of a lit wall at its area share although it sends more than that (the indirect light
// of CIE 171 test 5.8 0.6 % short on coarse elements). So every leaf x gets, for each
// ancestor a, weights in proportion to its own form factors toward the far ends of a's links
// (issue #4), each far end counted with what it sends (issue #27):
//
//   receive_a(x) ∝ Σ_{links a ← s} F(x → s) E_s / Σ F(a → s) E_s       (a's direct light at x)
//   reflected_a(x) ∝ Σ_{links a ← s} F(x → s) R_s / Σ F(a → s) R_s     (per channel)
//   emit_a(x)    ∝ Σ_{links r ← a} F(x → r) / Σ A_r F(r → a) / A_a  (x's share of what a sends)
//
// with E_s the far end's emission and R_s its reflected radiosity B − E. Weighing the far ends
// by one common F made a leaf in a dim concave corner, which sees more of the dim walls beside
// it and as much of the bright ones as the rest of its node, take the node's irradiance times
// its larger F: on the Cornell box 45 % too much light on the back wall by the green wall and
// the ceiling. R_s comes from the last solve: before the first, reflected_a falls back to the
// far ends' form factors alone.
//
// (A_x F(x → r) = A_r F(r → x)), each scaled to an area mean of 1 over a's leaves; a partly
// occluded link counts with its mean, F(a → s), for every leaf, as its visibility from the
// leaf is not known without rays. The links' totals, and so the energy balance, stay those of
// the links themselves; only where within a node their light lands and leaves from changes.
// With uniform radiosity every leaf then gathers what links of its own would bring (the
// furnace), and with uniform importance every leaf sends what links of its own would take.

#include <cstdint>
#include <span>
#include <vector>

#include "hierarchy/hierarchy.h"
#include "links/link_store.h"

namespace penumbra::solver {

struct LeafWeights {
    /// Per node and one past the last: where a leaf's entries start, one per ancestor, by the
    /// ancestor's level (inner nodes have none).
    std::vector<std::uint32_t> offset;
    std::vector<float> receive, emit;
    std::vector<Rgb> receive_reflected;
    /// The same before the scaling to unit means, and a hash of each node's links (its sent
    /// ones only where it is an inner node, the only nodes read): what the
    /// next refinement cycle reuses where neither the leaf nor the ancestor's links changed.
    std::vector<float> raw_receive, raw_emit;
    std::vector<Rgb> raw_reflected;
    std::vector<std::uint64_t> signature;
    /// Whether receive_reflected was weighed by the reflected radiosities of a solve with
    /// these materials; until then (before the first solve, after loading a saved state) the
    /// next weights weigh every entry afresh. Not saved.
    bool reflected_solved = false;

    bool empty() const { return offset.empty(); }
    /// Index of leaf \p x's weights for its ancestor at level \p level.
    std::size_t at(std::uint32_t x, std::int32_t level) const {
        return offset[x] + std::uint32_t(level);
    }
};

/// Link indices grouped by source node, in link order (CSR): the links each node sends through.
struct LinksBySource {
    std::vector<std::uint32_t> start, order;
};
/// \p inner_sources_only: leaves' links are left out (their groups are empty).
LinksBySource index_by_source(const Hierarchy& h, std::span<const Link> links,
                              bool inner_sources_only = false);

/// \brief The weights of every leaf for each of its ancestors: the far ends of the ancestor's
///        element links seen from the leaf's centroid (analytic point form factors, no rays),
///        weighed by their emission and by their reflected part of \p b (node radiosities;
///        \p solved: of a solve, else nothing is known of the reflected light yet). Entries
///        whose leaf and whose ancestor's links are as in \p previous (the last cycle's
///        weights, or none) are taken from it, the reflected ones only if previous weighed
///        them by a solve's radiosities. Parallel over leaves, deterministic.
LeafWeights leaf_weights(const Hierarchy& h, const LinkStore& links, const std::vector<Rgb>& b,
                         bool solved, const LeafWeights& previous);

} // namespace penumbra::solver
