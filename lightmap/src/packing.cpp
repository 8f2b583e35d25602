// pack_atlases: charts turned and scaled into texel units, packed by two packers (stb's on
// bounding rectangles, ours on texel profiles), the denser layout kept, and each chart's
// vertices placed in its atlas.

#include "lightmap/atlas.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "core/error.h"

#include "packing_internal.h"
#include "texel_cover.h"
#include "uv_geometry.h"

namespace penumbra::lightmap {

namespace {

Oriented orient_chart(const Chart& chart, double density) {
    std::vector<Vec2> used;
    for (const ChartTriangle& t : chart.triangles)
        for (std::uint32_t v : t.vertices)
            used.push_back(chart.vertices[v].uv);
    // An artist's layout keeps its axes (quarter turns only): its islands were laid out
    // against them.
    const double angle = chart.kind == ChartKind::imported ? 0.0 : min_area_rectangle_angle(used);
    const double c = std::cos(angle), s = std::sin(angle);
    Oriented o;
    o.density = density;
    Vec2 lo{1e300, 1e300}, hi{-1e300, -1e300};
    for (const ChartVertex& v : chart.vertices)
        o.q.push_back(rotate(v.uv, c, s) * density);
    for (const Vec2& p : used) {
        const Vec2 q = rotate(p, c, s) * density;
        lo = {std::min(lo.x, q.x), std::min(lo.y, q.y)};
        hi = {std::max(hi.x, q.x), std::max(hi.y, q.y)};
    }
    for (Vec2& p : o.q)
        p = p - lo;
    o.width = hi.x - lo.x;
    o.height = hi.y - lo.y;
    return o;
}

// The chart at the density, or scaled down (with a warning) until it fits one atlas.
Oriented fit_chart(const Chart& chart, const AtlasSettings& settings, const Context& ctx) {
    Oriented o = orient_chart(chart, settings.texels_per_metre);
    const int room = settings.size - 2 * settings.padding;
    const double extent = std::max(o.width, o.height);
    if (covered_count(extent) <= room)
        return o;
    const double density = settings.texels_per_metre * room / extent * (1 - 1e-9);
    ctx.warn("lightmap: a chart of object '{}' ({:.3g} m across) does not fit a {}² atlas at {} "
             "texels/m; it gets {:.4g} texels/m",
             chart.object, extent / settings.texels_per_metre, settings.size,
             settings.texels_per_metre, density);
    return orient_chart(chart, density);
}

// Fewest atlases first, then the lowest used height in the last one.
std::tuple<int, int> packing_cost(const Packing& p, const std::vector<Oriented>& charts) {
    int height = 0;
    for (std::size_t i = 0; i < charts.size(); ++i)
        if (int(p.placed[i].atlas) == p.atlases - 1)
            height = std::max(height, p.placed[i].y + charts[i].covered_height(p.placed[i].turns));
    return {p.atlases, height};
}

ChartPlacement place_chart(const Oriented& o, const Placed& placed) {
    ChartPlacement p;
    p.atlas = placed.atlas;
    p.texels_per_metre = o.density;
    p.rect = {placed.x, placed.y, o.covered_width(placed.turns), o.covered_height(placed.turns)};
    for (const Vec2& q : o.q) {
        const Vec2 t = o.turn(q, placed.turns);
        p.texel_uv.push_back({t.x + p.rect.x, t.y + p.rect.y});
    }
    return p;
}

std::vector<double> measure_coverage(const Charts& charts, const AtlasLayout& layout) {
    std::vector<std::vector<std::uint8_t>> masks(
        std::size_t(layout.atlas_count),
        std::vector<std::uint8_t>(std::size_t(layout.size) * std::size_t(layout.size), 0));
    for (std::size_t c = 0; c < charts.charts.size(); ++c) {
        const ChartPlacement& p = layout.placements[c];
        auto& mask = masks[p.atlas];
        for (const ChartTriangle& t : charts.charts[c].triangles)
            for_each_covered_texel(
                {p.texel_uv[t.vertices[0]], p.texel_uv[t.vertices[1]], p.texel_uv[t.vertices[2]]},
                layout.size, [&](int x, int y) {
                    mask[std::size_t(y) * std::size_t(layout.size) + std::size_t(x)] = 1;
                });
    }
    std::vector<double> coverage;
    for (const auto& mask : masks)
        coverage.push_back(double(std::count(mask.begin(), mask.end(), 1)) / double(mask.size()));
    return coverage;
}

void check_settings(const AtlasSettings& s) {
    if (!(s.texels_per_metre > 0 && std::isfinite(s.texels_per_metre)))
        throw ConfigError("lightmap: texels per metre must be > 0");
    if (s.size < 1 || s.size > 8192)
        throw ConfigError("lightmap: the atlas size must lie in [1, 8192] texels");
    if (s.padding < 0 || s.size - 2 * s.padding < 1)
        throw ConfigError("lightmap: the padding must be >= 0 and leave room in the atlas");
}

} // namespace

AtlasLayout pack_atlases(const Charts& charts, const AtlasSettings& settings, const Context& ctx) {
    check_settings(settings);
    std::vector<Oriented> oriented;
    for (const Chart& chart : charts.charts)
        oriented.push_back(fit_chart(chart, settings, ctx));
    AtlasLayout layout;
    layout.size = settings.size;
    layout.padding = settings.padding;
    if (charts.charts.empty())
        return layout;
    Packing packing = pack_rectangles(oriented, settings);
    Packing profiles = pack_profiles(charts, oriented, settings);
    layout.packer = AtlasPacker::rectangles;
    if (packing_cost(profiles, oriented) < packing_cost(packing, oriented)) {
        packing = std::move(profiles);
        layout.packer = AtlasPacker::profiles;
    }
    layout.atlas_count = packing.atlases;
    for (std::size_t i = 0; i < oriented.size(); ++i)
        layout.placements.push_back(place_chart(oriented[i], packing.placed[i]));
    layout.coverage = measure_coverage(charts, layout);
    return layout;
}

} // namespace penumbra::lightmap
