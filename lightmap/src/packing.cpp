// Atlas packing with stb_rect_pack's skyline packer (Sean Barrett, libstb-dev). Generated
// charts are first turned to their minimum-area bounding rectangles; then every combination of a
// 90° orientation policy (landscape, portrait) and a skyline heuristic (bottom-left, best-fit) is
// packed and the one with the fewest atlases, then the lowest skyline in the last one, kept.
// Rectangles go in one at a time in our own sorted order, so the result never depends on
// qsort's handling of equal keys inside stb.

#include "lightmap/atlas.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <memory>
#include <tuple>

#define STB_RECT_PACK_IMPLEMENTATION
#include <stb/stb_rect_pack.h>

#include "core/error.h"

#include "texel_cover.h"
#include "uv_geometry.h"

namespace penumbra::lightmap {

namespace {

// Texel coordinates within 1e-9 of a texel edge do not cover the next texel
// (triangle_overlaps_texel's margin).
int covered_count(double extent) {
    return std::max(1, int(std::ceil(extent - 1e-9)));
}

// A chart in texel units, turned to its minimum-area rectangle, its bounding box at (0, 0).
struct Oriented {
    std::vector<Vec2> q; ///< per chart vertex
    double width = 0, height = 0;
    double density = 0;
};

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

struct Policy {
    bool portrait = false;
    int heuristic = STBRP_HEURISTIC_Skyline_BL_sortHeight;
};

struct Placed {
    std::uint32_t atlas = 0;
    int x = 0, y = 0; // the padded rectangle's corner
    bool turned = false;
};

struct Packing {
    std::vector<Placed> placed;
    int atlases = 0;
    int last_height = 0; // highest rectangle top in the last atlas
};

class AtlasBins {
public:
    AtlasBins(int width, int heuristic) : width_(width), heuristic_(heuristic) {}

    // Places a w × h rectangle in the first atlas that takes it, opening one if none does.
    Placed place(int w, int h) {
        for (std::size_t a = 0;; ++a) {
            if (a == bins_.size())
                open();
            stbrp_rect rect{0, w, h, 0, 0, 0};
            stbrp_pack_rects(&bins_[a]->context, &rect, 1);
            if (rect.was_packed) {
                tops_[a] = std::max(tops_[a], rect.y + h);
                return {std::uint32_t(a), rect.x, rect.y, false};
            }
        }
    }
    int count() const { return int(bins_.size()); }
    int last_top() const { return tops_.empty() ? 0 : tops_.back(); }

private:
    struct Bin {
        stbrp_context context{};
        std::vector<stbrp_node> nodes;
    };
    void open() {
        auto bin = std::make_unique<Bin>();
        bin->nodes.resize(std::size_t(width_));
        stbrp_init_target(&bin->context, width_, width_, bin->nodes.data(), width_);
        stbrp_setup_heuristic(&bin->context, heuristic_);
        bins_.push_back(std::move(bin));
        tops_.push_back(0);
    }
    int width_, heuristic_;
    std::vector<std::unique_ptr<Bin>> bins_; // stb keeps pointers into the nodes
    std::vector<int> tops_;
};

Packing pack(const std::vector<Oriented>& charts, const AtlasSettings& settings, Policy policy) {
    struct Item {
        int w, h;
        bool turned;
        std::uint32_t chart;
    };
    std::vector<Item> items;
    for (std::uint32_t i = 0; i < charts.size(); ++i) {
        const int w = covered_count(charts[i].width), h = covered_count(charts[i].height);
        const bool turned = policy.portrait ? w > h : h > w;
        items.push_back(
            {(turned ? h : w) + settings.padding, (turned ? w : h) + settings.padding, turned, i});
    }
    std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
        return std::tie(b.h, b.w, a.chart) < std::tie(a.h, a.w, b.chart);
    });
    // The packing area leaves a padding strip along the right and bottom edges; each
    // rectangle carries its padding on its left and top.
    AtlasBins bins(settings.size - settings.padding, policy.heuristic);
    Packing result;
    result.placed.resize(charts.size());
    for (const Item& item : items) {
        result.placed[item.chart] = bins.place(item.w, item.h);
        result.placed[item.chart].turned = item.turned;
    }
    result.atlases = bins.count();
    result.last_height = bins.last_top();
    return result;
}

Packing best_packing(const std::vector<Oriented>& charts, const AtlasSettings& settings) {
    std::optional<Packing> best;
    for (bool portrait : {false, true})
        for (int heuristic :
             {STBRP_HEURISTIC_Skyline_BL_sortHeight, STBRP_HEURISTIC_Skyline_BF_sortHeight}) {
            Packing p = pack(charts, settings, {portrait, heuristic});
            if (!best ||
                std::tie(p.atlases, p.last_height) < std::tie(best->atlases, best->last_height))
                best = std::move(p);
        }
    return std::move(*best);
}

ChartPlacement place_chart(const Oriented& o, const Placed& placed, const AtlasSettings& s) {
    ChartPlacement p;
    p.atlas = placed.atlas;
    p.texels_per_metre = o.density;
    const int w = covered_count(o.width), h = covered_count(o.height);
    p.rect = {placed.x + s.padding, placed.y + s.padding, placed.turned ? h : w,
              placed.turned ? w : h};
    for (const Vec2& q : o.q) {
        // A quarter turn (x, y) → (height − y, x) keeps the box at the origin.
        const Vec2 t = placed.turned ? Vec2{o.height - q.y, q.x} : q;
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
    const Packing packing = best_packing(oriented, settings);
    layout.atlas_count = packing.atlases;
    for (std::size_t i = 0; i < oriented.size(); ++i)
        layout.placements.push_back(place_chart(oriented[i], packing.placed[i], settings));
    layout.coverage = measure_coverage(charts, layout);
    return layout;
}

} // namespace penumbra::lightmap
