#include "geometry2d.h"

#include <algorithm>
#include <limits>

namespace penumbra::mesher {

double signed_area(const std::vector<Vec2>& polygon) {
    double a = 0;
    for (std::size_t i = 0, n = polygon.size(); i < n; ++i)
        a += cross(polygon[i], polygon[(i + 1) % n]);
    return 0.5 * a;
}

bool point_in_polygon(const Vec2& p, const std::vector<Vec2>& polygon) {
    bool inside = false;
    for (std::size_t i = 0, n = polygon.size(), j = n - 1; i < n; j = i++) {
        const Vec2& a = polygon[i];
        const Vec2& b = polygon[j];
        if ((a.y > p.y) != (b.y > p.y)) {
            const double x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
            if (p.x < x)
                inside = !inside;
        }
    }
    return inside;
}

double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
    const Vec2 d = b - a;
    const double len2 = dot(d, d);
    const double t = len2 > 0 ? std::clamp(dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
    return length(p - (a + d * t));
}

double distance_to_boundary(const Vec2& p, const std::vector<Vec2>& polygon) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0, n = polygon.size(); i < n; ++i)
        best = std::min(best, distance_to_segment(p, polygon[i], polygon[(i + 1) % n]));
    return best;
}

std::vector<Interval> clip_line_to_polygon(const Vec2& p, const Vec2& d, double t0, double t1,
                                           const std::vector<Vec2>& polygon, double margin) {
    // Crossings of the line with the outline, paired even-odd.
    std::vector<double> ts;
    const std::size_t n = polygon.size();
    const Vec2 normal{-d.y, d.x};
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2& a = polygon[i];
        const Vec2& b = polygon[(i + 1) % n];
        const double sa = dot(a - p, normal), sb = dot(b - p, normal);
        if ((sa > 0) == (sb > 0))
            continue;
        const Vec2 x = a + (b - a) * (sa / (sa - sb));
        ts.push_back(dot(x - p, d) / dot(d, d));
    }
    std::sort(ts.begin(), ts.end());
    std::vector<Interval> out;
    for (std::size_t i = 0; i + 1 < ts.size(); i += 2) {
        const double lo = std::max(t0, ts[i] - margin), hi = std::min(t1, ts[i + 1] + margin);
        if (hi > lo)
            out.emplace_back(lo, hi);
    }
    return merge_intervals(std::move(out), 0.0);
}

std::vector<Interval> merge_intervals(std::vector<Interval> intervals, double gap) {
    std::sort(intervals.begin(), intervals.end());
    std::vector<Interval> out;
    for (const Interval& iv : intervals) {
        if (!out.empty() && iv.first <= out.back().second + gap)
            out.back().second = std::max(out.back().second, iv.second);
        else
            out.push_back(iv);
    }
    return out;
}

std::vector<Interval> intersect_intervals(const std::vector<Interval>& a,
                                          const std::vector<Interval>& b) {
    std::vector<Interval> out;
    std::size_t i = 0, j = 0;
    while (i < a.size() && j < b.size()) {
        const double lo = std::max(a[i].first, b[j].first);
        const double hi = std::min(a[i].second, b[j].second);
        if (hi > lo)
            out.emplace_back(lo, hi);
        if (a[i].second < b[j].second)
            ++i;
        else
            ++j;
    }
    return out;
}

namespace {

bool proper_crossing(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, double eps) {
    const double scale = std::max(length(b - a), length(d - c));
    auto side = [&](const Vec2& p, const Vec2& q, const Vec2& r) {
        const double s = cross(q - p, r - p) / std::max(length(q - p), 1e-300);
        return s > eps ? 1 : (s < -eps ? -1 : 0);
    };
    if (scale <= 0)
        return false;
    return side(a, b, c) * side(a, b, d) < 0 && side(c, d, a) * side(c, d, b) < 0;
}

// Whether some point just inside \p a (an edge midpoint moved inwards, or a vertex) lies
// strictly inside \p b.
bool sample_inside(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double eps) {
    const double orientation = signed_area(a) >= 0 ? 1.0 : -1.0;
    for (std::size_t i = 0, n = a.size(); i < n; ++i) {
        const Vec2 p = a[i], q = a[(i + 1) % n];
        const Vec2 e = q - p;
        const double len = length(e);
        if (point_in_polygon(p, b) && distance_to_boundary(p, b) > eps)
            return true;
        if (len <= 4 * eps)
            continue;
        const Vec2 inward = Vec2{-e.y, e.x} * (orientation * 4 * eps / len);
        const Vec2 m = (p + q) * 0.5 + inward;
        if (point_in_polygon(m, b) && distance_to_boundary(m, b) > eps)
            return true;
    }
    return false;
}

} // namespace

bool polygons_overlap(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double eps) {
    for (std::size_t i = 0; i < a.size(); ++i)
        for (std::size_t j = 0; j < b.size(); ++j)
            if (proper_crossing(a[i], a[(i + 1) % a.size()], b[j], b[(j + 1) % b.size()], eps))
                return true;
    return sample_inside(a, b, eps) || sample_inside(b, a, eps);
}

} // namespace penumbra::mesher
