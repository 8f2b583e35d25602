#pragma once
// The sky's direct light at the vertices of the hierarchical solver's leaf mesh: gathered at
// the vertices of the input mesh (its roots) and interpolated linearly over each root to the
// vertices refinement added. The sky's light varies smoothly at the input mesh's element size
// (no hard shadows), and the gather is the costliest part of a daylight bake, which refinement
// for the sun's patch or interreflection would multiply (docs/daylight.md).

#include <cstdint>
#include <span>
#include <vector>

#include "core/mesh.h"
#include "core/sky.h"
#include "core/visibility.h"
#include "kernels/element_rows.h"

namespace penumbra::solver {

/// \brief The sky's direct irradiance (W/m²) at each vertex of \p leaves, whose element e lies
///        in element leaf_root[e] of \p roots. Root vertices gather at their
///        vertex_gather_positions with k_sky_vertex_quadrature from the stream (sky_visibility,
///        v, 3, vertex_visibility, seed), as make_solution's own gathers do.
std::vector<Rgb> sky_at_vertices(const Sky& sky, const RadiosityMesh& roots,
                                 const ElementGeometry& root_geo, const RadiosityMesh& leaves,
                                 std::span<const std::uint32_t> leaf_root,
                                 const VisibilityQuery& visibility, std::uint64_t seed);

} // namespace penumbra::solver
