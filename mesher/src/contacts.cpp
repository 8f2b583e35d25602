// Contact and intersection splitting. For each pair of surfaces whose boxes come within the
// contact tolerance:
//  - transversal planes: the contact is the part of the planes' common line where both
//    polygons lie within the tolerance of the other's plane (the projection of the polygon's
//    slab-clipped part onto the line, for each polygon, intersected);
//  - parallel planes closer than the tolerance: the overlap covers the facing sides.
// Every pair is computed once, in surface order, and the results are appended in that order.

#include "contacts.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace penumbra::mesher {

namespace {

struct Line3 {
    Vec3 point, dir; ///< dir is a unit vector
};

// The common line of two non-parallel planes.
Line3 plane_intersection(const Surface& s, const Surface& t) {
    const Vec3 d = cross(s.normal, t.normal);
    const double d2 = dot(d, d);
    const Vec3 p = (cross(t.normal, d) * s.offset + cross(d, s.normal) * t.offset) / d2;
    return {p, d / std::sqrt(d2)};
}

// Parameters along \p line of the part of polygon \p p within \p half_width of plane \p q:
// the union of the projections of (a) its edges clipped to the slab and (b) the polygon's
// crossings of the slab's two boundary planes. Together these bound every component of
// the polygon-slab intersection, so their projections cover its projection.
std::vector<Interval> slab_projection(const Surface& p, const Surface& q, const Line3& line,
                                      double half_width) {
    std::vector<Interval> out;
    const std::size_t n = p.outline.size();
    auto along = [&](const Vec3& x) { return dot(x - line.point, line.dir); };
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3 a = p.outline[i], b = p.outline[(i + 1) % n];
        const double da = q.distance(a), db = q.distance(b);
        double lo = 0, hi = 1;
        if (da != db) {
            double u0 = (-half_width - da) / (db - da), u1 = (half_width - da) / (db - da);
            if (u0 > u1)
                std::swap(u0, u1);
            lo = std::max(lo, u0);
            hi = std::min(hi, u1);
        } else if (std::abs(da) > half_width) {
            continue;
        }
        if (lo > hi)
            continue;
        const double ta = along(a + (b - a) * lo), tb = along(a + (b - a) * hi);
        out.emplace_back(std::min(ta, tb), std::max(ta, tb));
    }
    for (double level : {-half_width, half_width}) {
        std::vector<double> ts;
        for (std::size_t i = 0; i < n; ++i) {
            const Vec3 a = p.outline[i], b = p.outline[(i + 1) % n];
            const double da = q.distance(a) - level, db = q.distance(b) - level;
            if ((da > 0) != (db > 0))
                ts.push_back(along(a + (b - a) * (da / (da - db))));
        }
        std::sort(ts.begin(), ts.end());
        for (std::size_t i = 0; i + 1 < ts.size(); i += 2)
            out.emplace_back(ts[i], ts[i + 1]);
    }
    return merge_intervals(std::move(out), 0.0);
}

struct PairResult {
    std::uint32_t surface;
    bool is_cover = false;
    Segment2 cut;
    Cover cover;
};

void transversal_contact(const Surface& s, const Surface& t, const MeshParams& params,
                         std::vector<PairResult>& out) {
    const Line3 line = plane_intersection(s, t);
    const double half_width = std::max(params.contact_tol, params.snap);
    const auto common = intersect_intervals(slab_projection(s, t, line, half_width),
                                            slab_projection(t, s, line, half_width));
    const double min_length = std::max(2 * params.contact_tol, 10 * params.snap);
    for (const Interval& iv : common) {
        if (iv.second - iv.first < min_length)
            continue;
        const Vec3 a = line.point + line.dir * iv.first, b = line.point + line.dir * iv.second;
        out.push_back({s.id, false, {s.to_2d(a), s.to_2d(b)}, {}});
        out.push_back({t.id, false, {t.to_2d(a), t.to_2d(b)}, {}});
    }
}

std::vector<Vec2> project_outline(const Surface& from, const Surface& onto) {
    std::vector<Vec2> out;
    for (const Vec3& v : from.outline)
        out.push_back(onto.to_2d(v));
    return out;
}

double mean_distance(const Surface& from, const Surface& to) {
    double sum = 0;
    for (const Vec3& v : from.outline)
        sum += to.distance(v);
    return sum / double(from.outline.size());
}

