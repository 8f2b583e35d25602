// Planar surfaces from scene polygons, with near-contacts closed first: a vertex within the
// contact tolerance of another surface's plane (and above that surface) moves onto that plane
// along its own polygon's plane, by the smallest such move (min-norm solution of at most three
// plane equations). A wall floating 1 mm above a floor thus stands on it, so no ray and no
// element can see through the gap.

#include "surfaces.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "core/material.h"
#include "surface_bvh.h"

namespace penumbra::mesher {

Vec3 newell_normal(const std::vector<Vec3>& p) {
    Vec3 n;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const Vec3& a = p[i];
        const Vec3& b = p[(i + 1) % p.size()];
        n += Vec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    return n;
}

bool make_surface(const std::vector<Vec3>& outline, Surface& out) {
    BBox box;
    for (const Vec3& v : outline)
        box.extend(v);
    const Vec3 n = newell_normal(outline);
    const double size = box.diagonal();
    if (outline.size() < 3 || !(length(n) > 1e-12 * size * size))
        return false;
    out.normal = normalize(n);
    out.offset = 0;
    for (const Vec3& v : outline)
        out.offset += dot(out.normal, v);
    out.offset /= double(outline.size());
    // The longest edge gives the best-conditioned in-plane axis.
    Vec3 longest;
    for (std::size_t i = 0; i < outline.size(); ++i) {
        Vec3 e = outline[(i + 1) % outline.size()] - outline[i];
        e -= out.normal * dot(e, out.normal);
        if (length(e) > length(longest))
            longest = e;
    }
    out.axis_u = normalize(longest);
    out.axis_v = cross(out.normal, out.axis_u);
    out.origin = outline[0] - out.normal * out.distance(outline[0]);
    out.outline = outline;
    out.outline2d.clear();
    for (const Vec3& v : outline)
        out.outline2d.push_back(out.to_2d(v));
    out.box = box;
    out.area = signed_area(out.outline2d);
    return out.area > 0;
}

namespace {

// Solves the symmetric system g·y = b (size ≤ 3) by Gaussian elimination; false if singular.
bool solve_small(std::array<std::array<double, 3>, 3> g, std::array<double, 3> b, std::size_t n,
                 std::array<double, 3>& y) {
    for (std::size_t c = 0; c < n; ++c) {
        std::size_t pivot = c;
        for (std::size_t r = c + 1; r < n; ++r)
            if (std::abs(g[r][c]) > std::abs(g[pivot][c]))
                pivot = r;
        if (std::abs(g[pivot][c]) < 1e-12)
            return false;
        std::swap(g[c], g[pivot]);
        std::swap(b[c], b[pivot]);
        for (std::size_t r = c + 1; r < n; ++r) {
            const double f = g[r][c] / g[c][c];
            for (std::size_t k = c; k < n; ++k)
                g[r][k] -= f * g[c][k];
            b[r] -= f * b[c];
        }
    }
    for (std::size_t c = n; c-- > 0;) {
        double s = b[c];
        for (std::size_t k = c + 1; k < n; ++k)
            s -= g[c][k] * y[k];
        y[c] = s / g[c][c];
    }
    return true;
}

struct PlaneRow {
    Vec3 normal;
    double rhs; ///< required change of dot(normal, v)
};

// Smallest move x with dot(row.normal, x) = row.rhs for every row.
bool min_norm_move(const std::vector<PlaneRow>& rows, Vec3& x) {
    const std::size_t n = rows.size();
    std::array<std::array<double, 3>, 3> g{};
    std::array<double, 3> b{}, y{};
    for (std::size_t i = 0; i < n; ++i) {
        b[i] = rows[i].rhs;
        for (std::size_t j = 0; j < n; ++j)
            g[i][j] = dot(rows[i].normal, rows[j].normal);
    }
    if (!solve_small(g, b, n, y))
        return false;
    x = Vec3();
    for (std::size_t i = 0; i < n; ++i)
        x += rows[i].normal * y[i];
    return true;
}

struct Candidate {
    double distance; ///< signed distance of the vertex to the plane
    std::uint32_t surface;
};

// Planes within the tolerance of v whose surface lies under v (its projection is inside).
std::vector<Candidate> nearby_planes(const std::vector<Surface>& pre, const SurfaceBvh& bvh,
                                     const Vec3& v, std::uint32_t own_polygon, double tol) {
    BBox query;
    query.extend(v - Vec3(tol, tol, tol));
    query.extend(v + Vec3(tol, tol, tol));
    std::vector<Candidate> out;
    for (std::uint32_t s : bvh.overlapping(query)) {
        const Surface& surface = pre[s];
        if (surface.polygon == own_polygon)
            continue;
        const double d = surface.distance(v);
        if (std::abs(d) > tol)
            continue;
        const Vec2 q = surface.to_2d(v - surface.normal * d);
        if (point_in_polygon(q, surface.outline2d) ||
            distance_to_boundary(q, surface.outline2d) <= tol)
            out.push_back({d, s});
    }
    std::sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) {
        return std::abs(a.distance) < std::abs(b.distance) ||
               (std::abs(a.distance) == std::abs(b.distance) && a.surface < b.surface);
    });
    return out;
}

