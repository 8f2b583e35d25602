#include "visibility/occluders.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace penumbra::solver {

namespace {

/// Grid cells per plane, at most this many per triangle (and per axis, this many).
constexpr double k_cells_per_triangle = 2.0;
constexpr std::uint32_t k_max_cells_per_axis = 4096;

using Key = std::array<std::int64_t, 4>;

std::int64_t quantize(double x, double unit) {
    return std::int64_t(std::llround(x / unit));
}

/// The plane of root \p r with the normal's largest component positive, so both sides of a
/// surface (and coplanar surfaces facing either way) share it.
std::pair<Vec3, double> canonical_plane(const Hierarchy& h, std::uint32_t r) {
    Vec3 n = h.normal[r];
    std::size_t a = 0;
    for (std::size_t k = 1; k < 3; ++k)
        if (std::abs(n[k]) > std::abs(n[a]))
            a = k;
    if (n[a] < 0)
        n = n * -1.0;
    return {n, dot(n, h.triangle[r][0])};
}

double cross2(double ax, double ay, double bx, double by) {
    return ax * by - ay * bx;
}
double length2(double x, double y) {
    return std::sqrt(x * x + y * y);
}

/// The grid coordinate of \p x along an axis of \p n cells of size \p cell from \p origin.
std::uint32_t grid_coordinate(double x, double origin, double cell, std::uint32_t n) {
    return std::uint32_t(std::clamp((x - origin) / cell, 0.0, double(n - 1)));
}

/// Calls fn(y · nx + x) for the cells (x0, y0)–(x1, y1) of \p range until it returns true;
/// returns whether it did.
template <typename Fn>
bool any_cell(const std::array<std::uint32_t, 4>& range, std::uint32_t nx, Fn&& fn) {
    for (std::uint32_t y = range[1]; y <= range[3]; ++y)
        for (std::uint32_t x = range[0]; x <= range[2]; ++x)
            if (fn(std::size_t(y) * nx + x))
                return true;
    return false;
}

/// Narrows [t0, t1] to the t where f0 + t · df >= 0 (Cyrus–Beck); false if no t is.
bool clip_to_half_plane(double f0, double df, double& t0, double& t1) {
    if (df == 0)
        return f0 >= 0;
    if (df > 0)
        t0 = std::max(t0, -f0 / df);
    else
        t1 = std::min(t1, -f0 / df);
    return true;
}

} // namespace

OccluderPlanes::OccluderPlanes(const Hierarchy& h) {
    const std::vector<std::int32_t>& twin = h.twin;
    const std::size_t n = h.root_count;
    const double diagonal = std::max(h.diagonal, 1e-9);
    tolerance_ = 1e-6 * diagonal;
    const double offset_unit = 1e-6 * diagonal, vertex_unit = 1e-7 * diagonal;

    // Planes: roots sorted by their quantized plane, numbered in that order.
    std::vector<std::pair<Key, std::uint32_t>> keyed(n);
    for (std::uint32_t r = 0; r < n; ++r) {
        const auto [nn, d] = canonical_plane(h, r);
        keyed[r] = {Key{quantize(nn.x, 1e-6), quantize(nn.y, 1e-6), quantize(nn.z, 1e-6),
                        quantize(d, offset_unit)},
                    r};
    }
    std::sort(keyed.begin(), keyed.end());
    root_plane_.assign(n, 0);
    std::vector<std::uint32_t> plane_begin; // into keyed
    for (std::size_t i = 0; i < n; ++i) {
        if (i == 0 || keyed[i].first != keyed[i - 1].first) {
            plane_begin.push_back(std::uint32_t(i));
            const auto [nn, d] = canonical_plane(h, keyed[i].second);
            const Frame f = Frame::from_normal(nn);
            Plane p;
            p.n = nn;
            p.d = d;
            p.u = f.s;
            p.v = f.t;
            planes_.push_back(p);
        }
        root_plane_[keyed[i].second] = std::uint32_t(planes_.size() - 1);
    }
    plane_begin.push_back(std::uint32_t(n));

    cell_segments_begin_.push_back(0);
    cell_triangles_begin_.push_back(0);
    std::vector<std::uint32_t> roots;
    for (std::size_t pi = 0; pi < planes_.size(); ++pi) {
        // The opaque roots; a two-sided surface once: its root of the smaller index.
        roots.clear();
        for (std::uint32_t i = plane_begin[pi]; i < plane_begin[pi + 1]; ++i) {
            const std::uint32_t r = keyed[i].second;
            if (h.opaque[r] && (twin[r] < 0 || std::uint32_t(twin[r]) > r))
                roots.push_back(r);
        }
        add_plane(planes_[pi], h, roots, vertex_unit);
    }
}

