// Conservative rasterization of packed charts: every texel a chart triangle overlaps with
// positive area is covered, so bilinear lookups at chart edges read texels of the chart.
// A covered texel whose centre lies off the chart is sampled at the chart's point nearest to
// its centre inside the texel (the triangle clipped to the texel, then the closest point):
// never outside the surface, where a sample could sit inside a wall.

#include "lightmap/texels.h"

#include <algorithm>
#include <limits>

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
    const std::size_t rect_texels = std::size_t(p.rect.width) * std::size_t(p.rect.height);
    hits.reserve(rect_texels + 2 * chart.triangles.size());
    for (std::uint32_t t = 0; t < chart.triangles.size(); ++t)
        for_each_covered_texel(texel_triangle(chart, p, t), size, [&](int x, int y) {
            hits.push_back({std::uint64_t(y) * std::uint64_t(size) + std::uint64_t(x), t});
        });
    std::sort(hits.begin(), hits.end());
    ChartTexels out;
    out.texels.reserve(rect_texels);
    out.overlaps.reserve(hits.size());
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

// The charts' texels of one atlas in row-major order: a scan of the atlas's texel grid rather
// than a sort, since each texel has exactly one owner. Releases the charts' own lists.
AtlasTexels merge_atlas(std::vector<ChartTexels>& per_chart, const AtlasLayout& layout,
                        std::uint32_t atlas) {
    // Texels of the atlas's charts numbered consecutively, chart by chart.
    std::vector<std::uint32_t> charts;
    std::vector<std::size_t> first{0};
    for (std::uint32_t c = 0; c < per_chart.size(); ++c)
        if (layout.placements[c].atlas == atlas) {
            charts.push_back(c);
            first.push_back(first.back() + per_chart[c].texels.size());
        }
    constexpr auto none = ~std::uint32_t(0);
    const auto size = std::size_t(layout.size);
    std::vector<std::uint32_t> owner(size * size, none); // 4 bytes per atlas texel
    for (std::size_t k = 0; k < charts.size(); ++k)
        for (std::size_t i = 0; i < per_chart[charts[k]].texels.size(); ++i) {
            const Texel& t = per_chart[charts[k]].texels[i];
            std::uint32_t& o = owner[std::size_t(t.y) * size + std::size_t(t.x)];
            if (o != none)
                throw InternalError("lightmap: two charts cover one texel; packing broke");
            o = std::uint32_t(first[k] + i);
        }
    AtlasTexels out;
    out.size = layout.size;
    out.texels.reserve(first.back());
    out.overlaps.reserve(first.back());
    for (std::uint32_t o : owner) {
        if (o == none)
            continue;
        const std::size_t k =
            std::size_t(std::upper_bound(first.begin(), first.end(), o) - first.begin()) - 1;
        const ChartTexels& chart = per_chart[charts[k]];
        Texel t = chart.texels[o - first[k]];
        const auto from = chart.overlaps.begin() + t.first_overlap;
        t.first_overlap = std::uint32_t(out.overlaps.size());
        out.overlaps.insert(out.overlaps.end(), from, from + t.overlap_count);
        out.texels.push_back(t);
    }
    for (std::uint32_t c : charts)
        per_chart[c] = {};
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
    for (std::uint32_t a = 0; a < atlases.size(); ++a)
        atlases[a] = merge_atlas(per_chart, layout, a);
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
