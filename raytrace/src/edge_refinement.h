#pragma once
// Sampling a pixel again where an edge of high contrast crosses it (a lamp's rim): the
// lightmap preview's render_hits() (issue #29) and the final gather (issue #28) share which
// pixels, how many samples and where. Internal to raytrace/.

#include "raytrace/raytrace.h"

#include "core/rng.h"
#include "core/vec.h"

#include <span>
#include <vector>

namespace penumbra::raytrace {

/// n² multi-jittered points of [0, 1)² (Chiu, Shirley and Wang 1994): one in each of the n × n
/// cells and, along each axis, one in each of the n² fine strata, so an edge nearly parallel to
/// an axis is placed to 1/n² of the square, where n × n jittered strata place it to 1/n.
std::vector<Vec2> multi_jittered(int n, Pcg32& rng);

/// Samples per axis for a pixel whose first samples span \p range: about range / tolerance
/// samples, capped; 0 without refinement.
int refined_strata(double range, const EdgeRefinement& refine);

/// The largest of \p range (per pixel, rows of \p width) over pixel (x, y) and its eight
/// neighbours: a rim that only clips a pixel's corner may miss all its first samples but not
/// its neighbours'.
double largest_around(std::span<const double> range, int width, int height, int x, int y);

} // namespace penumbra::raytrace