void OccluderPlanes::add_plane(Plane& plane, const Hierarchy& h,
                               const std::vector<std::uint32_t>& roots, double unit) {
    // Triangles, counter-clockwise in the plane's frame.
    const std::size_t first_triangle = triangles_.size();
    BBox bounds;
    for (std::uint32_t r : roots) {
        std::array<Point2, 3> t;
        for (std::size_t k = 0; k < 3; ++k) {
            t[k] = project(plane, h.triangle[r][k]);
            bounds.extend(Vec3(t[k].x, t[k].y, 0));
        }
        if (cross2(t[1].x - t[0].x, t[1].y - t[0].y, t[2].x - t[0].x, t[2].y - t[0].y) < 0)
            std::swap(t[1], t[2]);
        triangles_.push_back(t);
    }

    // The grid: about k_cells_per_triangle cells per triangle over the bounds.
    const double w = std::max(bounds.hi.x - bounds.lo.x, tolerance_);
    const double ht = std::max(bounds.hi.y - bounds.lo.y, tolerance_);
    const double count = double(std::max<std::size_t>(roots.size(), 1));
    plane.lo = {bounds.lo.x, bounds.lo.y};
    plane.hi = {bounds.hi.x, bounds.hi.y};
    plane.cell = std::max(std::sqrt(w * ht / (k_cells_per_triangle * count)),
                          std::max(w, ht) / double(k_max_cells_per_axis));
    plane.nx = std::clamp(std::uint32_t(std::ceil(w / plane.cell)), 1u, k_max_cells_per_axis);
    plane.ny = std::clamp(std::uint32_t(std::ceil(ht / plane.cell)), 1u, k_max_cells_per_axis);
    plane.cell_begin = std::uint32_t(cell_triangles_begin_.size() - 1);
    fill_cells(plane, cell_triangles_begin_, cell_triangles_, first_triangle, triangles_.size(),
               [&](std::size_t i) {
                   const auto& t = triangles_[i];
                   return cells_of(
                       plane,
                       {std::min({t[0].x, t[1].x, t[2].x}), std::min({t[0].y, t[1].y, t[2].y})},
                       {std::max({t[0].x, t[1].x, t[2].x}), std::max({t[0].y, t[1].y, t[2].y})});
               });

    // The union's boundary. The triangles' edges cancel where two triangles meet, also where
    // one's edge meets several of the other's (a T-vertex, as where two coplanar surfaces
    // touch): what is left on each line bounds the union or lies inside it, where triangles
    // overlap (a cabinet's back against a wall); of that, what no other triangle covers on
    // its outer side is the boundary.
    struct LinePiece {
        Key key;               ///< the line, quantized
        Point2 d;              ///< its direction (largest component positive)
        double c = 0;          ///< its offset along (−d.y, d.x)
        double s0 = 0, s1 = 0; ///< the edge's extent along d
        double sign = 0;       ///< +1 if the edge runs along d, −1 against
    };
    std::vector<LinePiece> lines;
    for (std::size_t t = first_triangle; t < triangles_.size(); ++t)
        for (std::size_t k = 0; k < 3; ++k) {
            const Point2 p0 = triangles_[t][k], p1 = triangles_[t][(k + 1) % 3];
            const double length = length2(p1.x - p0.x, p1.y - p0.y);
            if (length <= 0)
                continue;
            Point2 d{(p1.x - p0.x) / length, (p1.y - p0.y) / length};
            double sign = 1;
            if (std::abs(d.x) >= std::abs(d.y) ? d.x < 0 : d.y < 0) {
                d = {-d.x, -d.y};
                sign = -1;
            }
            const double c = cross2(d.x, d.y, p0.x, p0.y);
            const double s0 = d.x * p0.x + d.y * p0.y, s1 = d.x * p1.x + d.y * p1.y;
            lines.push_back({Key{quantize(d.x, 1e-6), quantize(d.y, 1e-6), quantize(c, unit), 0}, d,
                             c, std::min(s0, s1), std::max(s0, s1), sign});
        }
    std::sort(lines.begin(), lines.end(), [](const LinePiece& x, const LinePiece& y) {
        return x.key != y.key ? x.key < y.key : x.s0 < y.s0;
    });
    const std::size_t first_segment = segments_.size();
    std::vector<std::pair<double, double>> events; // position along the line, change of cover
    for (std::size_t i = 0; i < lines.size();) {
        std::size_t j = i + 1;
        while (j < lines.size() && lines[j].key == lines[i].key)
            ++j;
        events.clear();
        for (std::size_t k = i; k < j; ++k) {
            events.emplace_back(lines[k].s0, lines[k].sign);
            events.emplace_back(lines[k].s1, -lines[k].sign);
        }
        std::sort(events.begin(), events.end());
        const Point2 d = lines[i].d;
        const double c = lines[i].c;
        auto at = [&](double t) { return Point2{d.x * t - d.y * c, d.y * t + d.x * c}; };
        double cover = 0;
        for (std::size_t k = 0; k + 1 < events.size(); ++k) {
            cover += events[k].second;
            const double s0 = events[k].first, s1 = events[k + 1].first;
            if (std::abs(cover) < 0.5 || s1 - s0 <= tolerance_)
                continue;
            // Triangles along +d have their inside on the left, (−d.y, d.x).
            const Point2 out = cover > 0 ? Point2{d.y, -d.x} : Point2{-d.y, d.x};
            add_uncovered(plane, at(s0), at(s1), out);
        }
        i = j;
    }
    fill_cells(plane, cell_segments_begin_, cell_segments_, first_segment, segments_.size(),
               [&](std::size_t i) {
                   const auto& e = segments_[i];
                   return cells_of(plane, {std::min(e[0].x, e[1].x), std::min(e[0].y, e[1].y)},
                                   {std::max(e[0].x, e[1].x), std::max(e[0].y, e[1].y)});
               });
}

