#include "memory/memory_use.h"

#include <fmt/format.h>

#include "core/memory.h"

namespace penumbra::solver {

double system_bytes(const SystemSize& size) {
    return double(size.nodes) * double(k_bytes_per_node) +
           double(size.element_links) * double(k_bytes_per_element_link) +
           double(size.cluster_links) * double(k_bytes_per_cluster_link) +
           double(size.light_links) * double(k_bytes_per_light_link);
}

void check_system_memory(std::uint64_t limit_bytes, const SystemSize& size, std::string_view when,
                         std::string_view advice) {
    check_memory(limit_bytes,
                 fmt::format("solve: {} would make {:.3g} links over {:.3g} nodes, which", when,
                             double(size.element_links + size.cluster_links + size.light_links),
                             double(size.nodes)),
                 system_bytes(size), advice);
}

} // namespace penumbra::solver
