// Conservative rasterization of packed charts: every texel a chart triangle overlaps with
// positive area is covered, so bilinear lookups at chart edges read texels of the chart.
// A covered texel whose centre lies off the chart is sampled at the chart's point nearest to
// its centre inside the texel (the triangle clipped to the texel, then the closest point):
// never outside the surface, where a sample could sit inside a wall.

#include "lightmap/texels.h"

#include <algorithm>
#include <limits>
#include <tuple>

#include "core/error.h"
#include "core/parallel.h"

#include "texel_cover.h"
#include "uv_geometry.h"

namespace penumbra::lightmap {

namespace {

Triangle2 texel_triangle(const Chart& chart, const ChartPlacement& p, std::uint32_t t) {
    const auto& v = chart.triangles[t].vertices;
    return {p.texel_uv[v[0]], p.texel_uv[v[1]], p.texel_uv[v[2]]};
}

// Barycentric coordinates a hair outside [0, 1] from rounding are clamped, so the position is
// always a convex combination of the triangle's corners.
SurfacePoint surface_point(const Chart& chart, const ChartPlacement& p, std::uint32_t t,
                           const Vec2& uv) {
    const Triangle2 tri = texel_triangle(chart, p, t);
    Vec3 b = barycentric(tri, uv);
    b = {std::max(b.x, 0.0), std::max(b.y, 0.0), std::max(b.z, 0.0)};
    b = b / (b.x + b.y + b.z);
    const auto& v = chart.triangles[t].vertices;
    SurfacePoint s;
    s.triangle = t;
    s.barycentric = b;
    s.position = chart.vertices[v[0]].position * b.x + chart.vertices[v[1]].position * b.y +
                 chart.vertices[v[2]].position * b.z;
    s.normal = chart.triangles[t].normal;
    s.texel_uv = tri[0] * b.x + tri[1] * b.y + tri[2] * b.z;
    return s;
}

bool inside(const Triangle2& tri, const Vec2& p) {
    const Vec3 b = barycentric(tri, p);
    constexpr double eps = -1e-12;
    return b.x >= eps && b.y >= eps && b.z >= eps;
}

SurfacePoint centre_sample(const Chart& chart, const ChartPlacement& p, int x, int y,
                           const std::uint32_t* overlaps, std::size_t count) {
    const Vec2 centre{x + 0.5, y + 0.5};
    for (std::size_t i = 0; i < count; ++i)
        if (inside(texel_triangle(chart, p, overlaps[i]), centre))
            return surface_point(chart, p, overlaps[i], centre);
    std::uint32_t best = overlaps[0];
    Vec2 best_point = centre;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < count; ++i) {
        const Triangle2 tri = texel_triangle(chart, p, overlaps[i]);
        std::vector<Vec2> part = clip_to_texel(tri, x, y);
        if (part.empty())
            part.assign(tri.begin(), tri.end());
        const Vec2 q = closest_point_in_convex(part, centre);
        const double d2 = dot(q - centre, q - centre);
        if (d2 < best_d2) {
            best_d2 = d2;
            best = overlaps[i];
            best_point = q;
        }
    }
    return surface_point(chart, p, best, best_point);
}

struct ChartTexels {
    std::vector<Texel> texels; // first_overlap indexes overlaps
    std::vector<std::uint32_t> overlaps;
};

ChartTexels chart_texels(const Chart& chart, const ChartPlacement& p, std::uint32_t chart_id,
                         int size) {
    std::vector<std::pair<std::uint64_t, std::uint32_t>> hits; // (texel key, triangle)
    for (std::uint32_t t = 0; t < chart.triangles.size(); ++t)
        for_each_covered_texel(texel_triangle(chart, p, t), size, [&](int x, int y) {
            hits.push_back({std::uint64_t(y) * std::uint64_t(size) + std::uint64_t(x), t});
        });
    std::sort(hits.begin(), hits.end());
    ChartTexels out;
    for (std::size_t i = 0; i < hits.size();) {
        Texel texel;
        texel.x = int(hits[i].first % std::uint64_t(size));
        texel.y = int(hits[i].first / std::uint64_t(size));
        texel.chart = chart_id;
        texel.first_overlap = std::uint32_t(out.overlaps.size());
        const std::uint64_t key = hits[i].first;
        for (; i < hits.size() && hits[i].first == key; ++i)
            out.overlaps.push_back(hits[i].second);
        texel.overlap_count = std::uint32_t(out.overlaps.size()) - texel.first_overlap;
        texel.centre =
            centre_sample(chart, p, texel.x, texel.y, out.overlaps.data() + texel.first_overlap,
                          texel.overlap_count);
        out.texels.push_back(texel);
    }
    return out;
}

} // namespace

std::vector<AtlasTexels> rasterize(const Charts& charts, const AtlasLayout& layout,
                                   const Context& ctx) {
    std::vector<ChartTexels> per_chart(charts.charts.size());
    run_in_arena(ctx, [&] {
        parallel_for_index(charts.charts.size(), 1, [&](std::size_t c) {
            per_chart[c] =
                chart_texels(charts.charts[c], layout.placements[c], std::uint32_t(c), layout.size);
        });
    });
    std::vector<AtlasTexels> atlases(std::size_t(layout.atlas_count));
    for (AtlasTexels& a : atlases)
        a.size = layout.size;
    for (std::size_t c = 0; c < per_chart.size(); ++c) {
        AtlasTexels& atlas = atlases[layout.placements[c].atlas];
        const auto offset = std::uint32_t(atlas.overlaps.size());
        atlas.overlaps.insert(atlas.overlaps.end(), per_chart[c].overlaps.begin(),
                              per_chart[c].overlaps.end());
        for (Texel texel : per_chart[c].texels) {
            texel.first_overlap += offset;
            atlas.texels.push_back(texel);
        }
    }
    for (AtlasTexels& atlas : atlases) {
        std::sort(atlas.texels.begin(), atlas.texels.end(), [](const Texel& a, const Texel& b) {
            return std::tie(a.y, a.x) < std::tie(b.y, b.x);
        });
        for (std::size_t i = 1; i < atlas.texels.size(); ++i)
            if (atlas.texels[i].x == atlas.texels[i - 1].x &&
                atlas.texels[i].y == atlas.texels[i - 1].y)
                throw InternalError("lightmap: two charts cover one texel; packing broke");
    }
    return atlases;
}

std::vector<SurfacePoint> texel_samples(const Chart& chart, const ChartPlacement& placement,
                                        const AtlasTexels& atlas, const Texel& texel, int n) {
    std::vector<SurfacePoint> samples;
    const std::uint32_t* overlaps = atlas.overlaps.data() + texel.first_overlap;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const Vec2 p{texel.x + (i + 0.5) / n, texel.y + (j + 0.5) / n};
            for (std::uint32_t k = 0; k < texel.overlap_count; ++k)
                if (inside(texel_triangle(chart, placement, overlaps[k]), p)) {
                    samples.push_back(surface_point(chart, placement, overlaps[k], p));
                    break;
                }
        }
    if (samples.empty())
        samples.push_back(texel.centre);
    return samples;
}

std::vector<std::uint8_t> coverage_mask(const AtlasTexels& atlas) {
    std::vector<std::uint8_t> mask(std::size_t(atlas.size) * std::size_t(atlas.size), 0);
    for (const Texel& t : atlas.texels)
        mask[std::size_t(t.y) * std::size_t(atlas.size) + std::size_t(t.x)] = 1;
    return mask;
}

} // namespace penumbra::lightmap
