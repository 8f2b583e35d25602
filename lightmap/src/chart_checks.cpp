#include "chart_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace penumbra::lightmap {

namespace {

bool orientations_valid(const std::vector<Triangle2>& uv, const std::vector<double>& area_m2,
                        bool allow_mirrored) {
    for (std::size_t i = 0; i < uv.size(); ++i) {
        const double a = signed_area(uv[i]);
        const double floor = 1e-10 * area_m2[i];
        if (!(a > floor || (allow_mirrored && -a > floor)))
            return false;
    }
    return true;
}

struct Box2 {
    Vec2 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    Vec2 hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    void extend(const Vec2& p) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
};

// Candidate pairs from a uniform grid of about one cell per triangle.
bool any_overlap(const std::vector<Triangle2>& uv) {
    Box2 all;
    for (const Triangle2& t : uv)
        for (const Vec2& p : t)
            all.extend(p);
    const Vec2 extent = all.hi - all.lo;
    const double eps = 1e-9 * length(extent);
    const double cell = std::max(std::sqrt(extent.x * extent.y / double(uv.size())),
                                 std::max(extent.x, extent.y) / 1024.0);
    const int nx = std::max(1, int(std::ceil(extent.x / cell)));
    const int ny = std::max(1, int(std::ceil(extent.y / cell)));
    std::vector<std::vector<std::uint32_t>> cells(std::size_t(nx) * std::size_t(ny));
    auto clamp_cell = [&](double v, int n) {
        return std::clamp(int(std::floor(v / cell)), 0, n - 1);
    };
    for (std::uint32_t i = 0; i < uv.size(); ++i) {
        Box2 b;
        for (const Vec2& p : uv[i])
            b.extend(p - all.lo);
        for (int y = clamp_cell(b.lo.y, ny); y <= clamp_cell(b.hi.y, ny); ++y)
            for (int x = clamp_cell(b.lo.x, nx); x <= clamp_cell(b.hi.x, nx); ++x)
                cells[std::size_t(y) * std::size_t(nx) + std::size_t(x)].push_back(i);
    }
    for (const auto& members : cells)
        for (std::size_t a = 0; a < members.size(); ++a)
            for (std::size_t b = a + 1; b < members.size(); ++b)
                if (triangles_overlap(uv[members[a]], uv[members[b]], eps))
                    return true;
    return false;
}

} // namespace

bool uv_layout_valid(const std::vector<Triangle2>& uv, const std::vector<double>& area_m2,
                     bool allow_mirrored) {
    return orientations_valid(uv, area_m2, allow_mirrored) && !any_overlap(uv);
}

} // namespace penumbra::lightmap
