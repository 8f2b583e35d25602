#pragma once
// Exact direct irradiance from a uniform Lambertian polygon partly hidden by convex blockers:
// the source polygon clipped by each blocker's shadow as seen from the receiving point
// (inclusion–exclusion), integrated with Lambert's contour formula.

#include <vector>

#include "core/vec.h"

namespace penumbra::test {

/// \brief Irradiance (W/m²) at \p p, normal \p n, from the convex planar polygon \p light of
///        radiance \p radiance (W/(sr·m²)), behind up to three convex \p blockers given by
///        their vertices. Blocker points at or below p's tangent plane are lifted just above
///        it. The light must be entirely above that plane.
double exact_irradiance(const Vec3& p, const Vec3& n, const std::vector<Vec3>& light,
                        double radiance, const std::vector<std::vector<Vec3>>& blockers);

/// Lambert's formula: irradiance at p (normal n) from an unoccluded polygon of unit radiance.
double polygon_irradiance(const Vec3& p, const Vec3& n, const std::vector<Vec3>& polygon);

} // namespace penumbra::test
