// The lightmap preview: primary rays through raytrace::render_hits; the point hit is located
// on its input polygon's chart triangles (the polygon the radiosity element came from), and
// its barycentrics there interpolate the packed texel UVs, as a GPU interpolates TEXCOORD_1.

#include "lightmap_preview.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "core/error.h"

namespace penumbra::app {

namespace {

struct ChartTriangleRef {
    std::uint32_t chart = 0, triangle = 0;
};

// Per input polygon, the chart triangles that cover it.
std::vector<std::vector<ChartTriangleRef>> triangles_by_polygon(const Scene& scene,
                                                                const lightmap::Charts& charts) {
    std::vector<std::vector<ChartTriangleRef>> out(scene.polygons.size());
    for (std::uint32_t c = 0; c < charts.charts.size(); ++c) {
        const lightmap::Chart& chart = charts.charts[c];
        for (std::uint32_t t = 0; t < chart.triangles.size(); ++t)
            out[chart.triangles[t].polygon].push_back({c, t});
    }
    return out;
}

// Barycentrics of \p p projected onto the plane of triangle (a, b, c).
Vec3 barycentrics_3d(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 e1 = b - a, e2 = c - a, d = p - a;
    const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
    const double d1 = dot(d, e1), d2 = dot(d, e2);
    const double det = d11 * d22 - d12 * d12;
    if (!(det > 0))
        return {1, 0, 0};
    const double v = (d22 * d1 - d12 * d2) / det, w = (d11 * d2 - d12 * d1) / det;
    return {1 - v - w, v, w};
}

struct PreviewShader {
    const Scene& scene;
    const raytrace::EmbreeScene& rt;
    const LightmapResult& r;
    std::vector<std::vector<ChartTriangleRef>> by_polygon;

    // The atlas and texel coordinates of \p p on \p polygon: on the chart triangle that holds
    // it best (largest smallest barycentric; slightly outside at a shared edge is fine).
    std::optional<std::pair<std::uint32_t, Vec2>> lightmap_uv(std::uint32_t polygon,
                                                              const Vec3& p) const {
        double best = -std::numeric_limits<double>::infinity();
        std::optional<std::pair<std::uint32_t, Vec2>> out;
        for (const ChartTriangleRef& ref : by_polygon[polygon]) {
            const lightmap::Chart& chart = r.charts.charts[ref.chart];
            const auto& v = chart.triangles[ref.triangle].vertices;
            const Vec3 b =
                barycentrics_3d(p, chart.vertices[v[0]].position, chart.vertices[v[1]].position,
                                chart.vertices[v[2]].position);
            const double inside = std::min({b.x, b.y, b.z});
            if (inside <= best)
                continue;
            best = inside;
            const lightmap::ChartPlacement& place = r.layout.placements[ref.chart];
            out = {{place.atlas, place.texel_uv[v[0]] * b.x + place.texel_uv[v[1]] * b.y +
                                     place.texel_uv[v[2]] * b.z}};
        }
        return out;
    }

    Rgb operator()(const raytrace::EmbreeScene::Hit& hit) const {
        if (hit.element < 0)
            return hit.back_of_one_sided ? Rgb{} : scene.background;
        const RadiosityMesh& mesh = rt.mesh();
        const Patch& patch = mesh.patch_of(std::uint32_t(hit.element));
        if (patch.back)
            return {};
        const auto& t = mesh.triangles[std::uint32_t(hit.element)];
        const Vec3 p0 = mesh.vertex(t[0]);
        const Vec3 p = p0 + (mesh.vertex(t[1]) - p0) * double(hit.u) +
                       (mesh.vertex(t[2]) - p0) * double(hit.v);
        const auto uv = lightmap_uv(patch.polygon, p);
        const Rgb irradiance = uv ? sample_bilinear(r.atlases[uv->first], uv->second) : Rgb{};
        return (patch.reflectance * irradiance + patch.emission) * float(k_inv_pi);
    }
};

// The preview only looks texels up, so it can afford many samples where a lamp's rim crosses
// a pixel: at 16 jittered samples its placement errs by ~1/16 of 17 W/(sr·m²) on the Cornell
// box, which was nine tenths of the preview's RMSE against Cycles.
constexpr raytrace::EdgeRefinement k_preview_edges{k_preview_edge_tolerance, 64};

} // namespace

Rgb sample_bilinear(const Image& atlas, const Vec2& texel_uv) {
    const double x = texel_uv.x - 0.5, y = texel_uv.y - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const float wx = float(x - fx), wy = float(y - fy);
    const auto clamp_x = [&](double i) { return std::clamp(int(i), 0, atlas.width - 1); };
    const auto clamp_y = [&](double j) { return std::clamp(int(j), 0, atlas.height - 1); };
    const int x0 = clamp_x(fx), x1 = clamp_x(fx + 1), y0 = clamp_y(fy), y1 = clamp_y(fy + 1);
    const Rgb top = atlas.at(x0, y0) * (1 - wx) + atlas.at(x1, y0) * wx;
    const Rgb bottom = atlas.at(x0, y1) * (1 - wx) + atlas.at(x1, y1) * wx;
    return top * (1 - wy) + bottom * wy;
}

Image render_lightmap_preview(const Scene& scene, const raytrace::EmbreeScene& rt,
                              const LightmapResult& r, const Context& ctx) {
    if (!scene.camera)
        throw InternalError("render_lightmap_preview: the scene has no camera");
    const PreviewShader shader{scene, rt, r, triangles_by_polygon(scene, r.charts)};
    return raytrace::render_hits(rt, *scene.camera, std::cref(shader), k_preview_edges, ctx);
}

} // namespace penumbra::app