std::array<std::uint32_t, 4> OccluderPlanes::cells_of(const Plane& plane, Point2 lo,
                                                      Point2 hi) const {
    return {grid_coordinate(lo.x - tolerance_, plane.lo.x, plane.cell, plane.nx),
            grid_coordinate(lo.y - tolerance_, plane.lo.y, plane.cell, plane.ny),
            grid_coordinate(hi.x + tolerance_, plane.lo.x, plane.cell, plane.nx),
            grid_coordinate(hi.y + tolerance_, plane.lo.y, plane.cell, plane.ny)};
}

template <typename BoxOf>
void OccluderPlanes::fill_cells(const Plane& plane, std::vector<std::uint32_t>& begin,
                                std::vector<std::uint32_t>& items, std::size_t first,
                                std::size_t last, BoxOf&& box_of) {
    // Counting sort of the (cell, item) pairs.
    const std::size_t cells = std::size_t(plane.nx) * plane.ny;
    const std::size_t base = begin.size() - 1;
    begin.resize(base + cells + 1, 0);
    std::vector<std::uint32_t> counts(cells, 0);
    for (std::size_t i = first; i < last; ++i)
        any_cell(box_of(i), plane.nx, [&](std::size_t c) {
            ++counts[c];
            return false;
        });
    for (std::size_t c = 0; c < cells; ++c)
        begin[base + c + 1] = begin[base + c] + counts[c];
    items.resize(begin.back());
    std::vector<std::uint32_t> next(begin.begin() + std::ptrdiff_t(base), begin.end() - 1);
    for (std::size_t i = first; i < last; ++i)
        any_cell(box_of(i), plane.nx, [&](std::size_t c) {
            items[next[c]++] = std::uint32_t(i);
            return false;
        });
}

