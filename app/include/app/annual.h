#pragma once
// `penumbra annual` (issue #31): a year of hourly illuminance at a scene's sensors from an EPW
// weather file through daylight coefficients, and the climate-based metrics over it.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "annual/epw.h"
#include "annual/metrics.h"
#include "annual/sky_matrix.h"
#include "annual/sky_patches.h"
#include "core/context.h"
#include "core/scene.h"
#include "solver/daylight_coefficients.h"

namespace penumbra::app {

/// \brief What an annual study takes besides the scene.
struct AnnualOptions {
    std::string weather_file; ///< EPW
    int subdivision = 1;      ///< sky patches: 1 = Tregenza's 145 (+ ground), 2–4 Reinhart's
    /// The suns' bins: Reinhart's patches of this subdivision (2: 578, about 6° across).
    int sun_subdivision = 2;
    annual::SkyMatrixOptions sky; ///< from irradiance or illuminance; ground reflectance
    annual::Occupancy occupancy;  ///< 8:00–18:00 by default
    annual::MetricThresholds thresholds;
};

/// \brief A year at the sensors: coefficients, hourly illuminance and metrics.
struct AnnualResult {
    annual::Weather weather;
    solver::DaylightCoefficients coefficients;
    std::size_t patches = 0;
    std::size_t sun_bins = 0;
    /// Sensors × hours, lx: sky (seen and reflected), the sun's direct light and its
    /// reflected part.
    Eigen::MatrixXf illuminance_lx;
    Eigen::MatrixXf direct_sun_lx; ///< sensors × hours, lx: the sun's direct light only
    std::vector<bool> occupied;
    std::vector<annual::SensorMetrics> sensors;
    std::vector<annual::GridMetrics> grids; ///< per Scene::grids entry
    double coefficient_seconds = 0, hours_seconds = 0;
};

/// \brief The coefficients' binning of sky directions: each direction shared among the
///        patches around it (SkyPatches::interpolate). \p patches must outlive it.
solver::PatchBinning patch_binning(const annual::SkyPatches& patches);

/// \brief The year's suns binned by direction: each hour with the sun up names a bin, each
///        bin one direction (the mean of its hours'), for which the reflected light of a sun
///        is solved once.
struct SunBins {
    std::vector<Vec3> directions;                ///< per bin, unit
    std::vector<std::optional<std::size_t>> bin; ///< per hour; none when the sun is not up
};

/// \brief Bins the suns of \p matrix by the patches of \p bins.
SunBins bin_suns(const annual::SkyMatrix& matrix, const annual::SkyPatches& bins);

/// \brief Hourly illuminance (lx, sensors × hours) of the skies and suns of \p matrix on
///        \p coefficients: (direct + indirect) × radiance, the sun's direct part from
///        \p sun_direct (sensors × hours, W/m² per W/m² of normal irradiance), and its
///        reflected part through the coefficients of its bin.
Eigen::MatrixXf hourly_illuminance_lx(const solver::DaylightCoefficients& coefficients,
                                      const annual::SkyMatrix& matrix, const SunBins& suns,
                                      const Eigen::MatrixXf& sun_direct);

/// \brief The sun's direct illuminance (lx, sensors × hours) from its unit-irradiance
///        visibility \p sun_direct and each hour's normal illuminance.
Eigen::MatrixXf direct_sun_lx(const annual::SkyMatrix& matrix, const Eigen::MatrixXf& sun_direct);

/// \brief Meshes \p scene, computes its sensors' daylight coefficients and the year of
///        \p options' weather file, and the metrics. The scene's own sky and sun are not
///        used: the weather gives them; its compass (Sky::compass) orients the patches.
AnnualResult run_annual(const Scene& scene, const AnnualOptions& options, const Context& ctx);

/// \brief What `penumbra annual` writes besides its results' own choices.
struct AnnualWriteOptions {
    std::string directory;
    bool hourly = false;                        ///< --hourly
    std::optional<std::string> heat_map_sensor; ///< --heat-map NAME
};

/// \brief Throws ConfigError before any work if \p write names a heat-map sensor the scene
///        does not have.
void check_annual_outputs(const Scene& scene, const AnnualWriteOptions& write);

/// \brief Writes annual.csv, summary.json (with the run's patches, timings, weather and
///        coefficients' system), the plans, the heat map, the grids' points and on request the
///        hourly values (README.md, docs/annual.md).
void write_annual(const Scene& scene, const AnnualOptions& options, const AnnualResult& result,
                  const AnnualWriteOptions& write, const Context& ctx);

} // namespace penumbra::app
