#include "uv_geometry.h"

#include <algorithm>
#include <limits>

namespace penumbra::lightmap {

namespace {

struct Interval {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -std::numeric_limits<double>::infinity();
};

template <typename Points> Interval project(const Points& points, const Vec2& axis) {
    Interval r;
    for (const Vec2& p : points) {
        const double d = dot(p, axis);
        r.lo = std::min(r.lo, d);
        r.hi = std::max(r.hi, d);
    }
    return r;
}

double overlap(const Interval& a, const Interval& b) {
    return std::min(a.hi, b.hi) - std::max(a.lo, b.lo);
}

// The unit normal of edge k of the triangle; zero for a degenerate edge.
Vec2 edge_normal(const Triangle2& t, int k) {
    const Vec2 e = t[std::size_t((k + 1) % 3)] - t[std::size_t(k)];
    const double len = length(e);
    return len > 0 ? Vec2{-e.y / len, e.x / len} : Vec2{};
}

// Keeps the part of the polygon where dot(p, axis) <= limit.
std::vector<Vec2> clip_half_plane(const std::vector<Vec2>& polygon, const Vec2& axis,
                                  double limit) {
    std::vector<Vec2> out;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Vec2& a = polygon[i];
        const Vec2& b = polygon[(i + 1) % polygon.size()];
        const double da = dot(a, axis) - limit, db = dot(b, axis) - limit;
        if (da <= 0)
            out.push_back(a);
        if ((da < 0 && db > 0) || (da > 0 && db < 0))
            out.push_back(a + (b - a) * (da / (da - db)));
    }
    return out;
}

Vec2 closest_on_segment(const Vec2& a, const Vec2& b, const Vec2& p) {
    const Vec2 d = b - a;
    const double dd = dot(d, d);
    const double t = dd > 0 ? std::clamp(dot(p - a, d) / dd, 0.0, 1.0) : 0.0;
    return a + d * t;
}

} // namespace

bool triangles_overlap(const Triangle2& a, const Triangle2& b, double eps) {
    for (const Triangle2* t : {&a, &b})
        for (int k = 0; k < 3; ++k) {
            const Vec2 axis = edge_normal(*t, k);
            if (overlap(project(a, axis), project(b, axis)) <= eps)
                return false;
        }
    return true;
}

bool triangle_overlaps_texel(const Triangle2& t, int x, int y) {
    // Texel coordinates stay below 2^13, where double rounding is far below this margin.
    constexpr double eps = 1e-9;
    const std::array<Vec2, 4> square{Vec2{double(x), double(y)}, Vec2{x + 1.0, double(y)},
                                     Vec2{x + 1.0, y + 1.0}, Vec2{double(x), y + 1.0}};
    for (const Vec2& axis : {Vec2{1, 0}, Vec2{0, 1}})
        if (overlap(project(t, axis), project(square, axis)) <= eps)
            return false;
    for (int k = 0; k < 3; ++k) {
        const Vec2 axis = edge_normal(t, k);
        if (overlap(project(t, axis), project(square, axis)) <= eps)
            return false;
    }
    return true;
}

std::vector<Vec2> clip_to_texel(const Triangle2& t, int x, int y) {
    std::vector<Vec2> polygon(t.begin(), t.end());
    polygon = clip_half_plane(polygon, {1, 0}, x + 1.0);
    polygon = clip_half_plane(polygon, {-1, 0}, -double(x));
    polygon = clip_half_plane(polygon, {0, 1}, y + 1.0);
    return clip_half_plane(polygon, {0, -1}, -double(y));
}

Vec2 closest_point_in_convex(const std::vector<Vec2>& polygon, const Vec2& p) {
    if (polygon.empty())
        return p;
    bool has_positive = false, has_negative = false;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const double o = orient(polygon[i], polygon[(i + 1) % polygon.size()], p);
        has_positive = has_positive || o > 0;
        has_negative = has_negative || o < 0;
    }
    if (polygon.size() >= 3 && !(has_positive && has_negative))
        return p;
    Vec2 best = polygon[0];
    double best_d2 = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Vec2 q = closest_on_segment(polygon[i], polygon[(i + 1) % polygon.size()], p);
        const double d2 = dot(q - p, q - p);
        if (d2 < best_d2) {
            best_d2 = d2;
            best = q;
        }
    }
    return best;
}

Vec3 barycentric(const Triangle2& t, const Vec2& p) {
    const double d = orient(t[0], t[1], t[2]);
    const double b0 = orient(p, t[1], t[2]) / d;
    const double b1 = orient(t[0], p, t[2]) / d;
    return {b0, b1, 1.0 - b0 - b1};
}

std::vector<Vec2> convex_hull(std::vector<Vec2> points) {
    std::sort(points.begin(), points.end(),
              [](const Vec2& a, const Vec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    if (points.size() < 3)
        return points;
    std::vector<Vec2> hull(2 * points.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < points.size(); ++i) { // lower hull
        while (k >= 2 && orient(hull[k - 2], hull[k - 1], points[i]) <= 0)
            --k;
        hull[k++] = points[i];
    }
    for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) { // upper hull
        while (k >= lower && orient(hull[k - 2], hull[k - 1], points[i]) <= 0)
            --k;
        hull[k++] = points[i];
    }
    hull.resize(k - 1);
    return hull;
}

double min_area_rectangle_angle(const std::vector<Vec2>& points) {
    const std::vector<Vec2> hull = convex_hull(points);
    double best_angle = 0, best_area = std::numeric_limits<double>::infinity();
    if (hull.size() < 3)
        return 0; // no area: any orientation packs the same
    for (std::size_t i = 0; i < hull.size(); ++i) {
        const Vec2 e = hull[(i + 1) % hull.size()] - hull[i];
        const double angle = -std::atan2(e.y, e.x);
        const double c = std::cos(angle), s = std::sin(angle);
        Interval u, v;
        for (const Vec2& p : hull) {
            const Vec2 q = rotate(p, c, s);
            u.lo = std::min(u.lo, q.x);
            u.hi = std::max(u.hi, q.x);
            v.lo = std::min(v.lo, q.y);
            v.hi = std::max(v.hi, q.y);
        }
        const double area = (u.hi - u.lo) * (v.hi - v.lo);
        // Strictly smaller by a margin: an axis-aligned rectangle keeps angle 0 against the
        // equal areas of its other edges.
        if (area < best_area * (1 - 1e-12)) {
            best_area = area;
            best_angle = angle;
        }
    }
    return best_angle;
}

} // namespace penumbra::lightmap
