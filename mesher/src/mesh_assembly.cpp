#include "mesh_assembly.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <fmt/format.h>

#include "core/error.h"

namespace penumbra::mesher {

namespace {

double area_2d(const SideMesh& side, const std::array<std::uint32_t, 3>& t) {
    const Vec2 a = side.points[t[0]], b = side.points[t[1]], c = side.points[t[2]];
    return 0.5 * std::abs(cross(b - a, c - a));
}

// Appends one side as a patch; returns the element of each face (-1 where absent).
std::vector<std::int32_t> append_side(RadiosityMesh& mesh, const Surface& s, const SideMesh& side,
                                      const Patch& patch, std::size_t face_count) {
    std::vector<std::int32_t> element_of(face_count, -1);
    if (side.triangles.empty())
        return element_of;
    const auto patch_id = std::uint32_t(mesh.patches.size());
    mesh.patches.push_back(patch);
    const auto base = std::uint32_t(mesh.positions.size());
    for (const Vec2& p : side.points) {
        mesh.positions.push_back(Vec3f(s.to_3d(p)));
        mesh.vertex_patch.push_back(patch_id);
    }
    for (std::size_t i = 0; i < side.triangles.size(); ++i) {
        const auto& t = side.triangles[i];
        std::array<std::uint32_t, 3> tri = patch.back ? std::array<std::uint32_t, 3>{t[0], t[2], t[1]}
                                                      : t;
        for (auto& v : tri)
            v += base;
        element_of[side.face[i]] = std::int32_t(mesh.triangles.size());
        mesh.triangles.push_back(tri);
        mesh.element_patch.push_back(patch_id);
        mesh.element_twin.push_back(-1);
        mesh.element_area.push_back(area_2d(side, t));
        mesh.element_level.push_back(0);
    }
    return element_of;
}

} // namespace

void append_surface(RadiosityMesh& mesh, const Scene& scene, const Surface& s,
                    const SurfaceTriangulation& tri) {
    const Polygon& poly = scene.polygons[s.polygon];
    const Material& mat = scene.materials[poly.material];
    Patch front;
    front.polygon = s.polygon;
    front.surface = s.id;
    front.material = poly.material;
    front.normal = s.normal;
    front.reflectance = mat.reflectance;
    front.emission = mat.emission * float(k_pi);
    Patch back = front;
    back.back = true;
    back.normal = -s.normal;
    back.emission = mat.emission_two_sided ? front.emission : Rgb{};
    const auto f = append_side(mesh, s, tri.sides[0], front, tri.face_count);
    const auto b = s.two_sided ? append_side(mesh, s, tri.sides[1], back, tri.face_count)
                               : std::vector<std::int32_t>(tri.face_count, -1);
    for (std::size_t i = 0; i < tri.face_count; ++i) {
        if (f[i] >= 0 && b[i] >= 0) {
            mesh.element_twin[std::size_t(f[i])] = b[i];
            mesh.element_twin[std::size_t(b[i])] = f[i];
        }
        if (f[i] >= 0 || b[i] >= 0)
            mesh.geometry_elements.push_back(std::uint32_t(f[i] >= 0 ? f[i] : b[i]));
    }
    mesh.surfaces.push_back({s.polygon, s.area, tri.sides[0].hidden_area,
                             s.two_sided ? tri.sides[1].hidden_area : 0.0});
}

void check_patches(const RadiosityMesh& mesh) {
    using TriMesh = OpenMesh::TriMesh_ArrayKernelT<>;
    std::vector<std::vector<std::uint32_t>> elements(mesh.patches.size());
    for (std::size_t e = 0; e < mesh.element_count(); ++e)
        elements[mesh.element_patch[e]].push_back(std::uint32_t(e));
    for (std::size_t p = 0; p < elements.size(); ++p) {
        TriMesh tm;
        std::vector<TriMesh::VertexHandle> handle(mesh.vertex_count());
        for (std::uint32_t e : elements[p]) {
            std::array<TriMesh::VertexHandle, 3> vh;
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t v = mesh.triangles[e][std::size_t(k)];
                if (!handle[v].is_valid())
                    handle[v] = tm.add_vertex(TriMesh::Point(0, 0, 0));
                vh[std::size_t(k)] = handle[v];
            }
            if (!tm.add_face(vh[0], vh[1], vh[2]).is_valid())
                throw InternalError(fmt::format("mesher: patch {} (surface {}) is not a manifold "
                                                "triangle mesh at element {}",
                                                p, mesh.patches[p].surface, e));
        }
    }
}

} // namespace penumbra::mesher
