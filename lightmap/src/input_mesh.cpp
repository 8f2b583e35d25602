// Input polygons → welded triangle mesh. Planar polygons are ear-clipped in their plane
// (concave ones included); non-planar ones are split into the fan from vertex 0, the same
// triangles the mesher makes of them (mesher/src/surfaces.cpp), so texel normals match the
// radiosity patches'.

#include "input_mesh.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <unordered_map>

#include "uv_geometry.h"

namespace penumbra::lightmap {

namespace {

Vec3 newell_normal(const std::vector<Vec3>& v) {
    Vec3 n;
    for (std::size_t i = 0; i < v.size(); ++i)
        n += cross(v[i], v[(i + 1) % v.size()]);
    return n;
}

double diagonal(const std::vector<Vec3>& vertices) {
    BBox box;
    for (const Vec3& v : vertices)
        box.extend(v);
    return box.diagonal();
}

// Inside or on the boundary, with a margin relative to the triangle's area: a reflex vertex
// on an ear's diagonal, a hair outside after rounding, must still block it (or the ring ends
// in a degenerate triangle and a T-junction).
bool inside_closed(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
    const double margin = -1e-9 * orient(a, b, c);
    return orient(a, b, p) >= margin && orient(b, c, p) >= margin && orient(c, a, p) >= margin;
}

// An ear: a convex corner whose triangle holds no other vertex of the ring.
bool is_ear(const std::vector<Vec2>& p, const std::vector<std::uint32_t>& ring, std::size_t i) {
    const std::size_t n = ring.size();
    const std::uint32_t a = ring[(i + n - 1) % n], b = ring[i], c = ring[(i + 1) % n];
    if (orient(p[a], p[b], p[c]) <= 0)
        return false;
    for (std::uint32_t k : ring) {
        if (k == a || k == b || k == c)
            continue;
        const Vec2& q = p[k];
        const bool coincident = (q.x == p[a].x && q.y == p[a].y) ||
                                (q.x == p[b].x && q.y == p[b].y) ||
                                (q.x == p[c].x && q.y == p[c].y);
        if (!coincident && inside_closed(q, p[a], p[b], p[c]))
            return false;
    }
    return true;
}

std::vector<std::array<std::uint32_t, 3>> ear_clip(const std::vector<Vec2>& p) {
    std::vector<std::uint32_t> ring(p.size());
    for (std::uint32_t i = 0; i < ring.size(); ++i)
        ring[i] = i;
    std::vector<std::array<std::uint32_t, 3>> out;
    while (ring.size() > 3) {
        const std::size_t n = ring.size();
        std::size_t i = 0;
        while (i < n && !is_ear(p, ring, i))
            ++i;
        if (i == n) {
            // No ear left (a self-touching or numerically flat ring): the fan of what remains.
            for (std::size_t k = 1; k + 1 < n; ++k)
                out.push_back({ring[0], ring[k], ring[k + 1]});
            return out;
        }
        out.push_back({ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]});
        ring.erase(ring.begin() + std::ptrdiff_t(i));
    }
    out.push_back({ring[0], ring[1], ring[2]});
    return out;
}

// Greedy welding on a hash grid of cell size = tolerance: each vertex joins the first earlier
// representative within the tolerance, so the result depends only on the input order.
class Welder {
public:
    explicit Welder(double tolerance) : tol_(tolerance > 0 ? tolerance : 0) {}

    std::uint32_t add(const Vec3& p, std::vector<Vec3>& positions) {
        const Cell c = cell_of(p);
        for (std::int64_t dx = -1; dx <= 1; ++dx)
            for (std::int64_t dy = -1; dy <= 1; ++dy)
                for (std::int64_t dz = -1; dz <= 1; ++dz) {
                    auto it = grid_.find({c[0] + dx, c[1] + dy, c[2] + dz});
                    if (it == grid_.end())
                        continue;
                    for (std::uint32_t v : it->second)
                        if (length(positions[v] - p) <= tol_)
                            return v;
                }
        const auto id = std::uint32_t(positions.size());
        positions.push_back(p);
        grid_[c].push_back(id);
        return id;
    }

private:
    using Cell = std::array<std::int64_t, 3>;
    struct CellHash {
        std::size_t operator()(const Cell& c) const {
            return std::size_t(c[0] * 73856093) ^ std::size_t(c[1] * 19349663) ^
                   std::size_t(c[2] * 83492791);
        }
    };
    Cell cell_of(const Vec3& p) const {
        const double s = tol_ > 0 ? 1.0 / tol_ : 1e12;
        return {std::int64_t(std::floor(p.x * s)), std::int64_t(std::floor(p.y * s)),
                std::int64_t(std::floor(p.z * s))};
    }
    double tol_;
    std::unordered_map<Cell, std::vector<std::uint32_t>, CellHash> grid_;
};

void link_neighbours(InputMesh& mesh) {
    struct Edge {
        std::uint32_t lo, hi, triangle, k;
        bool forward; // lo → hi in the triangle's order
    };
    std::vector<Edge> edges;
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
        for (std::uint32_t k = 0; k < 3; ++k) {
            const std::uint32_t a = mesh.triangles[t].corners[k];
            const std::uint32_t b = mesh.triangles[t].corners[(k + 1) % 3];
            edges.push_back({std::min(a, b), std::max(a, b), t, k, a < b});
        }
    std::sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) {
        return std::tie(a.lo, a.hi, a.triangle, a.k) < std::tie(b.lo, b.hi, b.triangle, b.k);
    });
    mesh.neighbours.assign(mesh.triangles.size(), {});
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi)
            ++j;
        const Edge& a = edges[i];
        const Edge& b = edges[i + 1 < j ? i + 1 : i];
        if (j - i == 2 && a.forward != b.forward &&
            mesh.triangles[a.triangle].object == mesh.triangles[b.triangle].object) {
            mesh.neighbours[a.triangle][a.k] = b.triangle;
            mesh.neighbours[b.triangle][b.k] = a.triangle;
        }
        i = j;
    }
}

} // namespace

