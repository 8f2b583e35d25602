// Discontinuity meshing after Heckbert (1992) and Lischinski, Tampieri & Greenberg (1992):
// each critical wedge (critical.h) is intersected with the planes of the surfaces it reaches
// and clipped to their outlines; a piece is a real boundary where the critical line from the
// receiver point through the blocker feature to the source feature is not blocked by other
// geometry. Deviations: edge-edge-edge events are ignored, and visibility along a piece is
// sampled (at a quarter of the element size, transitions bisected to the snap distance), so a
// blocker narrower than the sample spacing can leave a short hidden piece in place.

#include "discontinuity.h"

#include <algorithm>
#include <cmath>
#include <map>

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
    for (const Interval& iv : clip_line_to_polygon(a, b - a, 0.0, 1.0, r.outline2d,
                                                   params.snap / len))
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
        Vec3 target = ev_.apex;
        if (ev_.kind == EventKind::edge_vertex && !through_vertex(x, target))
            return false;
        const Vec3 d = target - x;
        const double margin = std::max(1e-9, 10 * params_.snap / length(d));
        return !bvh_.occluded(x, d, margin, 1.0 - margin, skip_);
    }

private:
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

bool any_in_front(const Source& src, const Surface& r, double eps) {
    return std::any_of(r.outline.begin(), r.outline.end(),
                       [&](const Vec3& v) { return src.in_front(v, eps); });
}

std::vector<Piece> event_pieces(const Event& ev, const std::vector<Source>& sources,
                                const Features& features, const std::vector<Surface>& surfaces,
                                const SurfaceBvh& bvh, const MeshParams& params) {
    const Source& src = sources[ev.source];
    std::vector<std::uint32_t> skip = blocker_surfaces(ev, features);
    if (src.surface >= 0)
        skip.push_back(std::uint32_t(src.surface));
    std::vector<Piece> out;
    for (std::uint32_t ri : bvh.overlapping(ev.box)) {
        const Surface& r = surfaces[ri];
        if (std::find(skip.begin(), skip.end(), ri) != skip.end() ||
            !any_in_front(src, r, params.snap))
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
        for (const Segment2& s : contact ? contact_trace(ev, r, params)
                                         : wedge_trace(ev, r, params)) {
            const double len = s.length();
            auto open = [&](double t) { return line.open(r.to_3d(s.a + (s.b - s.a) * t)); };
            for (const Interval& iv : open_parts(open, len, params))
                if ((iv.second - iv.first) * len > 10 * params.snap)
                    out.push_back({ri, {s.a + (s.b - s.a) * iv.first, s.a + (s.b - s.a) * iv.second},
                                   contact ? 0 : ev.order});
        }
    }
    return out;
}

} // namespace

std::vector<std::vector<ReceiverSegment>> find_discontinuities(const Scene& scene,
                                                               const std::vector<Surface>& surfaces,
                                                               const SurfaceBvh& bvh,
                                                               const MeshParams& params,
                                                               const Context& ctx) {
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
                pieces[begin + k] = event_pieces(events[begin + k], sources, features, surfaces,
                                                 bvh, params);
            });
        });
        progress.update(double(end) / double(events.size()));
    }
    // Per surface, per (source, order): merge collinear overlapping pieces.
    std::vector<std::map<std::pair<std::int32_t, int>, std::vector<Segment2>>> groups(
        surfaces.size());
    for (std::size_t i = 0; i < events.size(); ++i)
        for (const Piece& p : pieces[i])
            if (p.order <= params.max_order)
                groups[p.receiver][{sources[events[i].source].id, p.order}].push_back(p.segment);
    for (std::size_t s = 0; s < surfaces.size(); ++s)
        for (const auto& [key, segments] : groups[s])
            for (const Segment2& m : merge_collinear(segments, params.snap))
                out[s].push_back({m, key.second, key.first});
    ctx.debug("mesh: {} sources, {} critical events", sources.size(), events.size());
    return out;
}

} // namespace penumbra::mesher
