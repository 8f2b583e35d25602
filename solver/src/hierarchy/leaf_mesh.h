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
    /// Empty when no root was subdivided: the base mesh is then the leaf mesh (of()).
    RadiosityMesh mesh;
    std::vector<std::uint32_t> element_node; ///< hierarchy node of each output element
    bool subdivided = false;

    /// \brief The mesh the leaf elements are: mesh, or \p base where nothing was subdivided.
    const RadiosityMesh& of(const RadiosityMesh& base) const { return subdivided ? mesh : base; }
};

/// \brief Builds the leaf mesh. Front and back leaves must be twins (subdivided together,
///        Hierarchy::twin).
LeafMesh build_leaf_mesh(const RadiosityMesh& base, const Hierarchy& h);

/// \brief The leaves of \p h as elements: build_leaf_mesh() where a root was subdivided, else
///        \p base's own elements (no copy: LeafMesh::of()).
LeafMesh leaf_elements(const RadiosityMesh& base, const Hierarchy& h);

} // namespace penumbra::solver
