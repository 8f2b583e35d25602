#pragma once
// 2D helpers of the mesher: every planar surface is meshed in its own 2D frame (metres).

#include <cmath>
#include <utility>
#include <vector>

#include "core/vec.h"

namespace penumbra::mesher {

/// A 2D segment.
struct Segment2 {
    Vec2 a, b;
    double length() const { return penumbra::length(b - a); }
};

/// Parameter interval [lo, hi] along a line.
using Interval = std::pair<double, double>;

/// Signed area, positive for counter-clockwise polygons.
double signed_area(const std::vector<Vec2>& polygon);

/// Even-odd point-in-polygon test (points on the boundary may go either way).
bool point_in_polygon(const Vec2& p, const std::vector<Vec2>& polygon);

/// Distance from \p p to the segment [a, b].
double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b);

/// Distance from \p p to the polygon's boundary.
double distance_to_boundary(const Vec2& p, const std::vector<Vec2>& polygon);

/// The parts of the line p + t·d, t in [t0, t1], inside \p polygon (even-odd), widened by
/// \p margin (in t units) at each end so that segments ending on the outline stay whole.
std::vector<Interval> clip_line_to_polygon(const Vec2& p, const Vec2& d, double t0, double t1,
                                           const std::vector<Vec2>& polygon, double margin);

/// Sorts and merges intervals that overlap or are closer than \p gap.
std::vector<Interval> merge_intervals(std::vector<Interval> intervals, double gap);

/// Intersection of two sorted, disjoint interval lists.
std::vector<Interval> intersect_intervals(const std::vector<Interval>& a,
                                          const std::vector<Interval>& b);

/// True if the interiors of the two polygons overlap (a proper edge crossing, or a vertex of
/// one strictly inside the other). Polygons that only share edges or vertices do not.
bool polygons_overlap(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double eps);

} // namespace penumbra::mesher
