// build_charts: imported UV sets where the scene has them, else segmentation (planar regions,
// growth by normal deviation), flattening (projection or LSCM) and checks, splitting a chart
// that fails until every piece passes (a single triangle always does).

#include "lightmap/charts.h"

#include <cmath>
#include <map>

#include "core/error.h"
#include "core/parallel.h"

#include "chart_draft.h"
#include "imported_charts.h"
#include "input_mesh.h"
#include "segmentation.h"

namespace penumbra::lightmap {

namespace {

constexpr double k_degree = k_pi / 180.0;

struct ObjectPolygons {
    std::string name;
    std::vector<std::uint32_t> polygons;
};

std::vector<ObjectPolygons> group_by_object(const Scene& scene) {
    std::vector<ObjectPolygons> objects;
    std::map<std::string, std::size_t> index;
    for (std::uint32_t pi = 0; pi < scene.polygons.size(); ++pi) {
        const std::string& name = scene.polygons[pi].name;
        const auto [it, added] = index.try_emplace(name, objects.size());
        if (added)
            objects.push_back({name, {}});
        objects[it->second].polygons.push_back(pi);
    }
    return objects;
}

// Every polygon of the object has a lightmap UV per vertex; a warning if only some have.
bool has_imported_uv(const Scene& scene, const ObjectPolygons& object, const Context& ctx) {
    std::size_t with = 0;
    for (std::uint32_t pi : object.polygons)
        if (!scene.polygons[pi].lightmap_uv.empty())
            ++with;
    if (with > 0 && with < object.polygons.size())
        ctx.warn("lightmap: {} of {} polygons of object '{}' have lightmap UVs; its charts are "
                 "generated",
                 with, object.polygons.size(), object.name);
    return with == object.polygons.size();
}

Chart to_chart(const InputMesh& mesh, const ChartDraft& draft, ChartKind kind) {
    Chart chart;
    chart.kind = kind;
    chart.object = mesh.objects[mesh.triangles[draft.triangles[0]].object];
    for (std::size_t i = 0; i < draft.vertices.size(); ++i)
        chart.vertices.push_back({mesh.positions[draft.vertices[i]], draft.uv[i]});
    for (std::size_t i = 0; i < draft.triangles.size(); ++i) {
        const InputTriangle& t = mesh.triangles[draft.triangles[i]];
        chart.triangles.push_back({draft.corners[i], t.polygon, t.normal});
    }
    return chart;
}

bool one_region(const PlanarRegions& regions, const std::vector<std::uint32_t>& triangles) {
    for (std::uint32_t t : triangles)
        if (regions.of_triangle[t] != regions.of_triangle[triangles[0]])
            return false;
    return true;
}

// Flattens the triangles as one chart, or splits them and recurses; appends to \p out.
void flatten(const InputMesh& mesh, const PlanarRegions& regions,
             std::vector<std::uint32_t> triangles, std::vector<Chart>& out, std::size_t& splits) {
    ChartDraft draft = make_draft(mesh, std::move(triangles));
    const bool planar = one_region(regions, draft.triangles);
    if (draft.triangles.size() == 1) {
        // Its own geometric normal: a positive projection whatever the polygon's plane.
        const auto& c = mesh.triangles[draft.triangles[0]].corners;
        const Vec3 n = cross(mesh.positions[c[1]] - mesh.positions[c[0]],
                             mesh.positions[c[2]] - mesh.positions[c[0]]);
        project_onto_plane(mesh, normalize(n), draft);
        out.push_back(to_chart(mesh, draft, ChartKind::planar));
        return;
    }
    if (planar)
        project_onto_plane(mesh, regions.normal[regions.of_triangle[draft.triangles[0]]], draft);
    if ((planar || flatten_lscm(mesh, draft)) && draft_valid(mesh, draft)) {
        out.push_back(to_chart(mesh, draft, planar ? ChartKind::planar : ChartKind::curved));
        return;
    }
    ++splits;
    for (std::vector<std::uint32_t>& part : split_chart(mesh, draft.triangles))
        flatten(mesh, regions, std::move(part), out, splits);
}

void check_settings(const ChartSettings& s) {
    if (!(s.max_normal_deviation_deg > 0 && s.max_normal_deviation_deg < 90))
        throw ConfigError("lightmap: max_normal_deviation_deg must lie in (0, 90)");
    if (!(s.planar_angle_deg >= 0 && s.planar_angle_deg < s.max_normal_deviation_deg))
        throw ConfigError("lightmap: planar_angle_deg must lie in [0, max_normal_deviation_deg)");
    for (const auto& t : {s.planar_distance_m, s.weld_tolerance_m})
        if (t && !(*t >= 0 && std::isfinite(*t)))
            throw ConfigError("lightmap: planar_distance_m and weld_tolerance_m must be >= 0");
}

// Charts of the polygons (indices into Scene::polygons), grouped by object in the order of
// their first polygon.
Charts generate_charts(const Scene& scene, const std::vector<std::uint32_t>& polygons,
                       const ChartSettings& settings, const Context& ctx) {
    const double diagonal = scene.bounds().diagonal();
    const InputMesh mesh =
        build_input_mesh(scene, polygons, settings.weld_tolerance_m.value_or(1e-6 * diagonal));
    const PlanarRegions regions =
        find_planar_regions(mesh, settings.planar_angle_deg * k_degree,
                            settings.planar_distance_m.value_or(1e-4 * diagonal));
    std::vector<std::vector<std::uint32_t>> grown =
        grow_charts(mesh, regions, settings.max_normal_deviation_deg * k_degree);
    std::vector<std::vector<Chart>> flattened(grown.size());
    std::vector<std::size_t> splits(grown.size(), 0);
    run_in_arena(ctx, [&] {
        parallel_for_index(grown.size(), 1, [&](std::size_t i) {
            flatten(mesh, regions, std::move(grown[i]), flattened[i], splits[i]);
        });
    });
    Charts result;
    result.skipped_polygons = mesh.skipped_polygons;
    for (std::size_t i = 0; i < flattened.size(); ++i) {
        result.split_charts += splits[i];
        for (Chart& chart : flattened[i])
            result.charts.push_back(std::move(chart));
    }
    return result;
}

} // namespace

double Chart::area_m2() const {
    double area = 0;
    for (const ChartTriangle& t : triangles) {
        const Vec3& a = vertices[t.vertices[0]].position;
        area += 0.5 * length(cross(vertices[t.vertices[1]].position - a,
                                   vertices[t.vertices[2]].position - a));
    }
    return area;
}

Charts build_charts(const Scene& scene, const ChartSettings& settings, const Context& ctx) {
    check_settings(settings);
    const std::vector<ObjectPolygons> objects = group_by_object(scene);
    std::map<std::string, std::vector<Chart>> by_object;
    std::vector<std::uint32_t> generated;
    for (const ObjectPolygons& object : objects) {
        std::optional<Chart> chart;
        if (settings.use_imported_uv && has_imported_uv(scene, object, ctx)) {
            chart = imported_chart(scene, object.name, object.polygons);
            if (!chart)
                ctx.warn("lightmap: the lightmap UVs of object '{}' overlap or have no area; its "
                         "charts are generated",
                         object.name);
        }
        if (chart)
            by_object[object.name].push_back(std::move(*chart));
        else
            generated.insert(generated.end(), object.polygons.begin(), object.polygons.end());
    }
    std::sort(generated.begin(), generated.end());
    Charts result = generate_charts(scene, generated, settings, ctx);
    for (Chart& chart : result.charts)
        by_object[chart.object].push_back(std::move(chart));
    result.charts.clear();
    for (const ObjectPolygons& object : objects)
        for (Chart& chart : by_object[object.name])
            result.charts.push_back(std::move(chart));
    if (result.skipped_polygons > 0)
        ctx.warn("lightmap: {} polygon(s) without area get no charts", result.skipped_polygons);
    return result;
}

} // namespace penumbra::lightmap
