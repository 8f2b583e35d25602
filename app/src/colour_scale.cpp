#include "colour_scale.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace penumbra::app {

namespace {

ColourScale linear_scale(double max_value, int max_steps) {
    ColourScale scale;
    if (!(max_value > 0) || !std::isfinite(max_value))
        return scale;
    // decade ≤ max_value / max_steps < 10 × decade, so a step of 10 × decade always fits.
    const double decade = std::pow(10.0, std::floor(std::log10(max_value / max_steps)));
    double step = 10 * decade, steps = 1;
    for (double mantissa : {10.0, 5.0, 2.5, 2.0, 1.0}) {
        // The tolerance keeps a maximum that is a whole number of steps from adding a step.
        const double n = std::max(1.0, std::ceil(max_value / (mantissa * decade) * (1 - 1e-12)));
        if (n <= max_steps)
            step = mantissa * decade, steps = n;
    }
    scale.levels.clear();
    for (int k = 0; k <= int(steps); ++k)
        scale.levels.push_back(k * step);
    return scale;
}

/// 1, 2, 5 × 10^k from the largest at or below \p lo to the smallest at or above \p hi; only
/// the decades when that would make more than 10 levels.
ColourScale log_scale(double lo, double hi) {
    ColourScale scale;
    scale.logarithmic = true;
    const bool decades_only = hi / lo > 1e3;
    const std::array<double, 3> mantissas{1, 2, 5};
    std::vector<double> candidates;
    for (int e = int(std::floor(std::log10(lo))) - 1; e <= int(std::ceil(std::log10(hi))); ++e)
        for (double m : mantissas)
            if (!decades_only || m == 1)
                candidates.push_back(m * std::pow(10.0, e));
    const double slack = 1 + 1e-12; // a value on a level is that level
    const auto first = std::find_if(candidates.rbegin(), candidates.rend(),
                                    [&](double c) { return c <= lo * slack; });
    const auto last = std::find_if(candidates.begin(), candidates.end(),
                                   [&](double c) { return c * slack >= hi; });
    scale.levels.assign(first.base() - 1, last + 1);
    return scale;
}

} // namespace

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

ColourScale ColourScale::covering(double min_value, double max_value, int max_steps) {
    if (min_value > 0 && std::isfinite(max_value) && max_value > 10 * min_value)
        return log_scale(min_value, max_value);
    return linear_scale(max_value, max_steps);
}

double ColourScale::fraction(double value) const {
    const double t = logarithmic ? std::log(value / bottom()) / std::log(top() / bottom())
                                 : (value - bottom()) / (top() - bottom());
    return std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
}

int ColourScale::band(double value) const {
    return int(std::upper_bound(levels.begin() + 1, levels.end(), value) - levels.begin()) - 1;
}

} // namespace penumbra::app
