#pragma once
// Private to penumbra_core: `!gensky` lines (issue #30), read as Radiance's gensky(1) reads its
// arguments and turned into the primitives it would print: the `skyfunc` brightfunc of
// skybright.cal and, for a sunny sky, the `solar` light and its `sun` source. Its formulas for
// the zenith radiance, the normalisation and the ground are gensky's (gensky.c), so that a
// scene keeps Radiance's sky; its sun is solar_position_gensky (core/solar_position.h).

#include <vector>

#include "core/vec.h"

#include "syntax.h"

namespace penumbra::radiance {

/// \brief gensky's results before printing (W/(sr·m²), Radiance's axes: x east, y north,
///        z up).
struct GenskyResult {
    int sky_type = 1;           ///< skybright.cal A1: 1 CIE clear, 2 overcast, 3 uniform, 4 interm.
    double zenith_radiance = 0; ///< A2
    double ground_radiance = 0; ///< A3 (the ground plane's, reflectance included)
    double normalisation = 0;   ///< A4 (F2) of the clear and intermediate skies, else 0
    Vec3 sun_direction;         ///< unit, toward the sun
    bool sun = false;           ///< a `solar` source is printed
    double sun_radiance = 0;    ///< of the solar disc, W/(sr·m²)
    /// What gensky prints as "Ground ambient level": the sky's horizontal irradiance / π
    /// (before the sun and the ground's reflectance).
    double ambient_level = 0;
};

/// \brief Interprets \p command ("gensky month day [+]hour options" or "gensky -ang altitude
///        azimuth options"): -s/+s, -c, -u, -i/+i, -b/-B, -r/-R, -t, -g, -a, -o, -m. The year
///        option -y (Michalsky's sun) and time-zone names after the hour are InputErrors at
///        the command's line, as are malformed arguments.
GenskyResult run_gensky(const Command& command);

/// \brief The primitives gensky prints for \p result, at \p where.
std::vector<Primitive> gensky_primitives(const GenskyResult& result, const SourceLine& where);

} // namespace penumbra::radiance
