#pragma once
// Checks of a whole lightmap layout that several tests share.

#include <vector>

#include "lightmap/atlas.h"
#include "lightmap/charts.h"
#include "lightmap/texels.h"

namespace penumbra::test {

/// Distance from \p p to the triangle abc (closest point by regions, after Ericson 2005 §5.1.5).
double distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// Every chart in [padding, size − padding)² of its atlas, no texel of one chart within
/// \p padding texels (Chebyshev) of another's, and every texel's centre sample on its
/// triangle (1e-6 m) and inside its texel (1e-9 texel).
void expect_valid_layout(const lightmap::Charts& charts, const lightmap::AtlasLayout& layout,
                         const std::vector<lightmap::AtlasTexels>& atlases);

/// Generated charts: every triangle positive (counter-clockwise) in atlas texel coordinates.
void expect_no_flips(const lightmap::Charts& charts, const lightmap::AtlasLayout& layout);

} // namespace penumbra::test
