// Surface triangulation for mesher v1: structured grids for convex quadrilaterals, uniform
// k-subdivision for triangles, ear clipping + longest-edge bisection (Rivara) with OpenMesh
// for everything else. Each result is conforming (no T-vertices) inside the surface.

#include "polygon_mesh.h"

#include <algorithm>
#include <cmath>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LongestEdgeT.hh>

#include "core/error.h"

namespace penumbra::mesher {

namespace {

struct DoubleTraits : OpenMesh::DefaultTraits {
    using Point = OpenMesh::Vec3d;
    using Normal = OpenMesh::Vec3d;
};
using TriMesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

int segments_for(double length, double max_edge) {
    return std::max(1, int(std::ceil(length / max_edge - 1e-9)));
}

bool is_convex(const std::vector<Vec3>& p, const Vec3& normal) {
    const std::size_t n = p.size();
    for (std::size_t i = 0; i < n; ++i) {
        Vec3 a = p[i], b = p[(i + 1) % n], c = p[(i + 2) % n];
        if (dot(cross(b - a, c - b), normal) <= 0)
            return false;
    }
    return true;
}

SurfaceMesh grid_quad(const std::vector<Vec3>& q, double max_edge) {
    const int nu = segments_for(std::max(length(q[1] - q[0]), length(q[2] - q[3])), max_edge);
    const int nv = segments_for(std::max(length(q[3] - q[0]), length(q[2] - q[1])), max_edge);
    SurfaceMesh m;
    for (int j = 0; j <= nv; ++j) {
        double v = double(j) / nv;
        for (int i = 0; i <= nu; ++i) {
            double u = double(i) / nu;
            m.points.push_back(q[0] * ((1 - u) * (1 - v)) + q[1] * (u * (1 - v)) + q[2] * (u * v) +
                               q[3] * ((1 - u) * v));
        }
    }
    auto id = [nu](int i, int j) { return std::uint32_t(j * (nu + 1) + i); };
    for (int j = 0; j < nv; ++j) {
        for (int i = 0; i < nu; ++i) {
            std::uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
            // Split each cell along its shorter diagonal.
            if (length(m.points[c] - m.points[a]) <= length(m.points[d] - m.points[b])) {
                m.triangles.push_back({a, b, c});
                m.triangles.push_back({a, c, d});
            } else {
                m.triangles.push_back({a, b, d});
                m.triangles.push_back({b, c, d});
            }
        }
    }
    return m;
}

SurfaceMesh subdivide_triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2, double max_edge) {
    const double longest = std::max({length(p1 - p0), length(p2 - p1), length(p0 - p2)});
    const int k = segments_for(longest, max_edge);
    SurfaceMesh m;
    // Row j holds k − j + 1 points p0 + (i/k)(p1 − p0) + (j/k)(p2 − p0).
    std::vector<std::uint32_t> row_start;
    for (int j = 0; j <= k; ++j) {
        row_start.push_back(std::uint32_t(m.points.size()));
        for (int i = 0; i <= k - j; ++i)
            m.points.push_back(p0 + (p1 - p0) * (double(i) / k) + (p2 - p0) * (double(j) / k));
    }
    for (int j = 0; j < k; ++j) {
        for (int i = 0; i < k - j; ++i) {
            std::uint32_t a = row_start[j] + i, b = a + 1, c = row_start[j + 1] + i;
            m.triangles.push_back({a, b, c});
            if (i + 1 < k - j)
                m.triangles.push_back({b, c + 1, c});
        }
    }
    return m;
}

// Ear clipping in the polygon's plane; returns triangles as index triples into \p p.
std::vector<std::array<std::uint32_t, 3>> ear_clip(const std::vector<Vec3>& p, const Vec3& n) {
    std::vector<std::uint32_t> idx(p.size());
    for (std::uint32_t i = 0; i < idx.size(); ++i)
        idx[i] = i;
    std::vector<std::array<std::uint32_t, 3>> tris;
    auto inside = [&](const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
        return dot(cross(b - a, q - a), n) >= 0 && dot(cross(c - b, q - b), n) >= 0 &&
               dot(cross(a - c, q - c), n) >= 0;
    };
    std::size_t guard = 0;
    while (idx.size() > 3 && guard++ < p.size() * p.size()) {
        bool clipped = false;
        for (std::size_t k = 0; k < idx.size() && !clipped; ++k) {
            std::uint32_t ia = idx[(k + idx.size() - 1) % idx.size()], ib = idx[k],
                          ic = idx[(k + 1) % idx.size()];
            if (dot(cross(p[ib] - p[ia], p[ic] - p[ib]), n) <= 0)
                continue; // reflex or degenerate corner
            bool ear = true;
            for (std::uint32_t other : idx)
                if (other != ia && other != ib && other != ic &&
                    inside(p[other], p[ia], p[ib], p[ic]))
                    ear = false;
            if (!ear)
                continue;
            tris.push_back({ia, ib, ic});
            idx.erase(idx.begin() + std::ptrdiff_t(k));
            clipped = true;
        }
        if (!clipped)
            return {};
    }
    if (idx.size() == 3)
        tris.push_back({idx[0], idx[1], idx[2]});
    return tris;
}

SurfaceMesh refine_with_openmesh(const std::vector<Vec3>& p,
                                 const std::vector<std::array<std::uint32_t, 3>>& tris,
                                 double max_edge) {
    TriMesh tm;
    std::vector<TriMesh::VertexHandle> vh;
    for (const Vec3& v : p)
        vh.push_back(tm.add_vertex(TriMesh::Point(v.x, v.y, v.z)));
    for (const auto& t : tris)
        if (!tm.add_face(vh[t[0]], vh[t[1]], vh[t[2]]).is_valid())
            throw InternalError("mesher: ear clipping produced a non-manifold triangle fan");
    OpenMesh::Subdivider::Uniform::LongestEdgeT<TriMesh, double> splitter;
    splitter.set_max_edge_length(max_edge);
    splitter.attach(tm);
    splitter(1);
    splitter.detach();
    SurfaceMesh m;
    for (auto v : tm.vertices()) {
        const auto& q = tm.point(v);
        m.points.emplace_back(q[0], q[1], q[2]);
    }
    for (auto f : tm.faces()) {
        std::array<std::uint32_t, 3> t{};
        int k = 0;
        for (auto v : tm.fv_range(f))
            t[k++] = std::uint32_t(v.idx());
        m.triangles.push_back(t);
    }
    return m;
}

} // namespace

Vec3 newell_normal(const std::vector<Vec3>& p) {
    Vec3 n;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const Vec3& a = p[i];
        const Vec3& b = p[(i + 1) % p.size()];
        n += Vec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    return n;
}

SurfaceMesh mesh_planar_polygon(const std::vector<Vec3>& outline, const Vec3& normal,
                                double max_edge) {
    if (outline.size() == 3)
        return subdivide_triangle(outline[0], outline[1], outline[2], max_edge);
    if (outline.size() == 4 && is_convex(outline, normal))
        return grid_quad(outline, max_edge);
    auto tris = ear_clip(outline, normal);
    if (tris.empty())
        return {};
    return refine_with_openmesh(outline, tris, max_edge);
}

} // namespace penumbra::mesher
