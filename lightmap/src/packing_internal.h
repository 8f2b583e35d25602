#pragma once
// What pack_atlases shares with its two packers: stb_rect_pack on bounding rectangles
// (rect_packer.cpp) and our own packer on the charts' texel profiles (profile_packer.cpp).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "lightmap/atlas.h"
#include "lightmap/charts.h"
#include "uv_geometry.h"

namespace penumbra::lightmap {

/// \brief Texels an extent covers from a texel corner: coordinates within 1e-9 of a texel edge
///        do not cover the next texel (triangle_overlaps_texel's margin).
inline int covered_count(double extent) {
    return std::max(1, int(std::ceil(extent - 1e-9)));
}

/// \brief A chart in texel units, turned to its minimum-area rectangle, its bounding box
///        [0, width] × [0, height].
struct Oriented {
    std::vector<Vec2> q; ///< per chart vertex
    double width = 0, height = 0;
    double density = 0; ///< texels per metre

    /// A point after \p turns quarter turns (counter-clockwise in x-right, y-down texel
    /// axes: (x, y) → (height − y, x) each), the box kept at the origin.
    Vec2 turn(const Vec2& p, int turns) const {
        switch (turns & 3) {
        case 1:
            return {height - p.y, p.x};
        case 2:
            return {width - p.x, height - p.y};
        case 3:
            return {p.y, width - p.x};
        default:
            return p;
        }
    }
    int covered_width(int turns) const { return covered_count(turns & 1 ? height : width); }
    int covered_height(int turns) const { return covered_count(turns & 1 ? width : height); }
};

/// \brief Where a packer put a chart: (x, y) is the corner of its covered texels.
struct Placed {
    std::uint32_t atlas = 0;
    int x = 0, y = 0;
    int turns = 0; ///< quarter turns, 0 to 3 (Oriented::turn)
};

/// \brief A packer's layout: per chart, and the number of atlases.
struct Packing {
    std::vector<Placed> placed;
    int atlases = 0;
};

/// \brief The best of stb_rect_pack's skyline packings of the charts' padded bounding
///        rectangles: every rectangle landscape or every one portrait, bottom-left or best-fit.
Packing pack_rectangles(const std::vector<Oriented>& charts, const AtlasSettings& settings);

/// \brief Our own skyline packer on the charts' covered texels (column profiles), turning each
///        chart by the quarter turns that place it lowest.
Packing pack_profiles(const Charts& charts, const std::vector<Oriented>& oriented,
                      const AtlasSettings& settings);

} // namespace penumbra::lightmap
