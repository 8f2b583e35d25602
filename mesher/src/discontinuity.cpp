// Discontinuity meshing after Heckbert (1992) and Lischinski, Tampieri & Greenberg (1992):
// each critical wedge (critical.h) is intersected with the planes of the surfaces it reaches
// and clipped to their outlines; a piece is a real boundary where the critical line from the
// receiver point through the blocker feature to the source feature is not blocked by other
// geometry (for the sun: the ray from the point along the critical direction leaves the
// scene). Deviations: edge-edge-edge events are ignored, and visibility along a piece is
// sampled (at a quarter of the element size, transitions bisected to the snap distance), so a
// blocker narrower than the sample spacing can leave a short hidden piece in place.

#include "discontinuity.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <variant>

#include "constraint_cleanup.h"
#include "core/parallel.h"
#include "critical.h"
#include "scene_features.h"

namespace penumbra::mesher {

namespace {

struct Piece {
    std::uint32_t receiver = 0;
    Segment2 segment;
    int order = 2;
};

// Narrows [lo, hi] along p0 + t·dir to the wedge; false if nothing is left.
bool clip_to_wedge(const Event& ev, const Vec3& p0, const Vec3& dir, double& lo, double& hi) {
    for (const HalfPlane& h : ev.bounds) {
        const double c0 = dot(h.m, p0 - h.q), c1 = dot(h.m, dir);
        if (c1 == 0) {
            if (c0 < 0)
                return false;
            continue;
        }
        const double t = -c0 / c1;
        if (c1 > 0)
            lo = std::max(lo, t);
        else
            hi = std::min(hi, t);
    }
    return hi > lo;
}

// The wedge's trace on receiver r, clipped to r's outline, as 2D segments.
std::vector<Segment2> wedge_trace(const Event& ev, const Surface& r, const MeshParams& params) {
    const Vec3 d = cross(ev.normal, r.normal);
    const double d2 = dot(d, d);
    if (d2 < 1e-18)
        return {}; // the wedge is parallel to the receiver
    const double h = dot(ev.normal, ev.apex);
    const Vec3 p0 = (cross(r.normal, d) * h + cross(d, ev.normal) * r.offset) / d2;
    const Vec3 dir = d / std::sqrt(d2);
    const double tc = dot((r.box.lo + r.box.hi) * 0.5 - p0, dir);
    const double reach = r.box.diagonal() + params.snap;
    double lo = tc - reach, hi = tc + reach;
    if (!clip_to_wedge(ev, p0, dir, lo, hi))
        return {};
    const Vec2 q0 = r.to_2d(p0), qd{dot(dir, r.axis_u), dot(dir, r.axis_v)};
    std::vector<Segment2> out;
    for (const Interval& iv : clip_line_to_polygon(q0, qd, lo, hi, r.outline2d, params.snap))
        out.push_back({q0 + qd * iv.first, q0 + qd * iv.second});
    return out;
}

// The blocker edge itself when it lies on the receiver (a contact: D0), clipped to r.
std::vector<Segment2> contact_trace(const Event& ev, const Surface& r, const MeshParams& params) {
    const Vec2 a = r.to_2d(ev.near_a), b = r.to_2d(ev.near_b);
    const double len = length(b - a);
    std::vector<Segment2> out;
    if (len <= params.snap)
        return out;
    for (const Interval& iv :
         clip_line_to_polygon(a, b - a, 0.0, 1.0, r.outline2d, params.snap / len))
        out.push_back({a + (b - a) * iv.first, a + (b - a) * iv.second});
    return out;
}

/// Decides whether the critical line from a receiver point to the source feature is open.
class CriticalLine {
public:
    CriticalLine(const Event& ev, const Source& src, const SurfaceBvh& bvh,
                 std::vector<std::uint32_t> skip, const MeshParams& params)
        : ev_(ev), src_(src), bvh_(bvh), skip_(std::move(skip)), params_(params) {}

    bool open(const Vec3& x) const {
        if (src_.at_infinity()) // through the blocker vertex, or along the touching direction
            return open_toward(x, ev_.kind == EventKind::edge_vertex ? normalize(ev_.apex - x)
                                                                     : ev_.toward);
        Vec3 target = ev_.apex;
        if (ev_.kind == EventKind::edge_vertex && !through_vertex(x, target))
            return false;
        const Vec3 d = target - x;
        const double margin = std::max(1e-9, 10 * params_.snap / length(d));
        return !bvh_.occluded(x, d, margin, 1.0 - margin, skip_);
    }

private:
    // The sun: the ray from x along the unit direction d leaves the scene.
    bool open_toward(const Vec3& x, const Vec3& d) const {
        const double reach = 2 * params_.diagonal;
        const double margin = std::max(1e-9, 10 * params_.snap / reach);
        return !bvh_.occluded(x, d * reach, margin, 1.0, skip_);
    }

