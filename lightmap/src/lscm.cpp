// Least squares conformal maps (Lévy, Petitjean, Ray & Maillot 2002) through CGAL 5.5's
// Surface_mesh_parameterization: a free border with two pinned vertices (CGAL's
// Two_vertices_parameterizer_3, the extremes along the longest axis), solved with Eigen.
// LSCM does not guarantee a one-to-one map, so the caller checks flips and overlaps.

#include <cmath>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include "chart_draft.h"

namespace penumbra::lightmap {

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using VertexIndex = SurfaceMesh::Vertex_index;
namespace SMP = CGAL::Surface_mesh_parameterization;

// The draft as a CGAL surface mesh; false when a face would make it non-manifold.
bool build_surface_mesh(const InputMesh& mesh, const ChartDraft& draft, SurfaceMesh& out,
                        std::vector<VertexIndex>& vertices) {
    for (std::uint32_t v : draft.vertices) {
        const Vec3& p = mesh.positions[v];
        vertices.push_back(out.add_vertex(Kernel::Point_3(p.x, p.y, p.z)));
    }
    for (const auto& c : draft.corners)
        if (out.add_face(vertices[c[0]], vertices[c[1]], vertices[c[2]]) ==
            SurfaceMesh::null_face())
            return false;
    return true;
}

// Uniform scale to the 3D area, mirrored if the map came out clockwise.
bool normalise_area(const InputMesh& mesh, ChartDraft& draft) {
    double uv_area = 0, area = 0;
    for (std::size_t i = 0; i < draft.triangles.size(); ++i) {
        uv_area += signed_area(draft.uv_triangle(i));
        area += mesh.triangles[draft.triangles[i]].area_m2;
    }
    const double mirror = uv_area < 0 ? -1.0 : 1.0;
    if (!(std::abs(uv_area) > 0) || !std::isfinite(uv_area))
        return false;
    const double scale = std::sqrt(area / std::abs(uv_area));
    for (Vec2& p : draft.uv)
        p = {mirror * p.x * scale, p.y * scale};
    return true;
}

} // namespace

bool flatten_lscm(const InputMesh& mesh, ChartDraft& draft) {
    try {
        SurfaceMesh surface;
        std::vector<VertexIndex> vertices;
        if (!build_surface_mesh(mesh, draft, surface, vertices))
            return false;
        SurfaceMesh::Halfedge_index border;
        for (SurfaceMesh::Halfedge_index h : surface.halfedges())
            if (surface.is_border(h)) {
                border = h;
                break;
            }
        if (border == SurfaceMesh::null_halfedge())
            return false; // closed: no disc to flatten
        auto uv_map = surface.add_property_map<VertexIndex, Kernel::Point_2>("v:uv").first;
        if (SMP::parameterize(surface, SMP::LSCM_parameterizer_3<SurfaceMesh>(), border, uv_map) !=
            SMP::OK)
            return false;
        for (std::size_t i = 0; i < vertices.size(); ++i) {
            const Kernel::Point_2& p = uv_map[vertices[i]];
            draft.uv[i] = {p.x(), p.y()};
        }
    } catch (const std::exception&) {
        return false; // CGAL's precondition failures: the chart gets split instead
    }
    return normalise_area(mesh, draft);
}

} // namespace penumbra::lightmap
