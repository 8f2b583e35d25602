#pragma once
// The element size bound over a surface: finer along discontinuity segments, where the
// illumination changes fastest (inside penumbrae), and the full size elsewhere.

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "geometry2d.h"

namespace penumbra::mesher {

class SizeField {
public:
    /// \brief Bound \p near_factor × \p max_edge on the \p segments, growing linearly to
    ///        \p max_edge at distance max_edge from them.
    SizeField(const std::vector<Segment2>& segments, double max_edge, double near_factor);

    /// The size bound at \p p.
    double bound(const Vec2& p) const;

private:
    std::uint64_t cell_key(std::int64_t x, std::int64_t y) const;
    std::vector<Segment2> segments_;
    double max_edge_, near_factor_;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid_; ///< cell → segments
};

} // namespace penumbra::mesher
