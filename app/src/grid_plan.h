#pragma once
// Private to penumbra_pipeline: the false-colour plan of a sensor grid (grid_NAME.png, and
// annual_GRID_METRIC.png): the grid's values interpolated over its outline in a perceptual
// colour map, iso-lines at the scale's round steps, the outline, the points, a legend with
// numbers and two lines of title.

#include <optional>
#include <vector>

#include "core/scene.h"

#include "canvas.h"
#include "colour_scale.h"
#include "daylight.h"

namespace penumbra::app {

/// \brief Where the parts of a plan lie, pixels from the top-left corner. The plan's longer
///        side is k_plan_long_px; it is seen from the sensors' side, u to the right and v up.
struct PlanLayout {
    static constexpr int k_plan_long_px = 480;
    static constexpr int k_margin = 16;
    static constexpr int k_title_height = 64; ///< two lines of text above the plan
    static constexpr int k_bar_gap = 24;      ///< between the plan and the colour bar
    static constexpr int k_bar_width = 20;
    static constexpr int k_legend_width = 116; ///< gap, bar, ticks and labels
    static constexpr int k_min_bar_height = 240;
    static constexpr int k_min_width = 496; ///< room for the statistics line

    int width = 0, height = 0;
    int plan_x = 0, plan_y = 0, plan_width = 0, plan_height = 0;
    int bar_x = 0, bar_y = 0, bar_height = 0;
    double px_per_m = 0;
    double u_min = 0, v_max = 0; ///< plane coordinates (m along u, v) of the plan's top left

    /// \brief The picture's layout for \p grid, from its outline's extent.
    static PlanLayout of(const SensorGrid& grid);
    /// \brief The fractional lattice coordinates (row, column) of pixel (x, y)'s centre.
    std::pair<double, double> lattice_at(const SensorGrid& grid, int x, int y) const;
    /// \brief The pixel (x, y) of the point at fractional lattice coordinates.
    std::pair<double, double> pixel_at(const SensorGrid& grid, double row, double column) const;
};

/// \brief The two lines above a plan: what it shows (with its unit) and its statistics.
struct PlanTitle {
    std::string heading;
    std::string statistics;
};

/// \brief Draws the plan of \p grid with \p values at its present points (in lattice order)
///        coloured on \p scale, under \p title. Between the points the values are bilinear;
///        beyond the outermost (within the wall offset) they hold the nearest points' values.
Canvas draw_grid_plan(const SensorGrid& grid, const std::vector<double>& values,
                      const PlanTitle& title, const ColourScale& scale);

/// \brief The colour bar of \p scale, \p width × \p height pixels from (\p x, \p top), its
///        bottom at the scale's bottom, with a tick and a number at every level right of it.
void draw_colour_bar(Canvas& canvas, int x, int top, int width, int height,
                     const ColourScale& scale);

/// \brief "avg A min B max C": a grid's statistics as a plan's title shows them.
std::string plan_statistics(const GridStats& stats);

/// \brief Draws the plan of \p grid with \p values at its present points (in lattice order,
///        as grid_illuminance_lx gives them) in \p quantity's unit, on the scale covering
///        them, titled with the quantity and the statistics (with U0 = min / avg).
Canvas draw_grid_plan(const SensorGrid& grid, const std::vector<double>& values,
                      const PlanQuantity& quantity);

} // namespace penumbra::app
