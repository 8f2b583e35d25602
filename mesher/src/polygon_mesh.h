#pragma once
// Triangulation of one planar surface into a conforming triangle mesh no edge of which is
// longer than a given length.

#include <array>
#include <cstdint>
#include <vector>

#include "core/vec.h"

namespace penumbra::mesher {

struct SurfaceMesh {
    std::vector<Vec3> points;
    std::vector<std::array<std::uint32_t, 3>> triangles; ///< CCW around the surface normal
};

/// \brief Meshes the planar polygon \p outline (CCW around \p normal) so that no edge is longer
///        than \p max_edge. Convex quadrilaterals become structured grids, triangles are split
///        into k² congruent triangles, other polygons are ear-clipped and refined by
///        longest-edge bisection (OpenMesh). Returns an empty mesh if ear clipping fails.
SurfaceMesh mesh_planar_polygon(const std::vector<Vec3>& outline, const Vec3& normal,
                                double max_edge);

/// Newell's normal of a polygon (not normalised: its length is twice the area for planar ones).
Vec3 newell_normal(const std::vector<Vec3>& outline);

} // namespace penumbra::mesher
