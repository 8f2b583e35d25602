#pragma once
// Private to penumbra_pipeline: the false-colour scale of grid plans. A perceptual colour
// map (viridis) and a scale from 0 to a round top in round steps, whose steps are the plan's
// iso-lines and the legend's ticks.

#include "canvas.h"

namespace penumbra::app {

/// \brief Viridis (van der Walt and Smith, matplotlib 2.0) at \p t in [0, 1] (clamped): dark
///        blue to yellow, lightness rising throughout, readable by colour-blind viewers and in
///        grey. Linear in sRGB between its colours at t = 0, 1/8, …, 1.
Rgb8 viridis(double t);

/// \brief The values 0 … top in steps of 1, 2, 2.5 or 5 × 10^k.
struct ColourScale {
    double step = 1;
    double top = 1; ///< a whole number of steps, ≥ the largest value

    /// \brief The smallest round step giving at most \p max_steps steps up to \p max_value
    ///        (≥ 0; 0 gives 0 … 1).
    static ColourScale covering(double max_value, int max_steps = 8);
    int steps() const;
    /// \brief The value's place on the scale, in [0, 1].
    double fraction(double value) const;
    /// \brief The value's band: 0 below the first step, 1 up to the second, …
    int band(double value) const;
    Rgb8 colour(double value) const { return viridis(fraction(value)); }
};

} // namespace penumbra::app
