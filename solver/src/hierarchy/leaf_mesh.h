#pragma once
// The output mesh of hierarchical radiosity: the leaves of the element hierarchy, made
// conforming (no T-vertices) by fanning every leaf that has hanging vertices on its edges
// around its centroid.

#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "hierarchy/hierarchy.h"

namespace penumbra::solver {

struct LeafMesh {
    RadiosityMesh mesh;
    std::vector<std::uint32_t> element_node; ///< hierarchy node of each output element
};

/// \brief Builds the leaf mesh. Front and back leaves must be twins (subdivided together,
///        Hierarchy::twin).
LeafMesh build_leaf_mesh(const RadiosityMesh& base, const Hierarchy& h);

} // namespace penumbra::solver