void OccluderPlanes::add_uncovered(const Plane& plane, Point2 a, Point2 b, Point2 out) {
    // The parts of the edge, moved off it by twice the tolerance, inside some triangle.
    const Point2 qa{a.x + 2 * tolerance_ * out.x, a.y + 2 * tolerance_ * out.y};
    const Point2 qb{b.x + 2 * tolerance_ * out.x, b.y + 2 * tolerance_ * out.y};
    std::vector<std::pair<double, double>> covered;
    const auto range = cells_of(plane, {std::min(qa.x, qb.x), std::min(qa.y, qb.y)},
                                {std::max(qa.x, qb.x), std::max(qa.y, qb.y)});
    any_cell(range, plane.nx, [&](std::size_t local) {
        const std::size_t cell = plane.cell_begin + local;
        for (std::uint32_t i = cell_triangles_begin_[cell]; i < cell_triangles_begin_[cell + 1];
             ++i) {
            const auto& t = triangles_[cell_triangles_[i]];
            double t0 = 0, t1 = 1;
            for (std::size_t k = 0; k < 3 && t0 < t1; ++k) {
                // Inside a counter-clockwise triangle: left of every edge.
                const Point2 p = t[k], q = t[(k + 1) % 3];
                if (!clip_to_half_plane(cross2(q.x - p.x, q.y - p.y, qa.x - p.x, qa.y - p.y),
                                        cross2(q.x - p.x, q.y - p.y, qb.x - qa.x, qb.y - qa.y), t0,
                                        t1))
                    t1 = -1;
            }
            if (t0 < t1)
                covered.emplace_back(t0, t1);
        }
        return false;
    });
    std::sort(covered.begin(), covered.end());
    const double length = length2(b.x - a.x, b.y - a.y);
    auto point = [&](double t) { return Point2{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)}; };
    double from = 0; // start of the uncovered part
    auto emit = [&](double to) {
        if ((to - from) * length > tolerance_)
            segments_.push_back({point(from), point(to)});
    };
    for (const auto& [t0, t1] : covered) {
        if (t0 > from)
            emit(t0);
        from = std::max(from, t1);
    }
    emit(1.0);
}

bool OccluderPlanes::inside_triangle(std::uint32_t t, Point2 x) const {
    const auto& p = triangles_[t];
    const double area = cross2(p[1].x - p[0].x, p[1].y - p[0].y, p[2].x - p[0].x, p[2].y - p[0].y);
    if (area == 0)
        return false;
    const double sign = area > 0 ? 1.0 : -1.0;
    for (int k = 0; k < 3; ++k) {
        const Point2 a = p[std::size_t(k)], b = p[std::size_t((k + 1) % 3)];
        const double ex = b.x - a.x, ey = b.y - a.y, len = length2(ex, ey);
        if (sign * cross2(ex, ey, x.x - a.x, x.y - a.y) < -tolerance_ * len)
            return false;
    }
    return true;
}

