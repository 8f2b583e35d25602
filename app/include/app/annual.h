#pragma once
// `penumbra annual` (issue #31): a year of hourly illuminance at a scene's sensors from an EPW
// weather file through daylight coefficients, and the climate-based metrics over it.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "annual/epw.h"
#include "annual/metrics.h"
#include "annual/sky_matrix.h"
#include "annual/sky_patches.h"
#include "core/context.h"
#include "core/mesh.h"
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
    /// LM-83's blinds rule (--blinds): per group of sensors, the hours it closes take the
    /// illuminance of the scene's `annual.blinds` state; ASE stays that of the open state.
    bool blinds = false;
    /// Metrics per element of the coefficients' mesh too (--mesh): elements × (patches + sun
    /// bins) floats more (docs/annual.md).
    bool mesh = false;
};

/// \brief LM-83's blinds in one group of sensors: a grid, or the sensors of no grid.
struct BlindsGroup {
    std::string name;                   ///< the grid's, or "" for the sensors of no grid
    std::vector<std::uint32_t> sensors; ///< indices into Scene::sensors
    std::vector<bool> closed;           ///< per hour: the shaded state's illuminance counts
};

/// \brief The metrics on every leaf element of the coefficients' system (--mesh); the sun,
///        direct and reflected, through its bins.
struct MeshMetrics {
    RadiosityMesh mesh;                          ///< the leaf elements
    std::vector<annual::SensorMetrics> elements; ///< per element of mesh
    std::vector<float> mean_illuminance_lx;      ///< per element, over the occupied hours
};

/// \brief A year at the sensors: coefficients, hourly illuminance and metrics, and what
///        `penumbra annual` writes of it (write_annual).
struct AnnualResult {
    AnnualOptions options; ///< what the year was computed with
    annual::Weather weather;
    solver::DaylightCoefficients coefficients;
    std::size_t patches = 0;
    std::size_t sun_bins = 0;
    /// Sensors × hours, lx: sky (seen and reflected), the sun's direct light and its
    /// reflected part; with blinds, the shaded state's in the hours its group closes them.
    Eigen::MatrixXf illuminance_lx;
    Eigen::MatrixXf direct_sun_lx; ///< sensors × hours, lx: the sun's direct light only, open
    std::vector<bool> occupied;
    std::vector<annual::SensorMetrics> sensors;
    std::vector<annual::GridMetrics> grids; ///< per Scene::grids entry
    std::vector<BlindsGroup> blinds;        ///< empty without options.blinds
    std::optional<MeshMetrics> mesh;        ///< with options.mesh
    /// Wall time of each stage, in order: weather and sky vectors, coefficients, ...
    std::vector<std::pair<std::string, double>> seconds;
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

/// \brief LM-83's groups of sensors for the blinds: one per grid (its present points), then
///        the sensors of no grid, if any, as one group.
std::vector<BlindsGroup> blinds_groups(const Scene& scene);

/// \brief LM-83's blinds rule: sets each group's closed hours by annual::blinds_closed on its
///        sensors' rows of \p direct_sun_lx (the open state's), and in those hours puts the
///        group's sensors' values of \p shaded_lx into \p illuminance_lx (all sensors × hours).
void apply_blinds(std::vector<BlindsGroup>& groups, const Eigen::MatrixXf& direct_sun_lx,
                  const Eigen::MatrixXf& shaded_lx, const annual::MetricThresholds& thresholds,
                  Eigen::MatrixXf& illuminance_lx);

/// \brief Meshes \p scene, computes its sensors' daylight coefficients and the year of
///        \p options' weather file, and the metrics. The scene's own sky and sun are not
///        used: the weather gives them; its compass (Sky::compass) orients the patches. With
///        options.blinds, a second mesh and set of coefficients for the scene with its
///        `annual.blinds` materials, and apply_blinds(); with options.mesh, mesh_metrics.
/// \throws InputError for a scene without sensors, or blinds without `annual.blinds`.
AnnualResult run_annual(const Scene& scene, const AnnualOptions& options, const Context& ctx);

/// \brief What `penumbra annual` writes besides its results' own choices.
struct AnnualWriteOptions {
    std::string directory;
    bool hourly = false; ///< --hourly: hourly_illuminance.f32 and .json
    /// --heat-map NAME; unset: the first point of the first grid, else the first sensor.
    std::optional<std::string> heat_map_sensor;
};

/// \brief Throws ConfigError before any work if \p write names a heat-map sensor the scene
///        does not have, or if \p options ask for blinds and the scene has no `annual.blinds`.
void check_annual_run(const Scene& scene, const AnnualOptions& options,
                      const AnnualWriteOptions& write);

/// \brief Writes annual.csv, summary.json (with the run's patches, timings, weather, blinds and
///        coefficients' system), the plans, the heat map, the grids' points, on request the
///        hourly values and annual_mesh.vtu (README.md, docs/annual.md) into write.directory
///        (created if missing), each atomically; removes the annual_*.png, annual_*.vtp and
///        heat_map_*.png an earlier run left for grids or sensors this one does not draw, and
///        the hourly files and annual_mesh.vtu this run does not write.
/// \throws ConfigError for an unknown --heat-map sensor (before writing anything);
///         InternalError for matrices or metrics whose sizes disagree with the scene.
void write_annual(const Scene& scene, const AnnualResult& result, const AnnualWriteOptions& write,
                  const Context& ctx);

} // namespace penumbra::app
