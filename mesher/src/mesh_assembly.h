#pragma once
// Turns triangulated surfaces into the patches, vertices and elements of a RadiosityMesh.

#include <vector>

#include "core/context.h"
#include "core/mesh.h"
#include "core/scene.h"
#include "surface_cdt.h"
#include "surfaces.h"

namespace penumbra::mesher {

/// \brief Appends the \p surfaces in order, each as a front patch and, for two-sided
///        materials, a back patch (reversed winding), each with its own vertices; twins for
///        faces present on both sides; one geometry element per face that is visible on some
///        side (the front one when it exists); and each surface's SurfaceInfo. Sides without
///        faces get no patch. The arrays are sized once and filled in parallel, in the same
///        order as appending the surfaces one by one.
void append_surfaces(RadiosityMesh& mesh, const Scene& scene, const std::vector<Surface>& surfaces,
                     const std::vector<SurfaceTriangulation>& tris, const Context& ctx);

/// \brief Checks with OpenMesh that every patch is a 2-manifold triangle mesh (each edge used
///        at most twice, consistently oriented, no T-vertex possible); throws InternalError
///        naming the first patch (lowest id) that is not. Patches are checked in parallel.
void check_patches(const RadiosityMesh& mesh, const Context& ctx);

} // namespace penumbra::mesher
