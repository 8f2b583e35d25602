#include "constraint_cleanup.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <tuple>
#include <unordered_map>

#include "core/disjoint_sets.h"

namespace penumbra::mesher {

namespace {

double distance_to_line(const Vec2& p, const Segment2& s) {
    const Vec2 d = s.b - s.a;
    const double len = length(d);
    return len > 0 ? std::abs(cross(d, p - s.a)) / len : length(p - s.a);
}

// The shorter segment lies on the longer one's line, and they are nearly parallel.
bool collinear(const Segment2& s, const Segment2& t, double tol) {
    const Segment2& longer = s.length() >= t.length() ? s : t;
    const Segment2& shorter = s.length() >= t.length() ? t : s;
    const double sine = std::abs(cross(longer.b - longer.a, shorter.b - shorter.a)) /
                        (longer.length() * shorter.length());
    return sine < 1e-2 && distance_to_line(shorter.a, longer) <= tol &&
           distance_to_line(shorter.b, longer) <= tol;
}

// Parameter interval of \p t projected on \p s's line, in units of s's length.
Interval project(const Segment2& t, const Segment2& s) {
    const Vec2 d = s.b - s.a;
    const double len2 = dot(d, d);
    const double u = dot(t.a - s.a, d) / len2, v = dot(t.b - s.a, d) / len2;
    return {std::min(u, v), std::max(u, v)};
}

/// Snaps points to the nearest anchor within a distance, else to the nearest earlier point,
/// with a hash grid.
class PointSnapper {
public:
    explicit PointSnapper(double tol) : tol_(tol) {}
    void add_anchor(const Vec2& p) {
        const auto [cx, cy] = cell(p);
        grid_[key(cx, cy)].push_back({p, true});
    }
    Vec2 snap(const Vec2& p) {
        const auto [cx, cy] = cell(p);
        const Entry* best = nullptr;
        double best_d = tol_;
        for (std::int64_t dx = -1; dx <= 1; ++dx)
            for (std::int64_t dy = -1; dy <= 1; ++dy) {
                auto it = grid_.find(key(cx + dx, cy + dy));
                if (it == grid_.end())
                    continue;
                for (const Entry& q : it->second) {
                    const double d = length(q.p - p);
                    const bool better = !best || (q.anchor && !best->anchor) ||
                                        (q.anchor == best->anchor && d < best_d);
                    if (d <= tol_ && better) {
                        best = &q;
                        best_d = d;
                    }
                }
            }
        if (best)
            return best->p;
        grid_[key(cx, cy)].push_back({p, false});
        return p;
    }

private:
    struct Entry {
        Vec2 p;
        bool anchor;
    };
    std::pair<std::int64_t, std::int64_t> cell(const Vec2& p) const {
        return {std::int64_t(std::floor(p.x / tol_)), std::int64_t(std::floor(p.y / tol_))};
    }
    static std::uint64_t key(std::int64_t x, std::int64_t y) {
        return (std::uint64_t(x) * 0x9E3779B97F4A7C15ull) ^ std::uint64_t(y);
    }
    double tol_;
    std::unordered_map<std::uint64_t, std::vector<Entry>> grid_;
};

bool boxes_near(const Segment2& s, const Segment2& t, double snap) {
    return std::min(s.a.x, s.b.x) <= std::max(t.a.x, t.b.x) + snap &&
           std::min(t.a.x, t.b.x) <= std::max(s.a.x, s.b.x) + snap &&
           std::min(s.a.y, s.b.y) <= std::max(t.a.y, t.b.y) + snap &&
           std::min(t.a.y, t.b.y) <= std::max(s.a.y, s.b.y) + snap;
}

// The parts of s not lying on any of the \p fixed segments.
std::vector<Segment2> subtract_fixed(const Segment2& s, const std::vector<Segment2>& fixed,
                                     double snap, double merge) {
    const double len = s.length();
    std::vector<Interval> covered;
    for (const Segment2& f : fixed)
        if (boxes_near(s, f, merge) && collinear(s, f, merge))
            covered.push_back(project(f, s));
    covered = merge_intervals(std::move(covered), snap / len);
    std::vector<Segment2> out;
    double from = 0;
    auto emit = [&](double lo, double hi) {
        if ((hi - lo) * len > 4 * snap)
            out.push_back({s.a + (s.b - s.a) * lo, s.a + (s.b - s.a) * hi});
    };
    for (const Interval& c : covered) {
        emit(from, std::min(1.0, c.first));
        from = std::max(from, c.second);
    }
    emit(from, 1.0);
    return out;
}

} // namespace

std::vector<Segment2> merge_collinear(const std::vector<Segment2>& segments, double snap) {
    const std::size_t n = segments.size();
    std::vector<std::size_t> by_x(n);
    std::iota(by_x.begin(), by_x.end(), 0);
    auto min_x = [&](std::size_t i) { return std::min(segments[i].a.x, segments[i].b.x); };
    auto max_x = [&](std::size_t i) { return std::max(segments[i].a.x, segments[i].b.x); };
    std::sort(by_x.begin(), by_x.end(), [&](std::size_t a, std::size_t b) {
        return min_x(a) < min_x(b) || (min_x(a) == min_x(b) && a < b);
    });
    DisjointSets groups(n);
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t i = by_x[k];
        for (std::size_t m = k + 1; m < n && min_x(by_x[m]) <= max_x(i) + snap; ++m) {
            const std::size_t j = by_x[m];
            if (!boxes_near(segments[i], segments[j], snap) ||
                !collinear(segments[i], segments[j], snap))
                continue;
            const Segment2& ref =
                segments[i].length() >= segments[j].length() ? segments[i] : segments[j];
            const Interval a = project(segments[i], ref), b = project(segments[j], ref);
            if (std::max(a.first, b.first) <= std::min(a.second, b.second) + snap / ref.length())
                groups.unite(std::uint32_t(i), std::uint32_t(j));
        }
    }
    std::vector<Segment2> out;
    std::vector<std::vector<std::size_t>> members(n);
    for (std::size_t i = 0; i < n; ++i)
        members[groups.find(std::uint32_t(i))].push_back(i);
    for (std::size_t g = 0; g < n; ++g) {
        if (members[g].empty())
            continue;
        std::size_t longest = members[g][0];
        for (std::size_t i : members[g])
            if (segments[i].length() > segments[longest].length())
                longest = i;
        const Segment2& ref = segments[longest];
        std::vector<Interval> intervals;
        for (std::size_t i : members[g])
            intervals.push_back(project(segments[i], ref));
        for (const Interval& iv : merge_intervals(std::move(intervals), snap / ref.length()))
            out.push_back(
                {ref.a + (ref.b - ref.a) * iv.first, ref.a + (ref.b - ref.a) * iv.second});
    }
    return out;
}

