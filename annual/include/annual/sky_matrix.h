#pragma once
// A year of skies as sky vectors (issue #31): for every hour of a weather file, the mean
// radiance of each sky patch under that hour's Perez all-weather sky, the ground's radiance,
// and the sun kept apart (its exact direction and direct-normal illuminance; it is not smeared
// into patches). Radiance's gendaymtx computes the same matrix (without -5 or -d/-s options);
// docs/annual.md gives the differences.

#include <vector>

#include <Eigen/Core>

#include "core/context.h"
#include "core/sky.h"
#include "core/vec.h"

#include "annual/epw.h"
#include "annual/sky_patches.h"

namespace penumbra::annual {

/// \brief Which of the EPW's solar fields make each hour's sky.
enum class WeatherInput {
    /// Direct-normal and diffuse-horizontal radiation (fields 15, 16) with Perez's luminous
    /// efficacies, as gendaymtx does by default.
    irradiance,
    /// Direct-normal and diffuse-horizontal illuminance (fields 18, 19); an hour where either
    /// is missing is an InputError.
    illuminance,
};

struct SkyMatrixOptions {
    WeatherInput input = WeatherInput::irradiance;
    /// Reflectance of the uniform ground (patch 0), whose radiance is ρ_g E_global / π.
    double ground_reflectance = 0.2;
};

/// \brief The sun of one hour.
struct HourSun {
    Vec3 direction;       ///< unit, toward the sun at mid-hour (also below the horizon)
    SolarAngles angles;   ///< the same as altitude and azimuth
    double normal_lx = 0; ///< direct normal illuminance; 0 when the sun is not above the horizon
};

/// \brief Sky vectors of a year, patch × hour.
struct SkyMatrix {
    /// patches × hours (SkyPatches order, ground first): mean radiance over each patch,
    /// W/(sr·m²) of luminance-equivalent grey (luminance / 179 lm/W, Radiance's convention).
    /// All zero in an hour without diffuse light and without the sun above the horizon.
    Eigen::MatrixXf radiance;
    std::vector<HourSun> suns; ///< one per hour
};

/// \brief The sky vectors and suns of every hour of \p weather over \p patches: each hour's
///        sky by perez_sky_and_sun() (sharp horizon, the sun at mid-hour), each patch's mean
///        radiance by a Gauss–Legendre rule over its altitude and azimuth bounds, finer near
///        the sun (about 2 600 directions over the sky for MF 1, 9 300 for MF 4; within 3e-4
///        of the exact mean). Hours run in parallel in the context's
///        arena; the result does not depend on the thread count.
/// \throws InputError for an hour whose illuminance fields are missing (WeatherInput::
///         illuminance); ConfigError for a ground reflectance outside [0, 1].
SkyMatrix sky_matrix(const Weather& weather, const SkyPatches& patches,
                     const SkyMatrixOptions& options, const Context& ctx);

/// \brief The mean radiance over each of \p patches of \p sky (W/(sr·m²), luminance-
///        equivalent), by the same rule as sky_matrix(); the ground gets sky.ground_radiance
///        (0 if unset).
Eigen::VectorXf sky_vector(const Sky& sky, const SkyPatches& patches);

} // namespace penumbra::annual
