#pragma once
// Mesher v1: scene polygons → conforming radiosity mesh (OpenMesh), uniformly refined to the
// scene's maximum element edge length. Discontinuity meshing comes with issue #5.

#include "core/context.h"
#include "core/mesh.h"
#include "core/scene.h"

namespace penumbra::mesher {

/// \brief Builds the radiosity mesh of \p scene.
///        Planar polygons become one surface each; non-planar polygons are fan-triangulated
///        from their first vertex, each fan triangle a surface of its own. Quadrilaterals are
///        meshed as structured grids, other polygons by ear clipping followed by longest-edge
///        bisection, so that no edge exceeds MesherSettings::max_edge_length. Two-sided
///        materials give a front and a back patch with separate vertices.
/// \throws InputError for degenerate polygons (naming the polygon's source).
RadiosityMesh build_mesh(const Scene& scene, const Context& ctx);

} // namespace penumbra::mesher
