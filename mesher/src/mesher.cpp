// Mesher v1: scene polygons → patches (one per side of each planar surface) → conforming
// triangle elements. Non-planar polygons are fan-triangulated from their first vertex, as
// path tracers do, each fan triangle becoming a planar surface of its own.

#include "mesher/mesher.h"

#include <cmath>

#include "core/error.h"
#include "polygon_mesh.h"

namespace penumbra::mesher {

namespace {

struct PlanarPiece {
    std::vector<Vec3> outline;
    Vec3 normal;
};

double polygon_size(const std::vector<Vec3>& p) {
    BBox box;
    for (const Vec3& v : p)
        box.extend(v);
    return box.diagonal();
}

std::vector<PlanarPiece> planar_pieces(const Polygon& poly, double tolerance) {
    const Vec3 n = normalize(newell_normal(poly.vertices));
    const double size = polygon_size(poly.vertices);
    double deviation = 0;
    for (const Vec3& v : poly.vertices)
        deviation = std::max(deviation, std::abs(dot(v - poly.vertices[0], n)));
    if (deviation <= tolerance * size)
        return {{poly.vertices, n}};
    std::vector<PlanarPiece> fan;
    for (std::size_t i = 1; i + 1 < poly.vertices.size(); ++i) {
        std::vector<Vec3> tri{poly.vertices[0], poly.vertices[i], poly.vertices[i + 1]};
        Vec3 tn = cross(tri[1] - tri[0], tri[2] - tri[0]);
        if (length(tn) > 1e-12 * size * size)
            fan.push_back({tri, normalize(tn)});
    }
    return fan;
}

double triangle_area(const RadiosityMesh& mesh, const std::array<std::uint32_t, 3>& t) {
    return 0.5 * length(cross(mesh.vertex(t[1]) - mesh.vertex(t[0]),
                              mesh.vertex(t[2]) - mesh.vertex(t[0])));
}

// Appends one side of a surface as a patch; returns the index of its first element.
std::size_t append_patch(RadiosityMesh& mesh, const SurfaceMesh& sm, const Patch& patch) {
    const auto patch_id = std::uint32_t(mesh.patches.size());
    mesh.patches.push_back(patch);
    const auto base = std::uint32_t(mesh.positions.size());
    for (const Vec3& p : sm.points) {
        mesh.positions.push_back(Vec3f(p));
        mesh.vertex_patch.push_back(patch_id);
    }
    const std::size_t first = mesh.triangles.size();
    for (const auto& t : sm.triangles) {
        std::array<std::uint32_t, 3> tri = patch.back
                                               ? std::array<std::uint32_t, 3>{t[0], t[2], t[1]}
                                               : t;
        for (auto& v : tri)
            v += base;
        mesh.triangles.push_back(tri);
        mesh.element_patch.push_back(patch_id);
        mesh.element_twin.push_back(-1);
        mesh.element_area.push_back(triangle_area(mesh, tri));
        mesh.element_level.push_back(0);
    }
    return first;
}

void add_surface(RadiosityMesh& mesh, const Scene& scene, std::uint32_t polygon_index,
                 std::uint32_t surface_id, const PlanarPiece& piece, const SurfaceMesh& sm) {
    const Polygon& poly = scene.polygons[polygon_index];
    const Material& mat = scene.materials[poly.material];
    Patch front;
    front.polygon = polygon_index;
    front.surface = surface_id;
    front.material = poly.material;
    front.normal = piece.normal;
    front.reflectance = mat.reflectance;
    front.emission = mat.emission * float(k_pi);
    const std::size_t first_front = append_patch(mesh, sm, front);
    for (std::size_t e = first_front; e < mesh.triangles.size(); ++e)
        mesh.geometry_elements.push_back(std::uint32_t(e));
    if (!mat.two_sided)
        return;
    Patch back = front;
    back.back = true;
    back.normal = -piece.normal;
    back.emission = mat.emission_two_sided ? front.emission : Rgb{};
    const std::size_t first_back = append_patch(mesh, sm, back);
    for (std::size_t i = 0; i < sm.triangles.size(); ++i) {
        mesh.element_twin[first_front + i] = std::int32_t(first_back + i);
        mesh.element_twin[first_back + i] = std::int32_t(first_front + i);
    }
}

} // namespace

RadiosityMesh build_mesh(const Scene& scene, const Context& ctx) {
    RadiosityMesh mesh;
    mesh.scene_diagonal = scene.bounds().diagonal();
    const double max_edge = scene.mesher.max_edge_length > 0 ? scene.mesher.max_edge_length
                                                              : mesh.scene_diagonal / 20.0;
    if (!(max_edge > 0))
        throw InputError(scene.file, "mesher.max_edge_length", "scene has no extent to mesh");
    std::uint32_t surface_id = 0;
    for (std::uint32_t pi = 0; pi < scene.polygons.size(); ++pi) {
        const Polygon& poly = scene.polygons[pi];
        for (const PlanarPiece& piece : planar_pieces(poly, scene.mesher.planarity_tolerance)) {
            SurfaceMesh sm = mesh_planar_polygon(piece.outline, piece.normal, max_edge);
            if (sm.triangles.empty())
                throw InputError(poly.source, "",
                                 "cannot triangulate polygon '" + poly.name +
                                     "': it intersects itself or has collinear vertices only");
            add_surface(mesh, scene, pi, surface_id++, piece, sm);
        }
    }
    ctx.info("mesh: {} polygons -> {} surfaces, {} patches, {} elements, {} vertices "
             "(max edge {:.4g} m)",
             scene.polygons.size(), surface_id, mesh.patches.size(), mesh.element_count(),
             mesh.vertex_count(), max_edge);
    return mesh;
}

} // namespace penumbra::mesher
