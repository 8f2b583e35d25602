#pragma once
// What a hierarchical solve holds per node and per link (issue #32, docs/memory.md), summed
// from the element types of the real arrays so that a changed type changes the figure, and
// the check refinement makes against the memory limit before each pass makes its links.
// solver.epsilon 1e-12 grew the links without bound; the count of a pass is known only
// once the pass has weighed every link, so the limit is checked there, not ahead.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hierarchy/hierarchy.h"
#include "hierarchy/leaf_weights.h"
#include "iteration/transport.h"
#include "links/link_store.h"

namespace penumbra::solver {

namespace memory_detail {
template <typename Vector> constexpr std::size_t item = sizeof(typename Vector::value_type);
} // namespace memory_detail

/// Bytes of the Hierarchy's arrays per node.
inline constexpr std::size_t k_hierarchy_bytes_per_node = [] {
    using namespace memory_detail;
    using H = Hierarchy;
    return item<decltype(H::triangle)> + item<decltype(H::normal)> + item<decltype(H::area)> +
           item<decltype(H::patch)> + item<decltype(H::parent)> + item<decltype(H::first_child)> +
           item<decltype(H::level)> + item<decltype(H::emission)> + item<decltype(H::reflectance)> +
           item<decltype(H::transmittance)> + item<decltype(H::twin)> + item<decltype(H::opaque)>;
}();

/// Bytes of NodeValues' per-node arrays (radiosities, irradiances, ranges; the transmitted
/// array counted as if some surface transmits), the links' receiver index and the leaf
/// weights' per-node part.
inline constexpr std::size_t k_values_bytes_per_node = [] {
    using namespace memory_detail;
    using V = NodeValues;
    return item<decltype(V::b)> + item<decltype(V::gathered_direct)> +
           item<decltype(V::gathered_indirect)> + item<decltype(V::h_direct)> +
           item<decltype(V::h_indirect)> + item<decltype(V::b_lo)> + item<decltype(V::b_hi)> +
           item<decltype(V::b_range)> + item<decltype(V::link_direct)> +
           item<decltype(V::link_indirect)> + item<decltype(V::extra_direct)> +
           item<decltype(V::extra_indirect)> + item<decltype(V::b_emit)> +
           item<decltype(V::transmitted)> + 2 * sizeof(std::uint32_t) /* receiver offsets */ +
           item<decltype(LeafWeights::offset)> + item<decltype(LeafWeights::signature)>;
}();

/// Levels of ancestors a leaf's weights are counted for: a leaf has one entry per ancestor, of
/// four floats (LeafWeights::receive, emit and their raw values) and two RGB values
/// (receive_reflected and its raw value).
inline constexpr std::size_t k_weight_levels = 8;

/// Bytes per node in all: a growing std::vector briefly holds its old block and its new one,
/// hence twice the arrays.
inline constexpr std::size_t k_bytes_per_node =
    2 * (k_hierarchy_bytes_per_node + k_values_bytes_per_node +
         k_weight_levels * (4 * memory_detail::item<decltype(LeafWeights::receive)> +
                            2 * memory_detail::item<decltype(LeafWeights::receive_reflected)>));

/// Bytes per element link: the link, and refinement's per-link bytes (its decision and
/// whether its oracle said keep).
inline constexpr std::size_t k_bytes_per_element_link = sizeof(Link) + 2;
/// Bytes per cluster link: the link and its keep flag.
inline constexpr std::size_t k_bytes_per_cluster_link = sizeof(ClusterLink) + 1;
/// Bytes per light link: a vector's, which refinement copies into a new one each pass.
inline constexpr std::size_t k_bytes_per_light_link = 2 * sizeof(LightLink);

/// \brief How big a hierarchical system is, or is about to be.
struct SystemSize {
    std::size_t nodes = 0, element_links = 0, cluster_links = 0, light_links = 0;
};

/// \brief Bytes of a system of \p size (docs/memory.md).
double system_bytes(const SystemSize& size);

/// What to change when refinement outgrows the limit.
inline constexpr std::string_view k_refinement_advice =
    "use a larger solver.epsilon (--epsilon) or solver.min_area (--min-area)";

/// \brief Throws ConfigError when a system of \p size would exceed \p limit_bytes (0 = no
///        limit); \p when says at which step, \p advice which settings to change (the
///        message adds --max-memory).
void check_system_memory(std::uint64_t limit_bytes, const SystemSize& size, std::string_view when,
                         std::string_view advice = k_refinement_advice);

} // namespace penumbra::solver
