#include "colour_scale.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace penumbra::app {

Rgb8 viridis(double t) {
    // Viridis at 9 evenly spaced points (as R's viridisLite::viridis(9) lists them).
    static constexpr std::array<Rgb8, 9> k_points{{{0x44, 0x01, 0x54},
                                                   {0x47, 0x2d, 0x7b},
                                                   {0x3b, 0x52, 0x8b},
                                                   {0x2c, 0x72, 0x8e},
                                                   {0x21, 0x90, 0x8c},
                                                   {0x27, 0xad, 0x81},
                                                   {0x5d, 0xc8, 0x63},
                                                   {0xaa, 0xdc, 0x32},
                                                   {0xfd, 0xe7, 0x25}}};
    const double x = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * (k_points.size() - 1);
    const std::size_t i = std::min(std::size_t(x), k_points.size() - 2);
    const double f = x - double(i);
    const auto mix = [f](std::uint8_t a, std::uint8_t b) {
        return std::uint8_t(std::lround(a + f * (b - a)));
    };
    const Rgb8 &a = k_points[i], &b = k_points[i + 1];
    return {mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b)};
}

ColourScale ColourScale::covering(double max_value, int max_steps) {
    if (!(max_value > 0) || !std::isfinite(max_value))
        return {1, 1};
    // decade ≤ max_value / max_steps < 10 × decade, so a step of 10 × decade always fits.
    const double decade = std::pow(10.0, std::floor(std::log10(max_value / max_steps)));
    ColourScale scale;
    for (double mantissa : {10.0, 5.0, 2.5, 2.0, 1.0}) {
        const double step = mantissa * decade;
        // The tolerance keeps a maximum that is a whole number of steps from adding a step.
        const double steps = std::max(1.0, std::ceil(max_value / step * (1 - 1e-12)));
        if (steps <= max_steps)
            scale = {step, steps * step};
    }
    return scale;
}

int ColourScale::steps() const {
    return int(std::lround(top / step));
}

double ColourScale::fraction(double value) const {
    return std::clamp(value / top, 0.0, 1.0);
}

int ColourScale::band(double value) const {
    return int(std::floor(std::clamp(value, 0.0, top) / step));
}

} // namespace penumbra::app
