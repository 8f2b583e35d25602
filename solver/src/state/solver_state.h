#pragma once
// The saved state of a hierarchical solve (issue #4: "what must be recomputed when a material
// changes"): the element hierarchy, every link with its form factor and visibility, and the
// radiosities. Reflectances and emissions are not part of it: a re-solve takes them from the
// new scene, keeps the links, re-runs the oracle on them (new radiosities may need finer
// links) and iterates from the old radiosities.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/mesh.h"
#include "hierarchy/hierarchy.h"
#include "hierarchy/leaf_weights.h"
#include "links/link_store.h"
#include "solver/solver.h"

namespace penumbra::solver {

struct HierarchicalState {
    std::uint64_t mesh_hash = 0; ///< of the input mesh's geometry (mesh_geometry_hash)
    bool clustered = false;
    Hierarchy hierarchy;
    MappedArray<Link> links;
    MappedArray<ClusterLink> cluster_links;
    std::vector<Rgb> radiosity; ///< per node
    LeafWeights weights;        ///< of the saved links (geometry only: reused as they are)
};

/// The checksum that ends a state file, of all the bytes before it (the fuzz target fixes it up
/// so that corrupt contents reach the reader's other checks).
std::uint64_t state_checksum(std::string_view bytes);

/// Hash of the elements' vertices, patches and twins: equal meshes, equal hashes.
std::uint64_t mesh_geometry_hash(const RadiosityMesh& mesh);

} // namespace penumbra::solver
