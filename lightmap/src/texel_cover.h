#pragma once
// Conservative coverage: the texels a triangle overlaps with positive area.

#include <algorithm>
#include <cmath>

#include "uv_geometry.h"

namespace penumbra::lightmap {

/// \brief Calls \p f(x, y) for every texel of [0, size)² that \p t (texel coordinates)
///        overlaps with positive area, row by row.
template <typename F> void for_each_covered_texel(const Triangle2& t, int size, F&& f) {
    double lo_x = t[0].x, hi_x = t[0].x, lo_y = t[0].y, hi_y = t[0].y;
    for (const Vec2& p : t) {
        lo_x = std::min(lo_x, p.x);
        hi_x = std::max(hi_x, p.x);
        lo_y = std::min(lo_y, p.y);
        hi_y = std::max(hi_y, p.y);
    }
    const int x0 = std::max(0, int(std::floor(lo_x))), x1 = std::min(size - 1, int(hi_x));
    const int y0 = std::max(0, int(std::floor(lo_y))), y1 = std::min(size - 1, int(hi_y));
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x)
            if (triangle_overlaps_texel(t, x, y))
                f(x, y);
}

} // namespace penumbra::lightmap
