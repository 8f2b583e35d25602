// Enumeration of VE and EV critical wedges. A blocker edge generates a VE event with a source
// vertex only if the faces sharing the edge all lie on one side of the wedge's plane (the edge
// is a silhouette seen from the vertex); a blocker vertex generates an EV event with a source
// edge only if its outline neighbours all lie on one side. Features that no sample line
// reaches from the source feature unoccluded are skipped (lights in other rooms). The sun's
// features are directions (critical.h): its wedges are the same half-plane bounded regions,
// with rays parallel to a direction where a finite source's rays leave a point.

#include "critical.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/parallel.h"

namespace penumbra::mesher {

namespace {

Source sun_source(const Sun& sun) {
    Source src;
    src.light = SunSource{};
    src.axis = sun.direction;
    const double r = sun.angular_radius();
    src.sin_radius = std::sin(r);
    if (r == 0) {
        src.vertices = {sun.direction};
        return src;
    }
    const Frame frame = Frame::from_normal(sun.direction);
    for (int k = 0; k < k_sun_rim_sides; ++k) {
        const double phi = 2.0 * k_pi * k / k_sun_rim_sides;
        src.vertices.push_back(frame.to_world(
            Vec3(src.sin_radius * std::cos(phi), src.sin_radius * std::sin(phi), std::cos(r))));
    }
    return src;
}

} // namespace

std::vector<Source> collect_sources(const Scene& scene, const std::vector<Surface>& surfaces) {
    std::vector<Source> out;
    for (const Surface& s : surfaces) {
        for (int side = 0; side < 2; ++side) {
            if (!(side == 0 ? s.emits_front : s.emits_back))
                continue;
            Source src;
            src.light = AreaSource{s.polygon};
            src.surface = s.id;
            src.vertices = s.outline;
            src.normal = side == 0 ? s.normal : -s.normal;
            src.offset = side == 0 ? s.offset : -s.offset;
            out.push_back(std::move(src));
        }
    }
    for (std::size_t i = 0; i < scene.point_lights.size(); ++i) {
        const PointLight& light = scene.point_lights[i];
        Source src;
        src.light = PointSource{std::uint32_t(i)};
        src.vertices = {light.position};
        if (light.spot) {
            src.axis = light.spot->direction;
            src.cos_cutoff = std::cos(light.spot->cutoff_deg * k_pi / 180.0);
        }
        out.push_back(std::move(src));
    }
    if (scene.sun && !scene.sun->irradiance.is_black())
        out.push_back(sun_source(*scene.sun));
    return out;
}

namespace {

bool parallel(const Vec3& a, const Vec3& b) {
    return length(cross(normalize(a), normalize(b))) < 1e-6;
}

// All points strictly on one side of the plane (normal m through q), ignoring points on it
// (within 1e-9 of the scene's \p diagonal).
bool one_side(const Vec3& m, const Vec3& q, const std::vector<Vec3>& points, double diagonal) {
    const double eps = 1e-9 * length(m) * diagonal;
    int sign = 0;
    for (const Vec3& p : points) {
        const double d = dot(m, p - q);
        const int s = d > eps ? 1 : (d < -eps ? -1 : 0);
        if (s == 0)
            continue;
        if (sign != 0 && s != sign)
            return false;
        sign = s;
    }
    return true;
}

// An event of \p kind between source \p si (its vertex or edge \p k) and blocker feature
// \p feature; the caller sets its wedge.
Event new_event(EventKind kind, std::uint32_t si, std::uint32_t feature, std::size_t k, int order) {
    Event ev;
    ev.kind = kind;
    ev.source = si;
    ev.feature = feature;
    ev.source_k = std::uint32_t(k);
    ev.order = order;
    return ev;
}

// Whether some of up to five points on [a, b] sees \p target (skipping \p skip).
bool sees(const SurfaceBvh& bvh, const Vec3& a, const Vec3& b, const Vec3& target,
          const std::vector<std::uint32_t>& skip) {
    for (double u : {0.5, 0.02, 0.98, 0.25, 0.75}) {
        const Vec3 p = a + (b - a) * u;
        if (!bvh.occluded(p, target - p, 1e-6, 1.0 - 1e-6, skip))
            return true;
    }
    return false;
}

// Bounds the wedge: its apex, the near points and both boundary rays out to \p reach.
void bound_wedge(Event& ev, const Vec3& base1, const Vec3& r1, const Vec3& base2, const Vec3& r2,
                 double reach) {
    ev.box.extend(ev.apex);
    ev.box.extend(base1);
    ev.box.extend(base2);
    ev.box.extend(base1 + normalize(r1) * reach);
    ev.box.extend(base2 + normalize(r2) * reach);
}

// VE wedge through source vertex v and the edge [a, b]; false if degenerate.
bool vertex_edge_wedge(Event& ev, const Vec3& v, const Vec3& a, const Vec3& b, double reach) {
    const Vec3 n = cross(a - v, b - v);
    if (length(n) <= 1e-12 * dot(a - v, a - v) + 1e-300)
        return false;
    ev.normal = normalize(n);
    ev.apex = v;
    ev.near_a = a;
    ev.near_b = b;
    Vec3 m1 = cross(ev.normal, a - v), m2 = cross(ev.normal, b - v), m3 = cross(ev.normal, b - a);
    if (dot(m1, b - v) < 0)
        m1 = -m1;
    if (dot(m2, a - v) < 0)
        m2 = -m2;
    if (dot(m3, v - a) > 0)
        m3 = -m3;
    ev.bounds = {{m1, v}, {m2, v}, {m3, a}};
    bound_wedge(ev, a, a - v, b, b - v, reach);
    return true;
}

// EV wedge from blocker vertex w between the rays along r1 and r2 (away from the source edge:
// w − a and w − b for a finite edge [a, b]); false if degenerate.
bool edge_vertex_wedge(Event& ev, const Vec3& w, const Vec3& r1, const Vec3& r2, double reach) {
    const Vec3 n = cross(r1, r2);
    if (length(n) <= 1e-12 * dot(r1, r1) + 1e-300)
        return false;
    ev.normal = normalize(n);
    ev.apex = w;
    Vec3 m1 = cross(ev.normal, r1), m2 = cross(ev.normal, r2);
    if (dot(m1, r2) < 0)
        m1 = -m1;
    if (dot(m2, r1) < 0)
        m2 = -m2;
    ev.bounds = {{m1, w}, {m2, w}};
    bound_wedge(ev, w, r1, w, r2, reach);
    return true;
}

std::vector<std::uint32_t> with_source(std::vector<std::uint32_t> skip, const Source& src) {
    if (src.surface)
        skip.push_back(*src.surface);
    return skip;
}

// The parts of [a, b] inside a spot's cut-off cone ([a, b] itself for other sources). Inside
// or not changes only where cos θ crosses cos_cutoff or dot(x − p, axis) changes sign, so
// the predicate is tested at the middle of each piece between those roots.
std::vector<std::pair<Vec3, Vec3>> lit_parts(const Source& src, const Vec3& a, const Vec3& b) {
    if (src.surface || src.cos_cutoff <= -1)
        return {{a, b}};
    const Vec3 u = a - src.vertices[0], w = b - a;
    const double alpha = dot(u, src.axis), beta = dot(w, src.axis);
    const double c2 = src.cos_cutoff * src.cos_cutoff;
    // (α + βt)² − c² |u + t w|² = qa t² + qb t + qc
    const double qa = beta * beta - c2 * dot(w, w);
    const double qb = 2.0 * (alpha * beta - c2 * dot(u, w));
    const double qc = alpha * alpha - c2 * dot(u, u);
    std::vector<double> cuts{0.0, 1.0};
    auto cut = [&](double t) {
        if (t > 0 && t < 1)
            cuts.push_back(t);
    };
    if (beta != 0)
        cut(-alpha / beta);
    if (qa != 0) {
        const double disc = qb * qb - 4.0 * qa * qc;
        if (disc >= 0) {
            cut((-qb - std::sqrt(disc)) / (2.0 * qa));
            cut((-qb + std::sqrt(disc)) / (2.0 * qa));
        }
    } else if (qb != 0) {
        cut(-qc / qb);
    }
    std::sort(cuts.begin(), cuts.end());
    std::vector<std::pair<Vec3, Vec3>> out;
    bool previous_inside = false;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
        const double t0 = cuts[k], t1 = cuts[k + 1];
        const Vec3 mid = u + w * (0.5 * (t0 + t1));
        const bool inside = t1 > t0 && dot(mid, src.axis) > src.cos_cutoff * length(mid);
        if (inside && previous_inside)
            out.back().second = a + w * t1; // pieces split only by dot(x − p, axis) = 0
        else if (inside)
            out.emplace_back(a + w * t0, a + w * t1);
        previous_inside = inside || (previous_inside && t1 <= t0);
    }
    return out;
}

// The part of [a, b] in front of the source; false if none.
bool clip_in_front(const Source& src, Vec3& a, Vec3& b, double eps) {
    if (!src.surface)
        return true;
    const double da = dot(src.normal, a) - src.offset, db = dot(src.normal, b) - src.offset;
    if (da <= eps && db <= eps)
        return false;
    if (da <= eps)
        a = a + (b - a) * ((eps - da) / (db - da));
    else if (db <= eps)
        b = b + (a - b) * ((eps - db) / (da - db));
    return true;
}

// ---- The sun ----

// The directions of the sun's rim whose planes with a line of direction \p e touch the disc's
// cone (the disc's centre alone when it has no size); none if the line points into the disc.
// A plane containing e with unit normal n touches the cone where n·s = sin r: n = c p1 ± √(1−c²)
// p2 in the frame p1 = s⊥e / |s⊥e|, p2 = e × p1, with c = sin r / |s⊥e|; the disc point it
// touches is s projected onto the plane.
int sun_tangent_directions(const Source& sun, const Vec3& e, std::array<Vec3, 2>& out) {
    const Vec3 u = normalize(e), &s = sun.axis;
    const Vec3 s_perp = s - u * dot(s, u);
    const double q = length(s_perp);
    if (sun.sin_radius == 0) {
        out[0] = s;
        return q > 1e-9 ? 1 : 0;
    }
    if (q <= sun.sin_radius * (1.0 + 1e-9))
        return 0;
    const Vec3 p1 = s_perp / q, p2 = cross(u, p1);
    const double c = sun.sin_radius / q, sn = std::sqrt(std::max(0.0, 1.0 - c * c));
    for (int k = 0; k < 2; ++k) {
        const Vec3 n = p1 * c + p2 * (k == 0 ? sn : -sn);
        out[std::size_t(k)] = normalize(s - n * sun.sin_radius);
    }
    return 2;
}

// The sun's rim as seen for blocker vertex w, a polygon inscribed in it: the touching
// directions of w's own edges (so that the chords end where the edges' VE planes touch the
// disc), each arc between two of them split evenly into chords of at most 2π / k_sun_rim_sides
// (the regular polygon if no edge has touching directions).
std::vector<Vec3> sun_rim_at(const Source& sun, const FeatureVertex& vertex) {
    const Frame frame = Frame::from_normal(sun.axis);
    std::vector<std::pair<double, Vec3>> breaks;
    for (const Vec3& nb : vertex.neighbours) {
        std::array<Vec3, 2> touching;
        const int count =
            length(nb - vertex.p) > 0 ? sun_tangent_directions(sun, nb - vertex.p, touching) : 0;
        for (int k = 0; k < count; ++k) {
            const Vec3& d = touching[std::size_t(k)];
            breaks.emplace_back(std::atan2(dot(d, frame.t), dot(d, frame.s)), d);
        }
    }
    if (breaks.empty())
        return sun.vertices;
    std::stable_sort(breaks.begin(), breaks.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    const double cos_radius = std::sqrt(1.0 - sun.sin_radius * sun.sin_radius);
    const double max_step = 2.0 * k_pi / k_sun_rim_sides;
    std::vector<Vec3> rim;
    for (std::size_t i = 0; i < breaks.size(); ++i) {
        const double a0 = breaks[i].first;
        const double a1 = i + 1 < breaks.size() ? breaks[i + 1].first : breaks[0].first + 2 * k_pi;
        if (a1 - a0 <= 1e-12)
            continue; // the same direction twice
        rim.push_back(breaks[i].second);
        const int parts = std::max(1, int(std::ceil((a1 - a0) / max_step - 1e-9)));
        for (int p = 1; p < parts; ++p) {
            const double phi = a0 + (a1 - a0) * p / parts;
            rim.push_back(frame.to_world(
                Vec3(sun.sin_radius * std::cos(phi), sun.sin_radius * std::sin(phi), cos_radius)));
        }
    }
    return rim;
}

// Whether some of up to five points on [a, b] sees the sun along the unit direction d.
bool sees_along(const SurfaceBvh& bvh, const Vec3& a, const Vec3& b, const Vec3& d, double reach,
                const std::vector<std::uint32_t>& skip) {
    for (double u : {0.5, 0.02, 0.98, 0.25, 0.75})
        if (!bvh.occluded(a + (b - a) * u, d * reach, 1e-6, 1.0, skip))
            return true;
    return false;
}

// Whether w sees some of up to five directions of the chord [a, b] of the sun's rim.
bool sees_chord(const SurfaceBvh& bvh, const Vec3& w, const Vec3& a, const Vec3& b, double reach,
                const std::vector<std::uint32_t>& skip) {
    for (double u : {0.5, 0.02, 0.98, 0.25, 0.75})
        if (!bvh.occluded(w, normalize(a + (b - a) * u) * reach, 1e-6, 1.0, skip))
            return true;
    return false;
}

// The sun's VE wedge: the part of the plane through the edge [a, b] and the direction d
// beyond the edge, between the lines through a and b parallel to d; false if degenerate.
bool sun_vertex_edge_wedge(Event& ev, const Vec3& d, const Vec3& a, const Vec3& b, double reach) {
    const Vec3 n = cross(b - a, d);
    if (length(n) <= 1e-12 * length(b - a) + 1e-300)
        return false;
    ev.normal = normalize(n);
    ev.apex = a;
    ev.toward = d;
    ev.near_a = a;
    ev.near_b = b;
    Vec3 m1 = cross(ev.normal, d), m2 = m1, m3 = cross(ev.normal, b - a);
    if (dot(m1, b - a) < 0)
        m1 = -m1;
    if (dot(m2, a - b) < 0)
        m2 = -m2;
    if (dot(m3, d) > 0)
        m3 = -m3;
    ev.bounds = {{m1, a}, {m2, b}, {m3, a}};
    for (const Vec3& p : {a, b, a - d * reach, b - d * reach})
        ev.box.extend(p);
    return true;
}

void sun_vertex_edge_events(const Source& src, std::uint32_t si, const FeatureEdge& edge,
                            std::uint32_t ei, const SurfaceBvh& bvh, const MeshParams& params,
                            std::vector<Event>& out) {
    const Vec3 &a = edge.a, &b = edge.b;
    const double reach = 2 * params.diagonal;
    std::array<Vec3, 2> touching;
    const int count = sun_tangent_directions(src, b - a, touching);
    for (int k = 0; k < count; ++k) {
        const Vec3& d = touching[std::size_t(k)];
        const Vec3 m = cross(b - a, d);
        if (!one_side(m, a, edge.wings, params.diagonal) ||
            !sees_along(bvh, a, b, d, reach, edge.surfaces))
            continue;
        // A disc's visible part grows as t^3/2.
        Event ev =
            new_event(EventKind::vertex_edge, si, ei, std::size_t(k), src.sin_radius > 0 ? 2 : 0);
        if (sun_vertex_edge_wedge(ev, d, a, b, reach))
            out.push_back(std::move(ev));
    }
}

void sun_edge_vertex_events(const Source& src, std::uint32_t si, const FeatureVertex& vertex,
                            std::uint32_t vi, const SurfaceBvh& bvh, const MeshParams& params,
                            std::vector<Event>& out) {
    if (src.sin_radius == 0)
        return; // parallel light: a point of the sky has no edges
    const Vec3& w = vertex.p;
    const double reach = 2 * params.diagonal;
    const std::vector<Vec3> rim = sun_rim_at(src, vertex);
    for (std::size_t k = 0; k < rim.size(); ++k) {
        const Vec3 &a = rim[k], &b = rim[(k + 1) % rim.size()];
        const Vec3 m = cross(a, b);
        if (!one_side(m, w, vertex.neighbours, params.diagonal) ||
            !sees_chord(bvh, w, a, b, reach, vertex.surfaces))
            continue;
        Event ev = new_event(EventKind::edge_vertex, si, vi, k, 2);
        if (edge_vertex_wedge(ev, w, -a, -b, reach))
            out.push_back(std::move(ev));
    }
}

// The VE events of the part [a, b] of blocker edge ei with each source vertex.
void vertex_edge_part_events(const Source& src, std::uint32_t si, const FeatureEdge& edge,
                             std::uint32_t ei, const Vec3& a, const Vec3& b,
                             const std::vector<std::uint32_t>& skip, const SurfaceBvh& bvh,
                             const MeshParams& params, std::vector<Event>& out) {
    const std::size_t n = src.vertices.size();
    for (std::size_t k = 0; k < n; ++k) {
        const Vec3& v = src.vertices[k];
        const Vec3 m = cross(a - v, b - v);
        if (!one_side(m, a, edge.wings, params.diagonal) || !sees(bvh, a, b, v, skip))
            continue;
        Event ev = new_event(EventKind::vertex_edge, si, ei, k,
                             !src.surface ? 0
                             : (parallel(src.vertices[(k + 1) % n] - v, b - a) ||
                                parallel(src.vertices[(k + n - 1) % n] - v, b - a))
                                 ? 1
                                 : 2);
        if (vertex_edge_wedge(ev, v, a, b, 2 * params.diagonal))
            out.push_back(std::move(ev));
    }
}

void vertex_edge_events(const Source& src, std::uint32_t si, const Features& features,
                        std::uint32_t ei, const SurfaceBvh& bvh, const MeshParams& params,
                        std::vector<Event>& out) {
    const FeatureEdge& edge = features.edges[ei];
    if (src.at_infinity())
        return sun_vertex_edge_events(src, si, edge, ei, bvh, params, out);
    if (src.surface &&
        std::find(edge.surfaces.begin(), edge.surfaces.end(), *src.surface) != edge.surfaces.end())
        return;
    Vec3 a = edge.a, b = edge.b;
    if (!clip_in_front(src, a, b, params.snap))
        return;
    const std::vector<std::uint32_t> skip = with_source(edge.surfaces, src);
    // A wedge from a part inside a spot's cone stays inside it: its rays leave the spot.
    for (const auto& [part_a, part_b] : lit_parts(src, a, b))
        vertex_edge_part_events(src, si, edge, ei, part_a, part_b, skip, bvh, params, out);
}

void edge_vertex_events(const Source& src, std::uint32_t si, const Features& features,
                        std::uint32_t vi, const SurfaceBvh& bvh, const MeshParams& params,
                        std::vector<Event>& out) {
    const FeatureVertex& vertex = features.vertices[vi];
    if (src.at_infinity())
        return sun_edge_vertex_events(src, si, vertex, vi, bvh, params, out);
    const Vec3& w = vertex.p;
    if (!src.surface || !src.in_front(w, params.snap))
        return;
    const std::vector<std::uint32_t> skip = with_source(vertex.surfaces, src);
    const std::size_t n = src.vertices.size();
    for (std::size_t k = 0; k < n; ++k) {
        const Vec3& a = src.vertices[k];
        const Vec3& b = src.vertices[(k + 1) % n];
        const Vec3 m = cross(b - a, w - a);
        if (!one_side(m, w, vertex.neighbours, params.diagonal) || !sees(bvh, a, b, w, skip))
            continue;
        Event ev = new_event(EventKind::edge_vertex, si, vi, k, 2);
        for (const Vec3& nb : vertex.neighbours)
            if (length(nb - w) > 0 && parallel(nb - w, b - a))
                ev.order = 1;
        if (edge_vertex_wedge(ev, w, w - a, w - b, 2 * params.diagonal))
            out.push_back(std::move(ev));
    }
}

} // namespace

std::vector<Event> critical_events(const std::vector<Source>& sources, const Features& features,
                                   const SurfaceBvh& bvh, const MeshParams& params,
                                   const Context& ctx) {
    const std::size_t ne = features.edges.size(), nv = features.vertices.size();
    const std::size_t per_source = ne + nv;
    std::vector<std::vector<Event>> chunks(sources.size() * per_source);
    run_in_arena(ctx, [&] {
        parallel_for_index(chunks.size(), 64, [&](std::size_t i) {
            const auto si = std::uint32_t(i / per_source);
            const std::size_t f = i % per_source;
            if (f < ne)
                vertex_edge_events(sources[si], si, features, std::uint32_t(f), bvh, params,
                                   chunks[i]);
            else
                edge_vertex_events(sources[si], si, features, std::uint32_t(f - ne), bvh, params,
                                   chunks[i]);
        });
    });
    std::vector<Event> out;
    for (auto& c : chunks)
        for (Event& e : c)
            out.push_back(std::move(e));
    return out;
}

} // namespace penumbra::mesher
