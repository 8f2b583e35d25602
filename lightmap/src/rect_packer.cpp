// Rectangle packing with stb_rect_pack's skyline packer (Sean Barrett, libstb-dev). Every
// combination of a 90° orientation policy (landscape, portrait) and a skyline heuristic
// (bottom-left, best-fit) is packed and the one with the fewest atlases, then the lowest
// skyline in its last atlas, kept. Rectangles go in one at a time in our own sorted order, so
// the result never depends on qsort's handling of equal keys inside stb.

#include <memory>
#include <optional>
#include <tuple>

#define STB_RECT_PACK_IMPLEMENTATION
#include <stb/stb_rect_pack.h>

#include "packing_internal.h"

namespace penumbra::lightmap {

namespace {

class AtlasBins {
public:
    AtlasBins(int width, int heuristic) : width_(width), heuristic_(heuristic) {}

    // Places a w × h rectangle in the first atlas that takes it, opening one if none does;
    // returns the rectangle's corner.
    Placed place(int w, int h) {
        for (std::size_t a = 0;; ++a) {
            if (a == bins_.size())
                open();
            stbrp_rect rect{0, w, h, 0, 0, 0};
            stbrp_pack_rects(&bins_[a]->context, &rect, 1);
            if (rect.was_packed) {
                tops_[a] = std::max(tops_[a], rect.y + h);
                return {std::uint32_t(a), rect.x, rect.y, 0};
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

struct Result {
    Packing packing;
    int last_top = 0;
};

Result pack(const std::vector<Oriented>& charts, const AtlasSettings& settings, bool portrait,
            int heuristic) {
    struct Item {
        int w, h;
        bool turned;
        std::uint32_t chart;
    };
    std::vector<Item> items;
    for (std::uint32_t i = 0; i < charts.size(); ++i) {
        const int w = charts[i].covered_width(0), h = charts[i].covered_height(0);
        const bool turned = portrait ? w > h : h > w;
        items.push_back(
            {(turned ? h : w) + settings.padding, (turned ? w : h) + settings.padding, turned, i});
    }
    std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
        return std::tie(b.h, b.w, a.chart) < std::tie(a.h, a.w, b.chart);
    });
    // The packing area leaves a padding strip along the right and bottom edges; each
    // rectangle carries its padding on its left and top.
    AtlasBins bins(settings.size - settings.padding, heuristic);
    Result result;
    result.packing.placed.resize(charts.size());
    for (const Item& item : items) {
        Placed p = bins.place(item.w, item.h);
        p.x += settings.padding;
        p.y += settings.padding;
        p.turns = item.turned ? 1 : 0;
        result.packing.placed[item.chart] = p;
    }
    result.packing.atlases = bins.count();
    result.last_top = bins.last_top();
    return result;
}

} // namespace

Packing pack_rectangles(const std::vector<Oriented>& charts, const AtlasSettings& settings) {
    std::optional<Result> best;
    for (bool portrait : {false, true})
        for (int heuristic :
             {STBRP_HEURISTIC_Skyline_BL_sortHeight, STBRP_HEURISTIC_Skyline_BF_sortHeight}) {
            Result r = pack(charts, settings, portrait, heuristic);
            if (!best || std::tie(r.packing.atlases, r.last_top) <
                             std::tie(best->packing.atlases, best->last_top))
                best = std::move(r);
        }
    return std::move(best->packing);
}

} // namespace penumbra::lightmap
