#include "size_field.h"

#include <algorithm>
#include <cmath>

namespace penumbra::mesher {

std::uint64_t SizeField::cell_key(std::int64_t x, std::int64_t y) const {
    return (std::uint64_t(x) * 0x9E3779B97F4A7C15ull) ^ std::uint64_t(y);
}

SizeField::SizeField(const std::vector<Segment2>& segments, double max_edge, double near_factor)
    : segments_(segments), max_edge_(max_edge), near_factor_(near_factor) {
    // Every cell within one cell of a point sampled every half cell along the segment: all
    // cells closer than max_edge to the segment.
    for (std::uint32_t i = 0; i < segments_.size(); ++i) {
        const Segment2& s = segments_[i];
        const int steps = int(std::ceil(2 * s.length() / max_edge_)) + 1;
        for (int k = 0; k <= steps; ++k) {
            const Vec2 p = s.a + (s.b - s.a) * (double(k) / steps);
            const auto cx = std::int64_t(std::floor(p.x / max_edge_));
            const auto cy = std::int64_t(std::floor(p.y / max_edge_));
            for (std::int64_t dx = -1; dx <= 1; ++dx)
                for (std::int64_t dy = -1; dy <= 1; ++dy) {
                    auto& cell = grid_[cell_key(cx + dx, cy + dy)];
                    if (cell.empty() || cell.back() != i)
                        cell.push_back(i);
                }
        }
    }
}

double SizeField::bound(const Vec2& p) const {
    const auto cx = std::int64_t(std::floor(p.x / max_edge_));
    const auto cy = std::int64_t(std::floor(p.y / max_edge_));
    auto it = grid_.find(cell_key(cx, cy));
    if (it == grid_.end())
        return max_edge_;
    double d = max_edge_;
    for (std::uint32_t i : it->second)
        d = std::min(d, distance_to_segment(p, segments_[i].a, segments_[i].b));
    return max_edge_ * (near_factor_ + (1 - near_factor_) * d / max_edge_);
}

} // namespace penumbra::mesher
