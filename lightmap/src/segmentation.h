#pragma once
// Cutting the input mesh into charts: planar regions (flood fill over manifold edges between
// coplanar triangles), then charts grown over the regions by normal deviation.

#include <cstdint>
#include <vector>

#include "core/vec.h"
#include "input_mesh.h"

namespace penumbra::lightmap {

struct PlanarRegions {
    std::vector<std::uint32_t> of_triangle;          ///< region of each triangle
    std::vector<Vec3> normal;                        ///< per region: its first triangle's normal
    std::vector<double> area_m2;                     ///< per region
    std::vector<std::vector<std::uint32_t>> members; ///< per region: its triangles, ascending
    /// Per region: some triangle joined it through a collinear (T-junction) edge only, so it
    /// is a planar chart on its own and never part of a curved one.
    std::vector<bool> joined_collinear;
};

/// \brief Regions of triangles connected by manifold or collinear edges whose normals lie within
///        \p max_angle_rad of the region's first triangle's and whose corners lie within
///        \p max_distance of that triangle's plane. Seeds in triangle order.
PlanarRegions find_planar_regions(const InputMesh& mesh, double max_angle_rad, double max_distance);

/// \brief Charts as ascending lists of triangles: per object, seeded at its largest region
///        not yet taken, grown over neighbouring regions (smallest deviation first) whose
///        triangles' normals all lie within \p max_deviation_rad of the seed region's normal.
///        Charts come grouped by object (InputMesh::objects order), largest seeds first.
std::vector<std::vector<std::uint32_t>>
grow_charts(const InputMesh& mesh, const PlanarRegions& regions, double max_deviation_rad);

/// \brief Splits \p triangles in two at the area median along the principal axis of their
///        area-weighted centroids, and returns the connected parts of both halves.
std::vector<std::vector<std::uint32_t>> split_chart(const InputMesh& mesh,
                                                    const std::vector<std::uint32_t>& triangles);

} // namespace penumbra::lightmap
