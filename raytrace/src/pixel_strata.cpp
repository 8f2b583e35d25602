#include "pixel_strata.h"

#include "core/rng.h"

namespace penumbra::raytrace {

std::uint32_t permuted(std::uint32_t i, std::uint32_t n, std::uint64_t key) {
    if (n <= 1)
        return 0;
    std::uint32_t mask = n - 1;
    for (int s = 1; s < 32; s *= 2)
        mask |= mask >> s;
    const std::uint64_t mixed = mix64(key);
    const auto k = std::uint32_t(mixed), k2 = std::uint32_t(mixed >> 32);
    // Each step is a bijection of 0 … mask: xor and add a constant, multiply by an odd one,
    // xor with a right shift of itself.
    do {
        i = (i ^ k) & mask;
        i = (i * 0x9e3779b1u) & mask;
        i ^= i >> 3;
        i = (i + k2) & mask;
        i = (i * 0x85ebca6bu) & mask;
        i ^= i >> 5;
        i = (i * 0xc2b2ae35u) & mask;
        i ^= i >> 2;
    } while (i >= n);
    return i;
}

std::uint32_t PixelStrata::cell(std::uint64_t stratum) const {
    const auto cells = std::uint32_t(per_axis) * std::uint32_t(per_axis);
    if (cells == 1)
        return 0; // one camera sample (a path's later vertices, or 1 spp): no hash to draw
    return permuted(std::uint32_t(sample), cells, hash_words({key, stratum}));
}

double PixelStrata::position(int stratum, int count, double jitter) const {
    const double cells = double(per_axis) * double(per_axis);
    return (stratum + (cell(std::uint64_t(stratum)) + jitter) / cells) / count;
}

Vec2 PixelStrata::position(int sx, int sy, int count, const Vec2& jitter) const {
    const std::uint32_t c = cell(std::uint64_t(sy) * std::uint64_t(count) + std::uint64_t(sx));
    const auto n = std::uint32_t(per_axis);
    return {(sx + (c % n + jitter.x) / per_axis) / count,
            (sy + (c / n + jitter.y) / per_axis) / count};
}

} // namespace penumbra::raytrace
