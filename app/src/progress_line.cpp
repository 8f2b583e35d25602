#include "progress_line.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace penumbra::app {

namespace {

/// Before this fraction the pace is mostly the stage's start-up: no estimate.
constexpr double k_least_fraction = 0.02;
constexpr int k_bar_cells = 40;

} // namespace

std::optional<double> seconds_left(double fraction, double elapsed_s) {
    if (!(fraction >= k_least_fraction) || fraction >= 1.0 || !(elapsed_s >= 0))
        return std::nullopt;
    return elapsed_s * (1.0 - fraction) / fraction;
}

std::string readable_duration(double seconds) {
    const auto s = static_cast<long long>(std::llround(std::max(0.0, seconds)));
    if (s < 60)
        return fmt::format("{} s", s);
    if (s < 3600)
        return fmt::format("{} min {:02} s", s / 60, s % 60);
    return fmt::format("{} h {:02} min", s / 3600, (s % 3600) / 60);
}

std::string progress_line(std::string_view stage, double fraction, double elapsed_s) {
    fraction = std::clamp(fraction, 0.0, 1.0);
    const int filled = int(fraction * k_bar_cells + 0.5);
    std::string line = fmt::format(
        "{:<14} [{}{}] {:3}% {:6.1f} s", stage, std::string(std::size_t(filled), '#'),
        std::string(std::size_t(k_bar_cells - filled), '.'), int(fraction * 100 + 0.5), elapsed_s);
    if (const auto left = seconds_left(fraction, elapsed_s))
        line += ", " + readable_duration(*left) + " left";
    return line;
}

} // namespace penumbra::app
