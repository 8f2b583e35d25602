#pragma once
// Exact pixel coverage of a flat polygon seen straight on: the analytic answer of the edge
// refinement tests (the lightmap preview's render_hits and the final gather's render).

#include <utility>
#include <vector>

#include "core/image.h"
#include "core/scene.h"
#include "core/vec.h"

namespace penumbra::test {

/// World-space extent, on the plane z = 0, of pixel column \p pixel of \p count (or of a row,
/// with y flipped, when \p vertical) for a camera on the z axis looking at the origin.
std::pair<double, double> footprint(const Camera& c, int pixel, int count, bool vertical);

/// Area of the axis-aligned box [x0, x1] × [y0, y1] inside the convex polygon \p poly
/// (counter-clockwise, in the plane z = 0).
double area_inside(double x0, double x1, double y0, double y1, const std::vector<Vec3>& poly);

/// The share of pixel (x, y)'s footprint that \p poly covers, for a camera as footprint()'s.
double covered_share(const Camera& c, int x, int y, const std::vector<Vec3>& poly);

/// \brief Green-channel errors of two renders of a lamp of \p radiance (polygon \p lamp)
///        against its exact coverage: worst over every pixel, RMS of every pixel's error
///        over the count of rim pixels (partly covered; the others should be exact).
struct RimErrors {
    int pixels = 0;           ///< rim pixels
    double worst_plain = 0;   ///< largest |error| of \p plain
    double worst_refined = 0; ///< largest |error| of \p refined
    double rms_refined = 0;   ///< RMS error of \p refined per rim pixel
};
RimErrors rim_errors(const Camera& c, const Image& plain, const Image& refined,
                     const std::vector<Vec3>& lamp, double radiance);

} // namespace penumbra::test
