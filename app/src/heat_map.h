#pragma once
// Private to penumbra_pipeline: the hour × day heat map of one sensor's illuminance over a
// year (heat_map_SENSOR.png): one cell per hour of the weather file, days to the right and the
// hours of each day downward, on a logarithmic colour scale in lx, with month and hour ticks.

#include <span>
#include <string>

#include "annual/epw.h"

#include "canvas.h"
#include "colour_scale.h"
#include "grid_plan.h"

namespace penumbra::app {

/// \brief Where the parts of a heat map lie, pixels from the top-left corner. Day d of the
///        year (1-based) is the column of cells from x = map_x + (d − 1) k_day_px; the EPW
///        hour h (ending at h, 1–24) the row from y = map_y + (h − 1) k_hour_px, so that the
///        row of clock hour 0–1 is on top.
struct HeatMapLayout {
    static constexpr int k_day_px = 2;
    static constexpr int k_hour_px = 10;
    static constexpr int k_margin = 16;
    static constexpr int k_title_height = 64; ///< two lines of text above the map
    static constexpr int k_axis_width = 40;   ///< the hours' labels left of the map
    static constexpr int k_axis_height = 36;  ///< the months' labels below it
    static constexpr int k_bar_gap = 24;
    static constexpr int k_bar_width = 20;
    static constexpr int k_legend_width = 140; ///< gap, bar, ticks and labels

    int days = 365;
    int width = 0, height = 0;
    int map_x = 0, map_y = 0, map_width = 0, map_height = 0;
    int bar_x = 0;

    /// \brief The layout for a year of \p days days (365 or 366).
    static HeatMapLayout of(int days);
    /// \brief The top-left pixel of the cell of day \p day_of_year and EPW hour \p hour.
    std::pair<int, int> cell(int day_of_year, int hour) const;
};

/// \brief The heat map's colour scale for values up to \p max_lx: logarithmic from 1 lx to the
///        round level at or above max(max_lx, 100 lx) (ColourScale::covering's 1-2-5 levels,
///        decades only past three decades). Hours at or below 1 lx, night included, take the
///        bottom colour.
ColourScale heat_map_scale(double max_lx);

/// \brief Draws the heat map of \p illuminance_lx (one value per hour of \p weather) under
///        \p title.
Canvas draw_heat_map(const annual::Weather& weather, std::span<const float> illuminance_lx,
                     const PlanTitle& title);

} // namespace penumbra::app
