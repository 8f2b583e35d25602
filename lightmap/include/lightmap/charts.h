#pragma once
// Lightmap charts (issue #29): the scene's input polygons, triangulated and cut into charts
// that each lie flat in the plane without overlaps, ready to be packed into atlases
// (lightmap/atlas.h). The lightmap mesh is the input geometry, not the radiosity elements: a
// game engine draws the input meshes. Charts cover the front side of each polygon (the side
// its counter-clockwise order faces). docs/lightmaps.md describes the method.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/context.h"
#include "core/scene.h"
#include "core/vec.h"

namespace penumbra::lightmap {

/// \brief How a chart was flattened.
enum class ChartKind {
    planar,   ///< one planar region projected onto its plane: no distortion
    curved,   ///< planar regions grown by normal deviation, flattened by LSCM
    imported, ///< the object's own lightmap UV set (Polygon::lightmap_uv)
};

/// \brief A corner shared by the triangles of one chart.
struct ChartVertex {
    Vec3 position; ///< world, metres
    /// Flattened chart coordinates in metres: lengths on the surface for planar charts, the
    /// LSCM map scaled to the chart's 3D area for curved ones, the file's UVs scaled to the
    /// object's 3D area for imported ones. Packing rotates, scales and moves them.
    Vec2 uv;
};

/// \brief One triangle of a chart.
struct ChartTriangle {
    std::array<std::uint32_t, 3> vertices{}; ///< into Chart::vertices
    std::uint32_t polygon = 0;               ///< index into Scene::polygons
    /// Unit normal of the side the chart covers: the polygon's plane normal when the polygon
    /// is planar (MesherSettings::planarity_tolerance, as the mesher decides), else this
    /// triangle's own.
    Vec3 normal;
};

/// \brief A connected piece of one object's surface with its flattened coordinates. Generated
///        charts have counter-clockwise (positive) uv triangles and no two overlap; imported
///        ones may be mirrored (negative) but do not overlap either.
struct Chart {
    ChartKind kind = ChartKind::planar;
    std::string object; ///< Polygon::name of every triangle in it
    std::vector<ChartVertex> vertices;
    std::vector<ChartTriangle> triangles;

    /// \brief Surface area of its triangles, m².
    double area_m2() const;
};

/// \brief Chart generation settings.
struct ChartSettings {
    /// Most angle between the normal of a curved chart's first planar region and any of its
    /// triangles' normals, degrees. Below 90° a chart is a height field over that region's
    /// plane, so LSCM rarely folds it; 40° keeps LSCM's area distortion small (≈ 1/cos 40°).
    double max_normal_deviation_deg = 40;
    /// Triangles whose normals differ by at most this (degrees) and whose corners lie within
    /// planar_distance of the region's plane belong to one planar region.
    double planar_angle_deg = 0.5;
    /// Metres; unset = 1e-4 × the scene's diagonal.
    std::optional<double> planar_distance_m;
    /// Corners closer than this (metres) are one vertex, joining the triangles of one object
    /// that share an edge. Unset = 1e-6 × the scene's diagonal.
    std::optional<double> weld_tolerance_m;
    /// Use the objects' own lightmap UVs (Polygon::lightmap_uv) where every polygon of the
    /// object has them and they do not overlap.
    bool use_imported_uv = true;
};

/// \brief The charts of a scene, in a deterministic order: objects in the order of their
///        first polygon, an object's charts largest first as they were grown.
struct Charts {
    std::vector<Chart> charts;
    std::size_t skipped_polygons = 0; ///< degenerate polygons (zero area), not charted
    std::size_t split_charts = 0;     ///< charts that failed a flip or overlap check and split
};

/// \brief Triangulates the scene's polygons and cuts them into charts: imported UV sets where
///        present (ChartSettings::use_imported_uv), else planar regions projected onto their
///        planes and curved parts grown by normal deviation and flattened by LSCM (CGAL);
///        a chart with a flipped or overlapping triangle is split in two along its principal
///        axis and retried, down to single triangles. Deterministic; warnings go to \p ctx.
Charts build_charts(const Scene& scene, const ChartSettings& settings, const Context& ctx);

} // namespace penumbra::lightmap
