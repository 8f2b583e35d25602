#pragma once
// Strata of a camera sample's split samples that the pixel's camera samples share (issue
// #28): each sample's own light and gather samples stay stratified as before, and together a
// pixel's samples fill a grid as many times finer, so the indirect light's noise falls faster
// than one over the samples where it varies smoothly over the hemisphere. Internal to
// raytrace/.

#include "core/vec.h"

#include <cstdint>

namespace penumbra::raytrace {

/// Element \p i of a pseudo-random permutation of 0 … n − 1 named by \p key: an invertible
/// hash of the bits of the next power of two, applied until it lands below n (cycle walking).
std::uint32_t permuted(std::uint32_t i, std::uint32_t n, std::uint64_t key);

/// Which of a pixel's camera samples take which fine cell of each coarse stratum.
struct PixelStrata {
    int per_axis = 1;      ///< the pixel's camera samples are per_axis² (stratified)
    int sample = 0;        ///< this camera sample
    std::uint64_t key = 0; ///< names the pixel and the kind of sample

    /// Where in [0, 1) a sample of stratum \p stratum (of \p count) falls: in the stratum, the
    /// fine cell (of per_axis²) this camera sample takes (a permutation per stratum), then
    /// \p jitter ∈ [0, 1) within it.
    double position(int stratum, int count, double jitter) const;
    /// The same in [0, 1)²: stratum (sx, sy) of count × count, fine cells per_axis × per_axis.
    Vec2 position(int sx, int sy, int count, const Vec2& jitter) const;

private:
    std::uint32_t cell(std::uint64_t stratum) const;
};

} // namespace penumbra::raytrace
