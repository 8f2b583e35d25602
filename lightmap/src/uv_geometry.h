#pragma once
// 2D geometry of chart coordinates: orientation, triangle overlap and clipping, closest points,
// convex hulls and minimum-area bounding rectangles.

#include <array>
#include <cmath>
#include <vector>

#include "core/vec.h"

namespace penumbra::lightmap {

using Triangle2 = std::array<Vec2, 3>;

/// Twice the signed area: positive when a, b, c turn counter-clockwise (x right, y up).
inline double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
    return cross(b - a, c - a);
}

/// Signed area of a triangle.
inline double signed_area(const Triangle2& t) {
    return 0.5 * orient(t[0], t[1], t[2]);
}

/// True if the interiors of the two triangles overlap by more than \p eps along every
/// separating axis (either orientation); triangles that only share edges or vertices do not.
bool triangles_overlap(const Triangle2& a, const Triangle2& b, double eps);

/// True if the triangle and the axis-aligned square [x, x + 1] × [y, y + 1] share interior.
bool triangle_overlaps_texel(const Triangle2& t, int x, int y);

/// The triangle clipped to the square [x, x + 1] × [y, y + 1] (Sutherland–Hodgman); empty if
/// they do not overlap.
std::vector<Vec2> clip_to_texel(const Triangle2& t, int x, int y);

/// The point of the convex polygon (either orientation) nearest to \p p.
Vec2 closest_point_in_convex(const std::vector<Vec2>& polygon, const Vec2& p);

/// Barycentric coordinates of \p p in \p t (not clamped).
Vec3 barycentric(const Triangle2& t, const Vec2& p);

/// Convex hull, counter-clockwise, without collinear points (Andrew's monotone chain).
std::vector<Vec2> convex_hull(std::vector<Vec2> points);

/// The rotation angle (radians) that makes the minimum-area bounding rectangle of the points
/// axis-aligned: rotating by it puts one hull edge on the x axis (Freeman & Shapira 1975).
double min_area_rectangle_angle(const std::vector<Vec2>& points);

/// \p p rotated counter-clockwise by the angle whose cosine and sine are given.
inline Vec2 rotate(const Vec2& p, double c, double s) {
    return {c * p.x - s * p.y, s * p.x + c * p.y};
}

} // namespace penumbra::lightmap