// The vertex moved onto the nearby planes it can reach inside its own plane.
Vec3 snapped_vertex(const std::vector<Surface>& pre, const SurfaceBvh& bvh, const Vec3& v,
                    const Vec3& own_normal, std::uint32_t own_polygon, const MeshParams& params) {
    const std::vector<Candidate> near = nearby_planes(pre, bvh, v, own_polygon, params.contact_tol);
    std::vector<PlaneRow> rows{{own_normal, 0.0}};
    std::vector<Vec3> basis{own_normal};
    bool moves = false;
    for (const Candidate& c : near) {
        if (rows.size() == 3)
            break;
        Vec3 r = pre[c.surface].normal;
        for (const Vec3& e : basis)
            r -= e * dot(r, e);
        if (length(r) < 0.25) // (nearly) parallel to planes already kept
            continue;
        basis.push_back(normalize(r));
        rows.push_back({pre[c.surface].normal, -c.distance});
        moves = moves || std::abs(c.distance) > params.snap;
    }
    Vec3 x;
    if (!moves || !min_norm_move(rows, x) || length(x) > 4 * params.contact_tol)
        return v;
    return v + x;
}

struct PlanarPiece {
    std::vector<Vec3> outline;
    bool fan = false;
};

std::vector<PlanarPiece> planar_pieces(const std::vector<Vec3>& vertices, double tolerance) {
    Surface whole;
    if (!make_surface(vertices, whole))
        return {};
    double deviation = 0;
    for (const Vec3& v : vertices)
        deviation = std::max(deviation, std::abs(whole.distance(v)));
    if (deviation <= tolerance * whole.box.diagonal())
        return {{vertices, false}};
    std::vector<PlanarPiece> fan;
    for (std::size_t i = 1; i + 1 < vertices.size(); ++i)
        fan.push_back({{vertices[0], vertices[i], vertices[i + 1]}, true});
    return fan;
}

// The polygons' vertices with near-contacts closed (see the file comment). Vertices snap to
// the planes of the planar pieces (fan triangles of non-planar polygons), so that a vertex
// lying on a piece stays put.
std::vector<std::vector<Vec3>> close_near_contacts(const Scene& scene, const MeshParams& params) {
    std::vector<std::vector<Vec3>> out;
    std::vector<Surface> pieces;
    std::vector<Vec3> own_normal(scene.polygons.size());
    for (std::uint32_t pi = 0; pi < scene.polygons.size(); ++pi) {
        const std::vector<Vec3>& vertices = scene.polygons[pi].vertices;
        out.push_back(vertices);
        Surface whole;
        if (make_surface(vertices, whole))
            own_normal[pi] = whole.normal;
        for (const PlanarPiece& piece : planar_pieces(vertices, scene.mesher.planarity_tolerance)) {
            Surface s;
            if (!make_surface(piece.outline, s))
                continue;
            s.polygon = pi;
            s.id = std::uint32_t(pieces.size());
            pieces.push_back(std::move(s));
        }
    }
    if (!params.split_contacts || params.contact_tol <= 0)
        return out;
    const SurfaceBvh bvh(pieces);
    for (std::uint32_t pi = 0; pi < scene.polygons.size(); ++pi) {
        if (length(own_normal[pi]) == 0)
            continue;
        for (std::size_t k = 0; k < out[pi].size(); ++k) // from the original positions only
            out[pi][k] = snapped_vertex(pieces, bvh, scene.polygons[pi].vertices[k], own_normal[pi],
                                        pi, params);
    }
    return out;
}

} // namespace

std::vector<Surface> build_surfaces(const Scene& scene, const MeshParams& params,
                                    const Context& ctx) {
    const std::vector<std::vector<Vec3>> vertices = close_near_contacts(scene, params);
    std::vector<Surface> surfaces;
    for (std::uint32_t pi = 0; pi < scene.polygons.size(); ++pi) {
        const Polygon& poly = scene.polygons[pi];
        const RadiosityResponse response = radiosity_response(scene.materials[poly.material]);
        const std::string name = fmt::format("'{}' ({})", poly.name, poly.source);
        const auto pieces = planar_pieces(vertices[pi], scene.mesher.planarity_tolerance);
        Surface original;
        if (pieces.empty() && !make_surface(poly.vertices, original))
            ctx.warn("mesh: polygon {} has zero area (collinear or repeated vertices); skipped",
                     name);
        else if (pieces.empty())
            ctx.warn("mesh: polygon {} is thinner than mesher.contact_tolerance and collapses "
                     "when near-contacts are closed; skipped",
                     name);
        for (const PlanarPiece& piece : pieces) {
            Surface s;
            if (!make_surface(piece.outline, s))
                continue; // a degenerate fan triangle: nothing to mesh
            s.polygon = pi;
            s.id = std::uint32_t(surfaces.size());
            s.two_sided = response.two_sided;
            s.emits_front = !response.emission.is_black();
            s.emits_back = s.emits_front && response.emission_two_sided;
            s.opaque = response.opaque();
            s.name = name;
            surfaces.push_back(std::move(s));
        }
    }
    return surfaces;
}

double estimated_elements(const std::vector<Surface>& surfaces, double max_edge) {
    double n = 0;
    for (const Surface& s : surfaces)
        n += (s.two_sided ? 2.0 : 1.0) * 2.0 * s.area / (max_edge * max_edge);
    return n;
}

} // namespace penumbra::mesher
