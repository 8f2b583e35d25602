// An hour × day heat map: each hour's value fills its cell in the colour of the scale; ticks
// mark the first day of every month (its name centred in the month) and every sixth hour.

#include "heat_map.h"

#include <algorithm>
#include <array>

#include <fmt/format.h>

#include "core/error.h"

namespace penumbra::app {

namespace {

constexpr Rgb8 k_white{255, 255, 255};
constexpr Rgb8 k_ink{20, 20, 20};
constexpr int k_text_scale = 2;
constexpr std::array<const char*, 12> k_months{"Jan", "Feb", "Mar", "Apr", "May", "Jun",
                                               "Jul", "Aug", "Sep", "Oct", "Nov", "Dec"};

void paint_cells(Canvas& canvas, const HeatMapLayout& layout, const annual::Weather& weather,
                 std::span<const float> illuminance_lx, const ColourScale& scale) {
    for (std::size_t i = 0; i < weather.hours.size(); ++i) {
        const auto [x, y] = layout.cell(annual::day_of_year(weather, i), weather.hours[i].hour);
        canvas.fill(x, y, x + HeatMapLayout::k_day_px, y + HeatMapLayout::k_hour_px,
                    scale.colour(illuminance_lx[i]));
    }
}

/// A tick under the map at each month's first day, the month's name centred between ticks.
void draw_month_axis(Canvas& canvas, const HeatMapLayout& layout, const annual::Weather& weather) {
    std::vector<int> first_days;
    for (std::size_t i = 0; i < weather.hours.size(); ++i)
        if (weather.hours[i].day == 1 && weather.hours[i].hour == 1)
            first_days.push_back(annual::day_of_year(weather, i));
    first_days.push_back(layout.days + 1);
    const int bottom = layout.map_y + layout.map_height;
    for (std::size_t m = 0; m + 1 < first_days.size() && m < k_months.size(); ++m) {
        const int x0 = layout.cell(first_days[m], 1).first;
        const int x1 = layout.cell(first_days[m + 1], 1).first;
        canvas.fill(x0, bottom, x0 + 1, bottom + 6, k_ink);
        const int text_x = (x0 + x1 - Canvas::text_width(k_months[m], k_text_scale)) / 2;
        canvas.text(text_x, bottom + 10, k_months[m], k_text_scale, k_ink);
    }
    const int end = layout.map_x + layout.map_width;
    canvas.fill(end - 1, bottom, end, bottom + 6, k_ink);
}

/// A tick left of the map at clock hours 0, 6, 12, 18 and 24, with its number.
void draw_hour_axis(Canvas& canvas, const HeatMapLayout& layout) {
    const int text_height = Canvas::text_height(k_text_scale);
    for (int hour = 0; hour <= 24; hour += 6) {
        const int y = layout.map_y + hour * HeatMapLayout::k_hour_px;
        canvas.fill(layout.map_x - 6, y - 1, layout.map_x, y + 1, k_ink);
        const std::string label = std::to_string(hour);
        canvas.text(layout.map_x - 10 - Canvas::text_width(label, k_text_scale),
                    y - text_height / 2, label, k_text_scale, k_ink);
    }
}

} // namespace

HeatMapLayout HeatMapLayout::of(int days) {
    HeatMapLayout l;
    l.days = days;
    l.map_x = k_margin + k_axis_width;
    l.map_y = k_title_height;
    l.map_width = days * k_day_px;
    l.map_height = 24 * k_hour_px;
    l.bar_x = l.map_x + l.map_width + k_bar_gap;
    l.width = l.map_x + l.map_width + k_legend_width + k_margin;
    l.height = l.map_y + l.map_height + k_axis_height + k_margin;
    return l;
}

std::pair<int, int> HeatMapLayout::cell(int day_of_year, int hour) const {
    return {map_x + (day_of_year - 1) * k_day_px, map_y + (hour - 1) * k_hour_px};
}

ColourScale heat_map_scale(double max_lx) {
    return ColourScale::covering(1, std::max(max_lx, 100.0));
}

Canvas draw_heat_map(const annual::Weather& weather, std::span<const float> illuminance_lx,
                     const PlanTitle& title) {
    if (illuminance_lx.size() != weather.hours.size())
        throw InternalError(fmt::format("draw_heat_map: {} values for {} hours",
                                        illuminance_lx.size(), weather.hours.size()));
    const HeatMapLayout layout = HeatMapLayout::of(weather.has_leap_day() ? 366 : 365);
    const double max_lx = illuminance_lx.empty()
                              ? 0.0
                              : *std::max_element(illuminance_lx.begin(), illuminance_lx.end());
    const ColourScale scale = heat_map_scale(max_lx);
    Canvas canvas(layout.width, layout.height, k_white);
    paint_cells(canvas, layout, weather, illuminance_lx, scale);
    draw_month_axis(canvas, layout, weather);
    draw_hour_axis(canvas, layout);
    draw_colour_bar(canvas, layout.bar_x, layout.map_y, HeatMapLayout::k_bar_width,
                    layout.map_height, scale);
    canvas.text(HeatMapLayout::k_margin, HeatMapLayout::k_margin, title.heading, k_text_scale,
                k_ink);
    canvas.text(HeatMapLayout::k_margin, HeatMapLayout::k_margin + 22, title.statistics,
                k_text_scale, k_ink);
    return canvas;
}

} // namespace penumbra::app
