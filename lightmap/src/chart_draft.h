#pragma once
// A chart under construction: a set of input-mesh triangles and their flattened coordinates.

#include <array>
#include <cstdint>
#include <vector>

#include "input_mesh.h"
#include "uv_geometry.h"

namespace penumbra::lightmap {

struct ChartDraft {
    std::vector<std::uint32_t> triangles;              ///< InputMesh triangles, ascending
    std::vector<std::uint32_t> vertices;               ///< welded vertices, in order of first use
    std::vector<std::array<std::uint32_t, 3>> corners; ///< per triangle: indices into vertices
    std::vector<Vec2> uv;                              ///< per vertex, metres

    Triangle2 uv_triangle(std::size_t i) const {
        return {uv[corners[i][0]], uv[corners[i][1]], uv[corners[i][2]]};
    }
};

/// \brief A draft of the given triangles with its vertex numbering; uv all zero.
ChartDraft make_draft(const InputMesh& mesh, std::vector<std::uint32_t> triangles);

/// \brief Orthogonal projection onto the plane of unit \p normal (Frame::from_normal axes):
///        lengths and areas of the plane kept exactly.
void project_onto_plane(const InputMesh& mesh, const Vec3& normal, ChartDraft& draft);

/// \brief Least squares conformal map (Lévy et al. 2002) with CGAL, scaled so the chart's uv
///        area equals its 3D area and mirrored if it came out clockwise. False when CGAL
///        cannot build or solve it (not a manifold with a border).
bool flatten_lscm(const InputMesh& mesh, ChartDraft& draft);

/// \brief uv_layout_valid() of a generated draft (no mirrored triangles allowed).
bool draft_valid(const InputMesh& mesh, const ChartDraft& draft);

} // namespace penumbra::lightmap
