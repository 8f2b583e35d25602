#pragma once
// The scene's input polygons as one welded triangle mesh with edge adjacency: the surface
// that charts cut up.

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/scene.h"
#include "core/vec.h"

namespace penumbra::lightmap {

struct InputTriangle {
    std::array<std::uint32_t, 3> corners{}; ///< welded vertices, counter-clockwise from the front
    std::uint32_t polygon = 0;
    std::uint32_t object = 0; ///< index of the polygon's name in InputMesh::objects
    Vec3 normal;              ///< unit, see ChartTriangle::normal
    double area_m2 = 0;
};

struct InputMesh {
    std::vector<Vec3> positions; ///< welded vertices, metres
    std::vector<InputTriangle> triangles;
    std::vector<std::string> objects; ///< object names, in order of first polygon
    /// Per triangle and edge k (corners k, k + 1): the triangle across it when exactly two
    /// triangles of the same object share it with opposite directions (a manifold edge).
    std::vector<std::array<std::optional<std::uint32_t>, 3>> neighbours;
    /// Per triangle: triangles of the same object with an edge along part of one of its edges
    /// that is not a manifold edge (T-junctions: a wall cut into pieces around a window).
    /// Planar regions join through them; LSCM charts do not (CGAL needs a manifold).
    std::vector<std::vector<std::uint32_t>> collinear_neighbours;
    std::size_t skipped_polygons = 0;
};

/// \brief Triangulates a polygon: ear clipping in its plane when it is planar within
///        \p planarity_tolerance × its diagonal; else the fan from vertex 0, as the mesher
///        splits non-planar polygons. Returns corner index triples, zero-area ones dropped.
std::vector<std::array<std::uint32_t, 3>> triangulate_polygon(const std::vector<Vec3>& vertices,
                                                              double planarity_tolerance);

/// \brief The unit plane normal of a planar polygon (Newell), or none when it is not planar
///        within \p planarity_tolerance × its diagonal or has no area.
std::optional<Vec3> planar_normal(const std::vector<Vec3>& vertices, double planarity_tolerance);

/// \brief InputMesh::collinear_neighbours: pairs of non-manifold edges of one object that run
///        in opposite directions along one line (within \p tolerance metres) and overlap by
///        more than \p tolerance.
std::vector<std::vector<std::uint32_t>> find_collinear_neighbours(const InputMesh& mesh,
                                                                  double tolerance);

/// \brief Triangulates and welds every polygon of \p polygon_ids (indices into Scene::polygons).
InputMesh build_input_mesh(const Scene& scene, const std::vector<std::uint32_t>& polygon_ids,
                           double weld_tolerance);

} // namespace penumbra::lightmap