std::optional<Vec3> planar_normal(const std::vector<Vec3>& vertices, double planarity_tolerance) {
    const Vec3 n = newell_normal(vertices);
    const double size = diagonal(vertices);
    if (vertices.size() < 3 || !(length(n) > 1e-12 * size * size))
        return std::nullopt;
    const Vec3 unit = normalize(n);
    double offset = 0;
    for (const Vec3& v : vertices)
        offset += dot(unit, v);
    offset /= double(vertices.size());
    for (const Vec3& v : vertices)
        if (std::abs(dot(unit, v) - offset) > planarity_tolerance * size)
            return std::nullopt;
    return unit;
}

std::vector<std::array<std::uint32_t, 3>> triangulate_polygon(const std::vector<Vec3>& vertices,
                                                              double planarity_tolerance) {
    std::vector<std::array<std::uint32_t, 3>> triangles;
    if (const std::optional<Vec3> n = planar_normal(vertices, planarity_tolerance)) {
        const Frame frame = Frame::from_normal(*n);
        std::vector<Vec2> p;
        for (const Vec3& v : vertices)
            p.push_back({dot(v, frame.s), dot(v, frame.t)});
        triangles = ear_clip(p);
    } else {
        for (std::uint32_t i = 1; i + 1 < vertices.size(); ++i)
            triangles.push_back({0, i, i + 1});
    }
    const double size = diagonal(vertices);
    std::erase_if(triangles, [&](const std::array<std::uint32_t, 3>& t) {
        const Vec3 n = cross(vertices[t[1]] - vertices[t[0]], vertices[t[2]] - vertices[t[0]]);
        return !(length(n) > 1e-12 * size * size);
    });
    return triangles;
}

InputMesh build_input_mesh(const Scene& scene, const std::vector<std::uint32_t>& polygon_ids,
                           double weld_tolerance) {
    InputMesh mesh;
    Welder welder(weld_tolerance);
    std::map<std::string, std::uint32_t> object_ids;
    const double tolerance = scene.mesher.planarity_tolerance;
    for (std::uint32_t pi : polygon_ids) {
        const Polygon& polygon = scene.polygons[pi];
        const auto triangles = triangulate_polygon(polygon.vertices, tolerance);
        if (triangles.empty()) {
            ++mesh.skipped_polygons;
            continue;
        }
        const auto [it, added] =
            object_ids.try_emplace(polygon.name, std::uint32_t(mesh.objects.size()));
        if (added)
            mesh.objects.push_back(polygon.name);
        const std::optional<Vec3> plane = planar_normal(polygon.vertices, tolerance);
        for (const auto& t : triangles) {
            InputTriangle tri;
            tri.polygon = pi;
            tri.object = it->second;
            const Vec3 n = cross(polygon.vertices[t[1]] - polygon.vertices[t[0]],
                                 polygon.vertices[t[2]] - polygon.vertices[t[0]]);
            tri.area_m2 = 0.5 * length(n);
            tri.normal = plane ? *plane : normalize(n);
            for (int k = 0; k < 3; ++k)
                tri.corners[std::size_t(k)] =
                    welder.add(polygon.vertices[t[std::size_t(k)]], mesh.positions);
            const auto& c = tri.corners;
            if (c[0] != c[1] && c[1] != c[2] && c[2] != c[0]) // else smaller than the weld
                mesh.triangles.push_back(tri);
        }
    }
    link_neighbours(mesh);
    mesh.collinear_neighbours = find_collinear_neighbours(mesh, weld_tolerance);
    return mesh;
}

} // namespace penumbra::lightmap
