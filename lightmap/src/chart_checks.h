#pragma once
// Checks of a flattened chart: every triangle keeps its orientation (no flips) and no two
// triangles overlap.

#include <vector>

#include "uv_geometry.h"

namespace penumbra::lightmap {

/// \brief True if every triangle has positive uv area (or, with \p allow_mirrored, non-zero
///        area of either sign) above 1e-10 × its 3D area \p area_m2, and no two triangles'
///        interiors overlap (a uniform grid finds the candidate pairs).
bool uv_layout_valid(const std::vector<Triangle2>& uv, const std::vector<double>& area_m2,
                     bool allow_mirrored);

} // namespace penumbra::lightmap
