// An imported UV set is kept as the artist laid it out: one chart per object (packing may
// turn it by a multiple of 90° or to its minimum-area rectangle and scales it to the density).
// Islands are not repacked, so the file's own padding between them is what the bake gets.

#include "imported_charts.h"

#include <cmath>

#include "chart_checks.h"
#include "input_mesh.h"

namespace penumbra::lightmap {

std::optional<Chart> imported_chart(const Scene& scene, const std::string& object,
                                    const std::vector<std::uint32_t>& polygons) {
    Chart chart;
    chart.kind = ChartKind::imported;
    chart.object = object;
    std::vector<double> areas;
    const double tolerance = scene.mesher.planarity_tolerance;
    for (std::uint32_t pi : polygons) {
        const Polygon& polygon = scene.polygons[pi];
        const auto base = std::uint32_t(chart.vertices.size());
        for (std::size_t k = 0; k < polygon.vertices.size(); ++k)
            chart.vertices.push_back({polygon.vertices[k], polygon.lightmap_uv[k]});
        const std::optional<Vec3> plane = planar_normal(polygon.vertices, tolerance);
        for (const auto& t : triangulate_polygon(polygon.vertices, tolerance)) {
            const Vec3 n = cross(polygon.vertices[t[1]] - polygon.vertices[t[0]],
                                 polygon.vertices[t[2]] - polygon.vertices[t[0]]);
            chart.triangles.push_back(
                {{base + t[0], base + t[1], base + t[2]}, pi, plane ? *plane : normalize(n)});
            areas.push_back(0.5 * length(n));
        }
    }
    std::vector<Triangle2> uv;
    double uv_area = 0, area = 0;
    for (std::size_t i = 0; i < chart.triangles.size(); ++i) {
        const auto& v = chart.triangles[i].vertices;
        uv.push_back({chart.vertices[v[0]].uv, chart.vertices[v[1]].uv, chart.vertices[v[2]].uv});
        uv_area += std::abs(signed_area(uv.back()));
        area += areas[i];
    }
    if (chart.triangles.empty() || !(uv_area > 0))
        return std::nullopt;
    const double scale = std::sqrt(area / uv_area);
    for (Triangle2& t : uv)
        for (Vec2& p : t)
            p = p * scale;
    if (!uv_layout_valid(uv, areas, true))
        return std::nullopt;
    for (ChartVertex& v : chart.vertices)
        v.uv = v.uv * scale;
    return chart;
}

} // namespace penumbra::lightmap