bool OccluderPlanes::blocks(std::uint32_t pi, std::span<const Vec3> a,
                            std::span<const Vec3> b) const {
    const Plane& plane = planes_[pi];
    if (plane.lo.x > plane.hi.x)
        return false; // no opaque triangle in this plane: nothing to block with
    // Where the segments between the points cross the plane; each must lie within the
    // bounds of the plane's triangles (most planes the rays meet are furniture that blocks a
    // part of the shaft).
    thread_local std::vector<Point2> x, hull;
    x.clear();
    bool inside = true;
    auto add = [&](Point2 p) {
        inside = inside && p.x >= plane.lo.x - tolerance_ && p.x <= plane.hi.x + tolerance_ &&
                 p.y >= plane.lo.y - tolerance_ && p.y <= plane.hi.y + tolerance_;
        x.push_back(p);
    };
    for (const Vec3& pa : a) {
        const double da = distance(pi, pa);
        for (const Vec3& pb : b) {
            const double db = distance(pi, pb);
            if (std::abs(da) <= tolerance_ && std::abs(db) <= tolerance_) {
                add(project(plane, pa)); // the segment lies in the plane
                add(project(plane, pb));
            } else if (da * db > 0) {
                return false; // both on one side: not a shaft through the plane
            } else {
                add(project(plane, pa + (pb - pa) * (da / (da - db))));
            }
            if (!inside)
                return false;
        }
    }
    // Their convex hull, counter-clockwise (Andrew's monotone chain).
    std::sort(x.begin(), x.end(),
              [](Point2 p, Point2 q) { return p.x != q.x ? p.x < q.x : p.y < q.y; });
    hull.resize(2 * x.size() + 1);
    std::size_t k = 0;
    auto turn = [](Point2 o, Point2 p, Point2 q) {
        return cross2(p.x - o.x, p.y - o.y, q.x - o.x, q.y - o.y);
    };
    for (std::size_t i = 0; i < x.size(); ++i) {
        while (k >= 2 && turn(hull[k - 2], hull[k - 1], x[i]) <= 0)
            --k;
        hull[k++] = x[i];
    }
    for (std::size_t i = x.size() - 1, lower = k + 1; i-- > 0;) {
        while (k >= lower && turn(hull[k - 2], hull[k - 1], x[i]) <= 0)
            --k;
        hull[k++] = x[i];
    }
    if (k < 4)
        return false; // fewer than three corners: a degenerate shaft proves nothing
    hull.resize(k - 1);
    double area = 0, perimeter = 0;
    Point2 centre;
    for (std::size_t i = 0; i < hull.size(); ++i) {
        const Point2 p = hull[i], q = hull[(i + 1) % hull.size()];
        area += 0.5 * cross2(p.x, p.y, q.x, q.y);
        perimeter += length2(q.x - p.x, q.y - p.y);
        centre.x += p.x / double(hull.size());
        centre.y += p.y / double(hull.size());
    }
    if (area <= 2.0 * tolerance_ * perimeter)
        return false; // thinner than the tolerance: nothing is left inside

    // No boundary edge may enter the hull shrunk by the tolerance (Cyrus–Beck clipping of the
    // edge against the hull's edges moved inward).
    struct Side {
        double nx, ny, offset; ///< inside where nx·x + ny·y >= offset
    };
    thread_local std::vector<Side> sides;
    sides.clear();
    for (std::size_t i = 0; i < hull.size(); ++i) {
        const Point2 p = hull[i], q = hull[(i + 1) % hull.size()];
        const double ex = q.x - p.x, ey = q.y - p.y, len = length2(ex, ey);
        if (len > 0) // inward normal of a counter-clockwise edge: (−ey, ex) / len
            sides.push_back({-ey / len, ex / len, (-ey * p.x + ex * p.y) / len + tolerance_});
    }
    auto enters = [&](const std::array<Point2, 2>& s) {
        double t0 = 0, t1 = 1;
        for (const Side& side : sides)
            if (!clip_to_half_plane(side.nx * s[0].x + side.ny * s[0].y - side.offset,
                                    side.nx * (s[1].x - s[0].x) + side.ny * (s[1].y - s[0].y), t0,
                                    t1) ||
                t0 > t1)
                return false;
        return true;
    };
    double x0 = hull[0].x, x1 = x0, y0 = hull[0].y, y1 = y0;
    for (const Point2& p : hull) {
        x0 = std::min(x0, p.x);
        x1 = std::max(x1, p.x);
        y0 = std::min(y0, p.y);
        y1 = std::max(y1, p.y);
    }
    auto cell_x = [&](double v) { return grid_coordinate(v, plane.lo.x, plane.cell, plane.nx); };
    auto cell_y = [&](double v) { return grid_coordinate(v, plane.lo.y, plane.cell, plane.ny); };
    const bool entered = any_cell(
        {cell_x(x0), cell_y(y0), cell_x(x1), cell_y(y1)}, plane.nx, [&](std::size_t local) {
            const std::size_t c = plane.cell_begin + local;
            for (std::uint32_t i = cell_segments_begin_[c]; i < cell_segments_begin_[c + 1]; ++i)
                if (enters(segments_[cell_segments_[i]]))
                    return true;
            return false;
        });
    if (entered)
        return false;
    // The hull then lies inside the union or outside it: inside if its centre is.
    if (centre.x < plane.lo.x || centre.y < plane.lo.y)
        return false;
    const std::size_t c =
        plane.cell_begin + std::size_t(cell_y(centre.y)) * plane.nx + cell_x(centre.x);
    for (std::uint32_t i = cell_triangles_begin_[c]; i < cell_triangles_begin_[c + 1]; ++i)
        if (inside_triangle(cell_triangles_[i], centre))
            return true;
    return false;
}

} // namespace penumbra::solver
