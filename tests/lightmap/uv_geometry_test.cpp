// The 2D helpers behind chart checks, packing and rasterization, against values worked out
// by hand.

#include <cmath>

#include <gtest/gtest.h>

#include "uv_geometry.h"

namespace penumbra::lightmap {
namespace {

double polygon_area(const std::vector<Vec2>& p) {
    double a = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
        a += cross(p[i], p[(i + 1) % p.size()]);
    return 0.5 * a;
}

TEST(UvGeometry, MinAreaRectangleOfARotatedRectangleUndoesTheRotation) {
    const double c = std::cos(0.3), s = std::sin(0.3);
    std::vector<Vec2> points;
    for (const Vec2& p : {Vec2{0, 0}, Vec2{3, 0}, Vec2{3, 1}, Vec2{0, 1}, Vec2{1.5, 0.5}})
        points.push_back(rotate(p, c, s));
    const double angle = min_area_rectangle_angle(points);
    Vec2 lo{1e9, 1e9}, hi{-1e9, -1e9};
    for (const Vec2& p : points) {
        const Vec2 q = rotate(p, std::cos(angle), std::sin(angle));
        lo = {std::min(lo.x, q.x), std::min(lo.y, q.y)};
        hi = {std::max(hi.x, q.x), std::max(hi.y, q.y)};
    }
    EXPECT_NEAR((hi.x - lo.x) * (hi.y - lo.y), 3.0, 1e-12);
    // An axis-aligned rectangle keeps its orientation.
    EXPECT_EQ(min_area_rectangle_angle({{0, 0}, {3, 0}, {3, 1}, {0, 1}}), 0.0);
}

TEST(UvGeometry, ClippingToATexelKeepsTheOverlap) {
    const Triangle2 t{Vec2{0, 0}, Vec2{2, 0}, Vec2{0, 2}};
    EXPECT_NEAR(polygon_area(clip_to_texel(t, 0, 0)), 1.0, 1e-15);
    EXPECT_NEAR(polygon_area(clip_to_texel(t, 1, 0)), 0.5, 1e-15);
    EXPECT_NEAR(polygon_area(clip_to_texel(t, 1, 1)), 0.0, 1e-15);
    EXPECT_TRUE(triangle_overlaps_texel(t, 1, 0));
    EXPECT_FALSE(triangle_overlaps_texel(t, 1, 1));  // touches its corner only
    EXPECT_FALSE(triangle_overlaps_texel(t, -1, 0)); // shares an edge only
}

TEST(UvGeometry, TrianglesSharingAnEdgeDoNotOverlap) {
    const Triangle2 a{Vec2{0, 0}, Vec2{1, 0}, Vec2{0, 1}};
    const Triangle2 b{Vec2{1, 0}, Vec2{1, 1}, Vec2{0, 1}};
    const Triangle2 c{Vec2{0.2, 0.2}, Vec2{1, 0.2}, Vec2{0.2, 1}};
    EXPECT_FALSE(triangles_overlap(a, b, 1e-12));
    EXPECT_TRUE(triangles_overlap(a, c, 1e-12));
    EXPECT_TRUE(triangles_overlap(b, c, 1e-12));
    const Triangle2 mirrored{Vec2{0.2, 0.2}, Vec2{0.2, 1}, Vec2{1, 0.2}};
    EXPECT_TRUE(triangles_overlap(a, mirrored, 1e-12));
}

TEST(UvGeometry, ClosestPointAndBarycentricCoordinates) {
    const std::vector<Vec2> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const Vec2 inside = closest_point_in_convex(square, {0.3, 0.4});
    EXPECT_EQ(inside.x, 0.3);
    EXPECT_EQ(inside.y, 0.4);
    const Vec2 edge = closest_point_in_convex(square, {2, 0.5});
    EXPECT_NEAR(edge.x, 1, 1e-15);
    EXPECT_NEAR(edge.y, 0.5, 1e-15);
    const Vec2 corner = closest_point_in_convex(square, {-1, -2});
    EXPECT_NEAR(corner.x, 0, 1e-15);
    EXPECT_NEAR(corner.y, 0, 1e-15);
    const Vec3 b = barycentric({Vec2{0, 0}, Vec2{2, 0}, Vec2{0, 2}}, {0.5, 0.5});
    EXPECT_NEAR(b.x, 0.5, 1e-15);
    EXPECT_NEAR(b.y, 0.25, 1e-15);
    EXPECT_NEAR(b.z, 0.25, 1e-15);
}

} // namespace
} // namespace penumbra::lightmap