    // The point of the source edge on the line from x through the blocker vertex.
    bool through_vertex(const Vec3& x, Vec3& target) const {
        const std::size_t n = src_.vertices.size();
        const Vec3& a = src_.vertices[ev_.source_k];
        const Vec3& b = src_.vertices[(ev_.source_k + 1) % n];
        const Vec3 u = ev_.apex - x, v = b - a, w0 = x - a;
        const double uu = dot(u, u), uv = dot(u, v), vv = dot(v, v);
        const double den = uu * vv - uv * uv;
        if (den <= 1e-300)
            return false;
        const double lambda = (uv * dot(v, w0) - dot(u, w0) * vv) / den;
        target = x + u * lambda;
        return lambda > 1;
    }

    const Event& ev_;
    const Source& src_;
    const SurfaceBvh& bvh_;
    std::vector<std::uint32_t> skip_;
    const MeshParams& params_;
};

// Parameter intervals of [0, 1] along a piece of length len where open(s) holds.
template <typename Open>
std::vector<Interval> open_parts(const Open& open, double len, const MeshParams& params) {
    const int n = std::clamp(int(len / (0.25 * params.max_edge)) + 2, 3, 64);
    const auto count = std::size_t(n);
    std::vector<double> s(count);
    std::vector<bool> state(count);
    for (int k = 0; k < n; ++k) {
        s[std::size_t(k)] = std::clamp(double(k) / (n - 1), 1e-6, 1.0 - 1e-6);
        state[std::size_t(k)] = open(s[std::size_t(k)]);
    }
    auto transition = [&](double lo, double hi, bool lo_state) {
        for (int it = 0; it < 60 && (hi - lo) * len > 0.5 * params.snap; ++it) {
            const double mid = 0.5 * (lo + hi);
            (open(mid) == lo_state ? lo : hi) = mid;
        }
        return 0.5 * (lo + hi);
    };
    std::vector<Interval> out;
    double start = 0;
    for (std::size_t k = 0; k + 1 < s.size(); ++k) {
        if (state[k] == state[k + 1])
            continue;
        const double t = transition(s[k], s[k + 1], state[k]);
        if (state[k])
            out.emplace_back(start, t);
        else
            start = t;
    }
    if (state.back())
        out.emplace_back(start, 1.0);
    return out;
}

const std::vector<std::uint32_t>& blocker_surfaces(const Event& ev, const Features& f) {
    return ev.kind == EventKind::vertex_edge ? f.edges[ev.feature].surfaces
                                             : f.vertices[ev.feature].surfaces;
}

// Whether the source can light r: some of r is in front of a polygon source; some side of r
// faces the sun (a surface edge-on to it, or a one-sided one facing away, has the sun below
// its horizon and receives nothing).
bool receives(const Source& src, const Surface& r, double eps) {
    if (src.at_infinity()) {
        const double c = dot(r.normal, src.axis);
        return r.two_sided ? std::abs(c) > 1e-9 : c > 1e-9;
    }
    return std::any_of(r.outline.begin(), r.outline.end(),
                       [&](const Vec3& v) { return src.in_front(v, eps); });
}

std::vector<Piece> event_pieces(const Event& ev, const std::vector<Source>& sources,
                                const Features& features, const std::vector<Surface>& surfaces,
                                const SurfaceBvh& bvh, const MeshParams& params) {
    const Source& src = sources[ev.source];
    std::vector<std::uint32_t> skip = blocker_surfaces(ev, features);
    if (src.surface)
        skip.push_back(*src.surface);
    std::vector<Piece> out;
    for (std::uint32_t ri : bvh.overlapping(ev.box)) {
        const Surface& r = surfaces[ri];
        if (std::find(skip.begin(), skip.end(), ri) != skip.end() || !receives(src, r, params.snap))
            continue;
        const bool contact = ev.kind == EventKind::vertex_edge &&
                             std::abs(r.distance(ev.near_a)) <= params.contact_tol &&
                             std::abs(r.distance(ev.near_b)) <= params.contact_tol;
        if (ev.kind == EventKind::edge_vertex &&
            std::abs(r.distance(ev.apex)) <= params.contact_tol)
            continue; // the wedge touches the receiver at the vertex only
        std::vector<std::uint32_t> line_skip = skip;
        line_skip.push_back(ri);
        const CriticalLine line(ev, src, bvh, std::move(line_skip), params);
        for (const Segment2& s :
             contact ? contact_trace(ev, r, params) : wedge_trace(ev, r, params)) {
            const double len = s.length();
            auto open = [&](double t) { return line.open(r.to_3d(s.a + (s.b - s.a) * t)); };
            for (const Interval& iv : open_parts(open, len, params))
                if ((iv.second - iv.first) * len > 10 * params.snap)
                    out.push_back({ri,
                                   {s.a + (s.b - s.a) * iv.first, s.a + (s.b - s.a) * iv.second},
                                   contact ? 0 : ev.order});
        }
    }
    return out;
}

// The crossing of the lines of s and t, if they are not parallel.
bool line_crossing(const Segment2& s, const Segment2& t, Vec2& x) {
    const Vec2 r = s.b - s.a, q = t.b - t.a;
    const double den = cross(r, q);
    if (std::abs(den) <= 1e-9 * length(r) * length(q))
        return false;
    x = s.a + r * (cross(t.a - s.a, q) / den);
    return true;
}

// Where the end v of the sun's segment t (w its other end) goes when it lies within merge of
// the interiors of the segments \p near: the crossing of two of them if one is within
// 2 merge, so that it stays on both; else onto the nearest one it is off: the point on t's
// line if within 4 merge, so that t keeps its line, else the nearest point. False: stays.
bool fitted_end(const Vec2& v, const Vec2& w, const std::vector<Segment2>& near, double merge,
                Vec2& target) {
    double best = 2 * merge;
    for (std::size_t p = 0; p < near.size(); ++p)
        for (std::size_t q = p + 1; q < near.size(); ++q) {
            Vec2 x;
            if (line_crossing(near[p], near[q], x) && length(x - v) < best) {
                best = length(x - v);
                target = x;
            }
        }
    if (best < 2 * merge)
        return best > 1e-9 * merge;
    const Segment2* nearest = nullptr;
    double nearest_d = merge;
    for (const Segment2& s : near) {
        const double d = distance_to_segment(v, s.a, s.b);
        if (d > 1e-9 * merge && d <= nearest_d) {
            nearest = &s;
            nearest_d = d;
        }
    }
    if (!nearest)
        return false;
    const Segment2& s = *nearest;
    Vec2 x;
    if (line_crossing({w, v}, s, x) && dot(x - w, v - w) > 0 && length(x - v) <= 4 * merge &&
        distance_to_segment(x, s.a, s.b) <= 1e-9 * merge + 1e-12 * length(s.b - s.a)) {
        target = x;
        return true;
    }
    const Vec2 q = s.b - s.a;
    target = s.a + q * std::clamp(dot(v - s.a, q) / dot(q, q), 0.0, 1.0);
    return true;
}

// Two ends v of t and p of s closer than merge (but apart), of segments longer than 2 merge:
// both move to the crossing of the two lines if it is within 2 merge of each, rather than
// the noding merging one into the other.
bool join_ends(Segment2& t, bool t_at_b, Segment2& s, bool s_at_b, double merge) {
    Vec2& v = t_at_b ? t.b : t.a;
    Vec2& p = s_at_b ? s.b : s.a;
    Vec2 x;
    if ((v.x == p.x && v.y == p.y) || length(v - p) > merge || t.length() <= 2 * merge ||
        s.length() <= 2 * merge || !line_crossing(t, s, x) || length(x - v) > 2 * merge ||
        length(x - p) > 2 * merge)
        return false;
    v = x;
    p = x;
    return true;
}

// The sun's boundaries are finer than the constraint merge distance (a penumbra is about 9 mm
// wide per metre from the blocker): a VE line overshoots its crossing with another edge's by
// less than that, a rim chord starts beside the line it touches, two edges' lines end less
// than that apart at a corner. The noding would bend one line through the other's end
// (node_segments splits a segment at every vertex within merge of it, and merges such
// points), moving a whole shadow boundary. Such ends move instead onto the lines they are
// near (fitted_end) or to the crossing of the two lines (join_ends), so that every line stays
// where it is; pieces left shorter than 4 snap, or lying on another of the sun's segments,
// are dropped.
void fit_sun_ends(std::vector<ReceiverSegment>& segs, const MeshParams& params) {
    std::vector<std::size_t> sun;
    for (std::size_t i = 0; i < segs.size(); ++i)
        if (std::holds_alternative<SunSource>(segs[i].source))
            sun.push_back(i);
    const double m = params.merge;
    for (int pass = 0; pass < 3; ++pass) {
        bool changed = false;
        std::vector<std::array<double, 4>> boxes; // x and y ranges, widened by merge
        for (std::size_t j : sun) {
            const Segment2& s = segs[j].segment;
            boxes.push_back({std::min(s.a.x, s.b.x) - m, std::max(s.a.x, s.b.x) + m,
                             std::min(s.a.y, s.b.y) - m, std::max(s.a.y, s.b.y) + m});
        }
        for (std::size_t i : sun)
            for (const bool at_b : {false, true}) {
                Segment2& t = segs[i].segment;
                Vec2& v = at_b ? t.b : t.a;
                std::vector<Segment2> near;
                for (std::size_t k = 0; k < sun.size(); ++k) {
                    const Segment2& s = segs[sun[k]].segment;
                    const auto& box = boxes[k];
                    if (sun[k] != i && v.x >= box[0] && v.x <= box[1] && v.y >= box[2] &&
                        v.y <= box[3] && distance_to_segment(v, s.a, s.b) <= m &&
                        length(v - s.a) > m && length(v - s.b) > m)
                        near.push_back(s);
                }
                Vec2 target;
                if (!near.empty() && fitted_end(v, at_b ? t.a : t.b, near, m, target)) {
                    v = target;
                    changed = true;
                }
                for (std::size_t k = 0; k < sun.size(); ++k) {
                    const auto& box = boxes[k];
                    if (sun[k] == i || v.x < box[0] || v.x > box[1] || v.y < box[2] || v.y > box[3])
                        continue;
                    for (const bool s_at_b : {false, true})
                        changed = join_ends(t, at_b, segs[sun[k]].segment, s_at_b, m) || changed;
                }
            }
        if (!changed)
            break;
    }
    std::vector<bool> drop(segs.size(), false);
    for (std::size_t i : sun) {
        const Segment2& t = segs[i].segment;
        drop[i] = t.length() <= 4 * params.snap;
        for (std::size_t j : sun) {
            const Segment2& s = segs[j].segment;
            if (drop[i] || j == i || drop[j] ||
                std::max(t.a.x, t.b.x) < std::min(s.a.x, s.b.x) - m ||
                std::min(t.a.x, t.b.x) > std::max(s.a.x, s.b.x) + m)
                continue;
            drop[i] = distance_to_segment(t.a, s.a, s.b) <= 1e-9 * m &&
                      distance_to_segment(t.b, s.a, s.b) <= 1e-9 * m;
        }
    }
    std::size_t kept = 0;
    for (std::size_t i = 0; i < segs.size(); ++i)
        if (!drop[i])
            segs[kept++] = segs[i];
    segs.resize(kept);
}

// The order of a light's segments among a surface's (the constraints' order shapes the
// triangulation): point lights from the last one, the sun, then polygons by index.
std::pair<int, std::int64_t> insertion_rank(const LightSource& light) {
    if (const auto* point = std::get_if<PointSource>(&light))
        return {0, -std::int64_t(point->index)};
    if (const auto* area = std::get_if<AreaSource>(&light))
        return {3, area->polygon};
    return {std::holds_alternative<SunSource>(light) ? 1 : 2, 0};
}

/// Orders (light, order) groups by insertion_rank, then by order.
struct InsertionOrder {
    bool operator()(const std::pair<LightSource, int>& x,
                    const std::pair<LightSource, int>& y) const {
        return std::pair(insertion_rank(x.first), x.second) <
               std::pair(insertion_rank(y.first), y.second);
    }
};

} // namespace

std::vector<std::vector<ReceiverSegment>>
find_discontinuities(const Scene& scene, const std::vector<Surface>& surfaces,
                     const SurfaceBvh& bvh, const MeshParams& params, const Context& ctx) {
    std::vector<std::vector<ReceiverSegment>> out(surfaces.size());
    const std::vector<Source> sources = collect_sources(scene, surfaces);
    if (params.max_order < 0 || sources.empty())
        return out;
    const Features features = collect_features(surfaces, 4 * params.snap);
    const std::vector<Event> events = critical_events(sources, features, bvh, params, ctx);
    std::vector<std::vector<Piece>> pieces(events.size());
    ProgressStage progress(ctx, "discontinuities");
    const std::size_t block = 1024;
    for (std::size_t begin = 0; begin < events.size(); begin += block) {
        const std::size_t end = std::min(events.size(), begin + block);
        run_in_arena(ctx, [&] {
            parallel_for_index(end - begin, 4, [&](std::size_t k) {
                pieces[begin + k] =
                    event_pieces(events[begin + k], sources, features, surfaces, bvh, params);
            });
        });
        progress.update(double(end) / double(events.size()));
    }
    // Per surface, per (source, order): merge collinear overlapping pieces.
    std::vector<std::map<std::pair<LightSource, int>, std::vector<Segment2>, InsertionOrder>>
        groups(surfaces.size());
    for (std::size_t i = 0; i < events.size(); ++i)
        for (const Piece& p : pieces[i])
            if (p.order <= params.max_order)
                groups[p.receiver][{sources[events[i].source].light, p.order}].push_back(p.segment);
    run_in_arena(ctx, [&] {
        parallel_for_index(surfaces.size(), 16, [&](std::size_t s) {
            for (const auto& [key, segments] : groups[s])
                for (const Segment2& m : merge_collinear(segments, params.snap))
                    out[s].push_back({m, key.second, key.first});
            fit_sun_ends(out[s], params);
        });
    });
    ctx.debug("mesh: {} sources, {} critical events", sources.size(), events.size());
    return out;
}

} // namespace penumbra::mesher
