#pragma once
// Turns triangulated surfaces into the patches, vertices and elements of a RadiosityMesh.

#include "core/mesh.h"
#include "core/scene.h"
#include "surface_cdt.h"
#include "surfaces.h"

namespace penumbra::mesher {

/// \brief Appends surface \p s: a front patch and, for two-sided materials, a back patch
///        (reversed winding), each with its own vertices; twins for faces present on both
///        sides; one geometry element per face that is visible on some side (the front one
///        when it exists); and the surface's SurfaceInfo. Sides without faces get no patch.
void append_surface(RadiosityMesh& mesh, const Scene& scene, const Surface& s,
                    const SurfaceTriangulation& tri);

/// \brief Checks with OpenMesh that every patch is a 2-manifold triangle mesh (each edge used
///        at most twice, consistently oriented, no T-vertex possible); throws InternalError.
void check_patches(const RadiosityMesh& mesh);

} // namespace penumbra::mesher