// A side of a surface for the coincident case: fronts win over backs, then lower ids.
struct Side {
    const Surface* surface;
    bool front;
    bool exists() const { return front || surface->two_sided; }
    bool beats(const Side& o) const {
        return front != o.front ? front : surface->id < o.surface->id;
    }
};

void coincident_covers(const Surface& s, const Surface& t, std::vector<PairResult>& out,
                       bool& duplicate) {
    const bool same_facing = dot(s.normal, t.normal) > 0;
    for (bool s_front : {true, false}) {
        // The side of s and the side of t that face the same way: one of them is kept.
        const Side a{&s, s_front}, b{&t, same_facing ? s_front : !s_front};
        if (!a.exists() || !b.exists())
            continue;
        const bool s_loses = b.beats(a);
        const Surface& loser = s_loses ? s : t;
        const Surface& winner = s_loses ? t : s;
        const bool loser_front = s_loses ? a.front : b.front;
        out.push_back(
            {loser.id, true, {}, {project_outline(winner, loser), loser_front, !loser_front}});
        duplicate = duplicate || (a.front && b.front);
    }
}

void coplanar_contact(const Surface& s, const Surface& t, const MeshParams& params,
                      std::vector<PairResult>& out, bool& duplicate) {
    const std::vector<Vec2> t_on_s = project_outline(t, s);
    if (!polygons_overlap(s.outline2d, t_on_s, params.snap))
        return;
    const double o_st = mean_distance(t, s), o_ts = mean_distance(s, t);
    const double coincident = std::max(params.snap, 1e-3 * params.contact_tol);
    if (std::abs(o_st) <= coincident) {
        coincident_covers(s, t, out, duplicate);
        return;
    }
    // The side of each surface that faces the other is covered where they overlap.
    out.push_back({s.id, true, {}, {t_on_s, o_st > 0, o_st < 0}});
    out.push_back({t.id, true, {}, {project_outline(s, t), o_ts > 0, o_ts < 0}});
}

bool within_plane(const Surface& from, const Surface& to, double tol) {
    for (const Vec3& v : from.outline)
        if (std::abs(to.distance(v)) > tol)
            return false;
    return true;
}

// Contacts of s with every later surface t; warns about exact duplicates.
std::vector<PairResult> contacts_of(const std::vector<Surface>& surfaces, const SurfaceBvh& bvh,
                                    std::uint32_t si, const MeshParams& params,
                                    const Context& ctx) {
    const Surface& s = surfaces[si];
    const double tol = std::max(params.contact_tol, params.snap);
    BBox query = s.box;
    query.extend(s.box.lo - Vec3(tol, tol, tol));
    query.extend(s.box.hi + Vec3(tol, tol, tol));
    std::vector<PairResult> out;
    for (std::uint32_t ti : bvh.overlapping(query)) {
        if (ti <= si)
            continue;
        const Surface& t = surfaces[ti];
        if (std::abs(dot(s.normal, t.normal)) > 0.99 && within_plane(t, s, tol) &&
            within_plane(s, t, tol)) {
            bool duplicate = false;
            coplanar_contact(s, t, params, out, duplicate);
            if (duplicate)
                ctx.warn("mesh: surfaces {} and {} coincide; the second is hidden where they "
                         "overlap",
                         s.name, t.name);
        } else if (length(cross(s.normal, t.normal)) > 1e-9) {
            transversal_contact(s, t, params, out);
        }
    }
    return out;
}

} // namespace

std::vector<SurfaceContacts> find_contacts(const std::vector<Surface>& surfaces,
                                           const SurfaceBvh& bvh, const MeshParams& params,
                                           const Context& ctx) {
    std::vector<SurfaceContacts> result(surfaces.size());
    if (!params.split_contacts)
        return result;
    std::vector<std::vector<PairResult>> per_surface(surfaces.size());
    run_in_arena(ctx, [&] {
        parallel_for_index(surfaces.size(), 16, [&](std::size_t i) {
            per_surface[i] = contacts_of(surfaces, bvh, std::uint32_t(i), params, ctx);
        });
    });
    for (auto& items : per_surface) {
        for (PairResult& r : items) {
            if (r.is_cover)
                result[r.surface].covers.push_back(std::move(r.cover));
            else
                result[r.surface].cuts.push_back(r.cut);
        }
    }
    return result;
}

} // namespace penumbra::mesher
