#pragma once
// Private to penumbra_pipeline: the false-colour scale of grid plans. A perceptual colour
// map (viridis) over round levels, which are the plan's iso-lines and the legend's ticks:
// linear from 0 in steps of 1, 2, 2.5 or 5 × 10^k, or logarithmic over 1-2-5 levels when the
// values span more than a decade (a side-lit room's daylight factors: 0.5 % to 20 %).

#include <vector>

#include "canvas.h"

namespace penumbra::app {

/// \brief Viridis (van der Walt and Smith, matplotlib 2.0) at \p t in [0, 1] (clamped): dark
///        blue to yellow, lightness rising throughout, readable by colour-blind viewers and in
///        grey. Linear in sRGB between its colours at t = 0, 1/8, …, 1.
Rgb8 viridis(double t);

/// \brief Round levels from the bottom of the scale to its top, and where values fall on it.
struct ColourScale {
    std::vector<double> levels{0, 1}; ///< ascending; front() the bottom, back() the top
    bool logarithmic = false;

    /// \brief The scale for values in [\p min_value, \p max_value] (≥ 0): logarithmic over
    ///        1-2-5 levels (decades only past three decades) when min_value > 0 and the span
    ///        exceeds 10; else linear from 0 in the smallest round step giving at most
    ///        \p max_steps steps (0 … 1 for all-zero values).
    static ColourScale covering(double min_value, double max_value, int max_steps = 8);
    double bottom() const { return levels.front(); }
    double top() const { return levels.back(); }
    /// \brief The value's place on the scale, in [0, 1].
    double fraction(double value) const;
    /// \brief How many levels above the bottom lie at or below the value.
    int band(double value) const;
    Rgb8 colour(double value) const { return viridis(fraction(value)); }
};

} // namespace penumbra::app
