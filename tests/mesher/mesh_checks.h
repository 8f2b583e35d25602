#pragma once
// Checks on RadiosityMesh shared by the mesher tests.

#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "core/scene.h"

namespace penumbra::test {

/// Longest element edge of the whole mesh.
double longest_edge(const RadiosityMesh& mesh);

/// Sum of element areas of one patch.
double patch_area(const RadiosityMesh& mesh, std::uint32_t patch);

/// Smallest angle (degrees) of the elements of \p patch.
double smallest_angle_deg(const RadiosityMesh& mesh, std::uint32_t patch);

/// The patch of polygon \p polygon's front (or back) side, or -1.
std::int32_t find_patch(const RadiosityMesh& mesh, std::uint32_t polygon, bool back = false);

/// Conformity of one patch: every half-edge is used once, and the boundary (half-edges without
/// an opposite) has total length \p boundary_length (a T-vertex would leave extra boundary).
void expect_conforming(const RadiosityMesh& mesh, std::uint32_t patch, double boundary_length);

/// Whether the segment [a, b] is covered by element edges of \p patch whose endpoints lie
/// within \p tol of the segment's line (checked at \p samples points along it).
bool segment_on_element_edges(const RadiosityMesh& mesh, std::uint32_t patch, const Vec3& a,
                              const Vec3& b, double tol, int samples = 50);

/// Whether some element of \p patch has points strictly on both sides of the line through
/// a and b (in the patch plane) within the segment's extent: an element straddling it.
bool element_straddles(const RadiosityMesh& mesh, std::uint32_t patch, const Vec3& a, const Vec3& b,
                       double tol);

} // namespace penumbra::test