std::vector<Segment2> clean_segments(const std::vector<Vec2>& outline,
                                     const std::vector<Segment2>& segments,
                                     const std::vector<Segment2>& fixed, double snap,
                                     double merge) {
    std::vector<Segment2> clipped;
    for (const Segment2& s : segments) {
        const double len = s.length();
        if (len <= 4 * snap)
            continue;
        for (const Interval& iv :
             clip_line_to_polygon(s.a, s.b - s.a, 0.0, 1.0, outline, snap / len))
            clipped.push_back({s.a + (s.b - s.a) * iv.first, s.a + (s.b - s.a) * iv.second});
    }
    std::vector<Segment2> on_hand = fixed;
    for (std::size_t i = 0; i < outline.size(); ++i)
        on_hand.push_back({outline[i], outline[(i + 1) % outline.size()]});
    std::vector<Segment2> out;
    for (const Segment2& m : merge_collinear(clipped, merge))
        for (const Segment2& piece : subtract_fixed(m, on_hand, snap, merge))
            out.push_back(piece);
    return out;
}

namespace {

// Crossing point of the interiors of two segments, if they cross properly.
bool crossing(const Segment2& s, const Segment2& t, Vec2& x) {
    const Vec2 r = s.b - s.a, q = t.b - t.a;
    const double den = cross(r, q);
    if (den == 0)
        return false;
    const double u = cross(t.a - s.a, q) / den, v = cross(t.a - s.a, r) / den;
    if (!(u > 0 && u < 1 && v > 0 && v < 1))
        return false;
    x = s.a + r * u;
    return true;
}

/// Indices of segment pairs whose boxes come within snap, found by a sweep over x.
template <typename Visit>
void near_pairs(const std::vector<Segment2>& segs, double snap, Visit&& visit) {
    std::vector<std::size_t> order(segs.size());
    std::iota(order.begin(), order.end(), 0);
    auto lo = [&](std::size_t i) { return std::min(segs[i].a.x, segs[i].b.x); };
    auto hi = [&](std::size_t i) { return std::max(segs[i].a.x, segs[i].b.x); };
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return lo(a) < lo(b) || (lo(a) == lo(b) && a < b);
    });
    for (std::size_t k = 0; k < order.size(); ++k)
        for (std::size_t m = k + 1; m < order.size() && lo(order[m]) <= hi(order[k]) + snap; ++m)
            if (boxes_near(segs[order[k]], segs[order[m]], snap))
                visit(std::min(order[k], order[m]), std::max(order[k], order[m]));
}

