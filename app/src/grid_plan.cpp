// A grid's plan: each pixel inside the outline takes the bilinear value of the lattice at its
// centre, the lattice's absent points filled from their nearest present ones (breadth-first);
// iso-lines are the pixels whose band of the colour scale differs from a neighbour's.

#include "grid_plan.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

#include <fmt/format.h>

#include "colour_scale.h"

namespace penumbra::app {

namespace {

constexpr Rgb8 k_white{255, 255, 255};
constexpr Rgb8 k_ink{20, 20, 20};
constexpr Rgb8 k_iso_line{45, 45, 45};
constexpr int k_text_scale = 2;

/// A statistic as a label: three significant digits, without an exponent below 10^6.
std::string label(double value) {
    const double a = std::abs(value);
    if (a >= 100 || a == 0)
        return fmt::format("{:.0f}", value);
    return fmt::format("{:.{}f}", value, a >= 10 ? 1 : (a >= 1 ? 2 : 3));
}

/// A level as a tick label, with the decimals the levels need (a step of 2.5: one; 0.5 %: one).
std::string level_label(double level, const ColourScale& scale) {
    int decimals = 0;
    const auto whole = [&](double v) {
        const double scaled = v * std::pow(10.0, decimals);
        return std::abs(scaled - std::round(scaled)) <= 1e-6 * std::max(1.0, std::abs(scaled));
    };
    for (double v : scale.levels)
        while (decimals < 6 && !whole(v))
            ++decimals;
    return fmt::format("{:.{}f}", level, decimals);
}

/// The lattice with each absent point given the value of its nearest present one (by steps
/// between neighbours: a breadth-first search from all present points at once).
std::vector<double> filled_lattice(const SensorGrid& grid, const std::vector<double>& values) {
    const std::size_t columns = std::size_t(grid.columns);
    std::vector<double> filled(grid.sensors.size(), std::numeric_limits<double>::quiet_NaN());
    std::deque<std::size_t> queue;
    for (std::size_t i = 0, k = 0; i < grid.sensors.size(); ++i)
        if (grid.sensors[i]) {
            filled[i] = values[k++];
            queue.push_back(i);
        }
    for (; !queue.empty(); queue.pop_front()) {
        const std::size_t i = queue.front(), r = i / columns, c = i % columns;
        const auto visit = [&](std::size_t j) {
            if (std::isnan(filled[j])) {
                filled[j] = filled[i];
                queue.push_back(j);
            }
        };
        if (c > 0)
            visit(i - 1);
        if (c + 1 < columns)
            visit(i + 1);
        if (r > 0)
            visit(i - columns);
        if (r + 1 < std::size_t(grid.rows))
            visit(i + columns);
    }
    return filled;
}

/// Bilinear in the filled lattice at fractional (row, column), clamped to the lattice.
double bilinear(const SensorGrid& grid, const std::vector<double>& filled, double row,
                double column) {
    const double r = std::clamp(row, 0.0, double(grid.rows - 1));
    const double c = std::clamp(column, 0.0, double(grid.columns - 1));
    const int r0 = std::min(int(r), std::max(grid.rows - 2, 0));
    const int c0 = std::min(int(c), std::max(grid.columns - 2, 0));
    const int r1 = std::min(r0 + 1, grid.rows - 1), c1 = std::min(c0 + 1, grid.columns - 1);
    const double fr = r - r0, fc = c - c0;
    const auto at = [&](int i, int j) {
        return filled[std::size_t(i) * std::size_t(grid.columns) + std::size_t(j)];
    };
    return (1 - fr) * ((1 - fc) * at(r0, c0) + fc * at(r0, c1)) +
           fr * ((1 - fc) * at(r1, c0) + fc * at(r1, c1));
}

/// Colours the plan's pixels inside the outline and draws the iso-lines: a pixel whose band
/// of the scale differs from its right or lower neighbour's.
void paint_field(Canvas& canvas, const PlanLayout& layout, const SensorGrid& grid,
                 const std::vector<double>& filled, const ColourScale& scale) {
    const int w = layout.plan_width, h = layout.plan_height;
    std::vector<std::optional<int>> band(std::size_t(w) * std::size_t(h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const auto [row, column] =
                layout.lattice_at(grid, layout.plan_x + x, layout.plan_y + y);
            if (!grid.covers(row, column))
                continue;
            const double value = bilinear(grid, filled, row, column);
            band[std::size_t(y) * std::size_t(w) + std::size_t(x)] = scale.band(value);
            canvas.set(layout.plan_x + x, layout.plan_y + y, scale.colour(value));
        }
    const auto band_at = [&](int x, int y) {
        return band[std::size_t(y) * std::size_t(w) + std::size_t(x)];
    };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const auto b = band_at(x, y);
            const bool edge = b && ((x + 1 < w && band_at(x + 1, y) && *band_at(x + 1, y) != *b) ||
                                    (y + 1 < h && band_at(x, y + 1) && *band_at(x, y + 1) != *b));
            if (edge)
                canvas.set(layout.plan_x + x, layout.plan_y + y, k_iso_line);
        }
}

void draw_outline_and_points(Canvas& canvas, const PlanLayout& layout, const SensorGrid& grid) {
    const auto lattice = [&](const Vec3& p) {
        const Vec3 d = p - grid.origin;
        return std::pair(dot(d, grid.v) / grid.spacing_m, dot(d, grid.u) / grid.spacing_m);
    };
    for (const auto& [a, b] : grid.outline) {
        const auto [ra, ca] = lattice(a);
        const auto [rb, cb] = lattice(b);
        const auto [xa, ya] = layout.pixel_at(grid, ra, ca);
        const auto [xb, yb] = layout.pixel_at(grid, rb, cb);
        canvas.line(xa, ya, xb, yb, 2, k_ink);
    }
    for (int r = 0; r < grid.rows; ++r)
        for (int c = 0; c < grid.columns; ++c)
            if (grid.sensor_at(r, c)) {
                const auto [x, y] = layout.pixel_at(grid, r, c);
                const int px = int(std::lround(x)), py = int(std::lround(y));
                canvas.fill(px - 1, py - 1, px + 2, py + 2, k_ink);
            }
}

void draw_title(Canvas& canvas, const PlanTitle& title) {
    const int x = PlanLayout::k_margin;
    canvas.text(x, PlanLayout::k_margin, title.heading, k_text_scale, k_ink);
    canvas.text(x, PlanLayout::k_margin + 22, title.statistics, k_text_scale, k_ink);
}

} // namespace

void draw_colour_bar(Canvas& canvas, int x, int top, int width, int height,
                     const ColourScale& scale) {
    for (int i = 0; i < height; ++i)
        canvas.fill(x, top + i, x + width, top + i + 1, viridis((height - i - 0.5) / height));
    const int text_height = Canvas::text_height(k_text_scale);
    const int tick_x = x + width;
    for (double level : scale.levels) {
        const int y = top + height - int(std::lround(scale.fraction(level) * height));
        canvas.fill(tick_x, y - 1, tick_x + 6, y + 1, k_ink);
        canvas.text(tick_x + 10, y - text_height / 2, level_label(level, scale), k_text_scale,
                    k_ink);
    }
}

PlanLayout PlanLayout::of(const SensorGrid& grid) {
    double u_lo = std::numeric_limits<double>::infinity(), u_hi = -u_lo;
    double v_lo = u_lo, v_hi = -u_lo;
    for (const auto& edge : grid.outline)
        for (const Vec3& p : edge) {
            u_lo = std::min(u_lo, dot(p, grid.u)), u_hi = std::max(u_hi, dot(p, grid.u));
            v_lo = std::min(v_lo, dot(p, grid.v)), v_hi = std::max(v_hi, dot(p, grid.v));
        }
    PlanLayout l;
    l.px_per_m = k_plan_long_px / std::max(u_hi - u_lo, v_hi - v_lo);
    l.u_min = u_lo;
    l.v_max = v_hi;
    l.plan_x = k_margin;
    l.plan_y = k_title_height;
    l.plan_width = std::max(1, int(std::lround((u_hi - u_lo) * l.px_per_m)));
    l.plan_height = std::max(1, int(std::lround((v_hi - v_lo) * l.px_per_m)));
    l.bar_x = l.plan_x + l.plan_width + k_bar_gap;
    l.bar_y = k_title_height;
    l.bar_height = std::max(l.plan_height, k_min_bar_height);
    l.width = std::max(k_margin + l.plan_width + k_legend_width + k_margin, k_min_width);
    l.height = k_title_height + l.bar_height + k_margin;
    return l;
}

std::pair<double, double> PlanLayout::lattice_at(const SensorGrid& grid, int x, int y) const {
    const double u = u_min + (x - plan_x + 0.5) / px_per_m;
    const double v = v_max - (y - plan_y + 0.5) / px_per_m;
    return {(v - dot(grid.origin, grid.v)) / grid.spacing_m,
            (u - dot(grid.origin, grid.u)) / grid.spacing_m};
}

std::pair<double, double> PlanLayout::pixel_at(const SensorGrid& grid, double row,
                                               double column) const {
    const Vec3 p = grid.point(row, column);
    return {plan_x + (dot(p, grid.u) - u_min) * px_per_m - 0.5,
            plan_y + (v_max - dot(p, grid.v)) * px_per_m - 0.5};
}

Canvas draw_grid_plan(const SensorGrid& grid, const std::vector<double>& values,
                      const PlanTitle& title, const ColourScale& scale) {
    const PlanLayout layout = PlanLayout::of(grid);
    Canvas canvas(layout.width, layout.height, k_white);
    paint_field(canvas, layout, grid, filled_lattice(grid, values), scale);
    draw_outline_and_points(canvas, layout, grid);
    draw_colour_bar(canvas, layout.bar_x, layout.bar_y, PlanLayout::k_bar_width, layout.bar_height,
                    scale);
    draw_title(canvas, title);
    return canvas;
}

std::string plan_statistics(const GridStats& stats) {
    return fmt::format("avg {} min {} max {}", label(stats.avg), label(stats.min),
                       label(stats.max));
}

Canvas draw_grid_plan(const SensorGrid& grid, const std::vector<double>& values,
                      const PlanQuantity& quantity) {
    const GridStats stats = stats_of(values);
    const PlanTitle title{fmt::format("{}: {} ({})", grid.name, quantity.name, quantity.unit),
                          fmt::format("{} U0 {:.2f}", plan_statistics(stats), stats.uniformity)};
    return draw_grid_plan(grid, values, title, ColourScale::covering(stats.min, stats.max));
}

} // namespace penumbra::app
