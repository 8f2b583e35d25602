#pragma once
// Mesher v2 (issue #5): scene polygons → conforming radiosity mesh, split along contacts and
// along the shadow boundaries of the sources (discontinuity meshing), hidden parts left out.

#include "core/context.h"
#include "core/mesh.h"
#include "core/scene.h"

namespace penumbra::mesher {

/// \brief Builds the radiosity mesh of \p scene (settings: Scene::mesher, documented in
///        docs/scene-format.md).
///        Planar polygons become one surface each; non-planar polygons are fan-triangulated
///        from their first vertex, each fan triangle a surface of its own. Near-contacts are
///        closed, surfaces are split where others touch or cross them, and parts hidden under
///        or inside other geometry get no elements (their area is in RadiosityMesh::surfaces).
///        The shadow boundaries of emissive polygons and point lights are inserted as element
///        edges and listed in RadiosityMesh::discontinuities. Each surface is a CGAL
///        constrained Delaunay triangulation refined to the size bound and a 20.7° minimum
///        angle. Two-sided materials give a front and a back patch with separate vertices.
///        Deterministic: the result does not depend on ctx.threads.
/// \throws InputError for a surface that cannot be triangulated (naming it); degenerate
///         polygons (zero area, collinear vertices) are skipped with a warning instead.
RadiosityMesh build_mesh(const Scene& scene, const Context& ctx);

} // namespace penumbra::mesher
