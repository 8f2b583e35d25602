// Our own atlas packer, compared with stb_rect_pack's by pack_atlases. It keeps a skyline
// over the atlas's columns as skyline packers do, but a chart meets it with its own texel
// profile (the lowest covered texel of each of its columns) rather than its bounding
// rectangle, and raises it by its covered texels dilated by the padding; so triangular and
// round charts nest into each other. Like every skyline, it gives up the holes under
// overhangs. Each chart goes where its top ends lowest, in whichever of its four quarter
// turns ends lowest.

#include <climits>
#include <optional>
#include <tuple>

#include "packing_internal.h"
#include "texel_cover.h"

namespace penumbra::lightmap {

namespace {

struct Profile {
    int width = 0, height = 0;
    std::vector<int> bottom; ///< per column: its lowest covered row (height if none)
    /// Per column from −padding to width + padding: one past the last row that the covered
    /// texels dilated by the padding block, relative to row 0; INT_MIN where none do.
    std::vector<int> top;
};

Profile make_profile(const Chart& chart, const Oriented& o, int turns, int padding) {
    Profile p;
    p.width = o.covered_width(turns);
    p.height = o.covered_height(turns);
    p.bottom.assign(std::size_t(p.width), p.height);
    std::vector<int> highest(std::size_t(p.width), -1);
    for (const ChartTriangle& t : chart.triangles) {
        const Triangle2 tri{o.turn(o.q[t.vertices[0]], turns), o.turn(o.q[t.vertices[1]], turns),
                            o.turn(o.q[t.vertices[2]], turns)};
        for_each_covered_texel(tri, std::max(p.width, p.height), [&](int x, int y) {
            if (x < p.width && y < p.height) {
                p.bottom[std::size_t(x)] = std::min(p.bottom[std::size_t(x)], y);
                highest[std::size_t(x)] = std::max(highest[std::size_t(x)], y);
            }
        });
    }
    p.top.assign(std::size_t(p.width + 2 * padding), INT_MIN);
    for (int c = 0; c < p.width; ++c)
        if (highest[std::size_t(c)] >= 0)
            for (int d = c; d <= c + 2 * padding; ++d) // columns c − padding … c + padding
                p.top[std::size_t(d)] =
                    std::max(p.top[std::size_t(d)], highest[std::size_t(c)] + 1 + padding);
    return p;
}

struct Spot {
    int x = 0, y = 0;
};

class ProfileAtlas {
public:
    ProfileAtlas(int size, int padding)
        : size_(size), padding_(padding), sky_(std::size_t(size), padding) {}

    // The lowest place for the profile (then leftmost), if it fits.
    std::optional<Spot> lowest(const Profile& p) const {
        std::optional<Spot> best;
        // Rows from which a spot is no better than the best so far (or does not fit).
        int limit = size_ - padding_ - p.height + 1;
        for (int x = padding_; x + p.width <= size_ - padding_; ++x) {
            int y = padding_;
            for (int c = 0; c < p.width && y < limit; ++c)
                if (p.bottom[std::size_t(c)] < p.height)
                    y = std::max(y, sky_[std::size_t(x + c)] - p.bottom[std::size_t(c)]);
            if (y < limit) {
                best = Spot{x, y};
                limit = y;
            }
        }
        return best;
    }

    void place(const Profile& p, Spot at) {
        for (int d = 0; d < p.width + 2 * padding_; ++d) {
            const int x = at.x - padding_ + d;
            if (x >= 0 && x < size_ && p.top[std::size_t(d)] != INT_MIN)
                sky_[std::size_t(x)] = std::max(sky_[std::size_t(x)], at.y + p.top[std::size_t(d)]);
        }
    }

private:
    int size_, padding_;
    std::vector<int> sky_; ///< per column: the first row not blocked
};

// In the first atlas where some turn fits (a new one if none does), the turn whose top ends
// lowest (ties: fewer turns), at its lowest, leftmost spot.
Placed place_lowest(const std::vector<Profile>& turns, std::vector<ProfileAtlas>& atlases,
                    const AtlasSettings& settings) {
    for (std::uint32_t a = 0;; ++a) {
        if (a == atlases.size())
            atlases.emplace_back(settings.size, settings.padding);
        std::optional<Placed> best;
        int best_top = 0;
        for (int k = 0; k < int(turns.size()); ++k) {
            const std::optional<Spot> spot = atlases[a].lowest(turns[std::size_t(k)]);
            const int top = spot ? spot->y + turns[std::size_t(k)].height : 0;
            if (spot && (!best || top < best_top)) {
                best = Placed{a, spot->x, spot->y, k};
                best_top = top;
            }
        }
        if (best) {
            atlases[a].place(turns[std::size_t(best->turns)], {best->x, best->y});
            return *best;
        }
    }
}

} // namespace

Packing pack_profiles(const Charts& charts, const std::vector<Oriented>& oriented,
                      const AtlasSettings& settings) {
    std::vector<std::uint32_t> order(oriented.size());
    for (std::uint32_t i = 0; i < order.size(); ++i)
        order[i] = i;
    auto key = [&](std::uint32_t i) {
        const int w = oriented[i].covered_width(0), h = oriented[i].covered_height(0);
        return std::tuple(std::max(w, h), std::min(w, h));
    };
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        return key(a) > key(b) || (key(a) == key(b) && a < b);
    });
    Packing packing;
    packing.placed.resize(oriented.size());
    std::vector<ProfileAtlas> atlases;
    for (std::uint32_t i : order) {
        std::vector<Profile> turns;
        for (int k = 0; k < 4; ++k)
            turns.push_back(make_profile(charts.charts[i], oriented[i], k, settings.padding));
        packing.placed[i] = place_lowest(turns, atlases, settings);
    }
    packing.atlases = int(atlases.size());
    return packing;
}

} // namespace penumbra::lightmap