// One noding pass: split points per segment (crossings and nearby vertices), then pieces.
std::vector<NodedSegment> node_pass(const std::vector<NodedSegment>& in, PointSnapper& snapper,
                                    double merge) {
    std::vector<Segment2> segs;
    for (const NodedSegment& n : in)
        segs.push_back(n.segment);
    std::vector<std::vector<Vec2>> splits(segs.size());
    near_pairs(segs, merge, [&](std::size_t i, std::size_t j) {
        Vec2 x;
        if (crossing(segs[i], segs[j], x)) {
            x = snapper.snap(x);
            splits[i].push_back(x);
            splits[j].push_back(x);
        }
        // The outline is the surface's geometry: its own vertices never split its other
        // edges (a sliver's short edge can be below the merge distance).
        if (in[i].outline && in[j].outline)
            return;
        for (const auto& [s, t] : {std::pair{i, j}, std::pair{j, i}})
            for (const Vec2& v : {segs[t].a, segs[t].b})
                if (distance_to_segment(v, segs[s].a, segs[s].b) <= merge &&
                    length(v - segs[s].a) > 0 && length(v - segs[s].b) > 0)
                    splits[s].push_back(v);
    });
    std::vector<NodedSegment> out;
    for (std::size_t i = 0; i < segs.size(); ++i) {
        const Segment2& s = segs[i];
        std::vector<std::pair<double, Vec2>> points{{0.0, s.a}, {1.0, s.b}};
        const Vec2 d = s.b - s.a;
        for (const Vec2& p : splits[i])
            points.emplace_back(dot(p - s.a, d) / dot(d, d), p);
        std::sort(points.begin(), points.end(),
                  [](const auto& x, const auto& y) { return x.first < y.first; });
        for (std::size_t k = 0; k + 1 < points.size(); ++k)
            if (length(points[k + 1].second - points[k].second) > 0)
                out.push_back({{points[k].second, points[k + 1].second}, in[i].outline});
    }
    return out;
}

// Sorted, without duplicates; a duplicate of an outline piece is an outline piece.
std::vector<NodedSegment> unique_segments(std::vector<NodedSegment> segs) {
    for (NodedSegment& n : segs)
        if (std::tie(n.segment.b.x, n.segment.b.y) < std::tie(n.segment.a.x, n.segment.a.y))
            std::swap(n.segment.a, n.segment.b);
    auto key = [](const NodedSegment& n) {
        return std::tie(n.segment.a.x, n.segment.a.y, n.segment.b.x, n.segment.b.y);
    };
    std::sort(segs.begin(), segs.end(), [&](const NodedSegment& s, const NodedSegment& t) {
        return key(s) < key(t) || (key(s) == key(t) && s.outline > t.outline);
    });
    segs.erase(
        std::unique(segs.begin(), segs.end(),
                    [&](const NodedSegment& s, const NodedSegment& t) { return key(s) == key(t); }),
        segs.end());
    return segs;
}

} // namespace

std::vector<NodedSegment> node_segments(const std::vector<Vec2>& outline,
                                        const std::vector<Segment2>& segments, double merge) {
    PointSnapper snapper(merge);
    std::vector<NodedSegment> segs;
    for (std::size_t i = 0; i < outline.size(); ++i) {
        snapper.add_anchor(outline[i]);
        if (length(outline[(i + 1) % outline.size()] - outline[i]) > 0)
            segs.push_back({{outline[i], outline[(i + 1) % outline.size()]}, true});
    }
    const std::size_t ring = segs.size();
    // Endpoints near the outline move onto it: the outline is the surface's geometry.
    auto place = [&](const Vec2& p) {
        Vec2 q = p;
        double best = merge;
        for (std::size_t i = 0; i < ring; ++i) {
            const Segment2& e = segs[i].segment;
            const Vec2 d = e.b - e.a;
            const double t = std::clamp(dot(p - e.a, d) / dot(d, d), 0.0, 1.0);
            const Vec2 x = e.a + d * t;
            if (length(x - p) < best) {
                best = length(x - p);
                q = x;
            }
        }
        return snapper.snap(q);
    };
    for (const Segment2& s : segments) {
        const Segment2 t{place(s.a), place(s.b)};
        if (length(t.b - t.a) > 0)
            segs.push_back({t, false});
    }
    for (int pass = 0; pass < 3; ++pass) {
        const std::size_t before = segs.size();
        segs = unique_segments(node_pass(segs, snapper, merge));
        if (segs.size() == before)
            break;
    }
    return segs;
}

} // namespace penumbra::mesher
