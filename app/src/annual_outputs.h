#pragma once
// Private to penumbra_pipeline: the files `penumbra annual` writes (issue #31) from a year of
// hourly illuminance at the scene's sensors and its metrics: annual.csv, summary.json, a plan
// per grid and metric, an hour × day heat map of one sensor, a .vtp per grid and, on request,
// the hourly values. README.md and docs/annual.md describe each file.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "annual/epw.h"
#include "annual/metrics.h"
#include "core/context.h"
#include "core/scene.h"

namespace penumbra::app {

/// \brief What `penumbra annual` computed, for its outputs. The pointers must outlive the
///        call to write_annual_outputs().
struct AnnualResults {
    const Scene* scene = nullptr;             ///< sensors (names, positions) and grids
    const annual::Weather* weather = nullptr; ///< the hours (month, day, hour)
    std::vector<bool> occupied;               ///< per hour
    annual::MetricThresholds thresholds;
    annual::Occupancy occupancy;
    Eigen::MatrixXf illuminance_lx; ///< sensors × hours: sky and sun, direct and reflected
    Eigen::MatrixXf direct_sun_lx;  ///< sensors × hours: the sun's direct light only
    std::vector<annual::SensorMetrics> sensors; ///< per sensor of the scene
    std::vector<annual::GridMetrics> grids;     ///< per Scene::grids entry
    /// Merged into summary.json's top level (the command's patches, timings, weather file,
    /// site); its keys must not be those this module writes.
    nlohmann::json run = nlohmann::json::object();
};

struct AnnualOutputOptions {
    std::string directory;
    bool hourly = false; ///< --hourly: hourly_illuminance.f32 and .json
    /// --heat-map NAME; unset: the first point of the first grid, else the first sensor.
    std::optional<std::string> heat_map_sensor;
};

/// \brief A per-sensor metric as the outputs show it: its annual.csv column (also its .vtp
///        array), the METRIC of annual_GRID_METRIC.png, its heading on a plan and its unit.
struct AnnualMetric {
    enum class GridStatistic { none, spatial_daylight_autonomy, annual_sunlight_exposure };

    std::string_view column;
    std::string_view file;
    std::string_view unit; ///< "%" (of the occupied hours) or "h"
    std::string (*heading)(const annual::MetricThresholds&);
    double (*value)(const annual::SensorMetrics&);
    GridStatistic statistic = GridStatistic::none; ///< shown in the plan's title
};

/// \brief The seven metrics, in annual.csv's order.
const std::vector<AnnualMetric>& annual_metrics();

/// \brief Sensor \p index's name as the outputs write it: its own, or "sINDEX" if empty.
std::string sensor_label(const Scene& scene, std::size_t index);

/// \brief The sensor of the heat map: the one named \p name, else the first point of the
///        first grid, else the first sensor; none when the scene has no sensors.
/// \throws ConfigError naming \p name when no sensor has it.
std::optional<std::size_t> heat_map_sensor(const Scene& scene,
                                           const std::optional<std::string>& name);

/// \brief annual.csv: a header, then per sensor its name, position and every metric.
std::string annual_csv(const AnnualResults& results);

/// \brief summary.json: hours, occupancy, thresholds, per grid sDA and ASE, and results.run.
/// \throws InternalError if results.run has a key of its own.
std::string annual_summary_json(const AnnualResults& results);

/// \brief Writes every file into options.directory (created if missing), each atomically,
///        and removes the annual_*.png, annual_*.vtp and heat_map_*.png an earlier run left
///        for grids or sensors this one does not draw, and the hourly files without --hourly.
/// \throws ConfigError for an unknown --heat-map sensor (before writing anything);
///         InternalError for matrices or metrics whose sizes disagree with the scene.
void write_annual_outputs(const AnnualResults& results, const AnnualOutputOptions& options,
                          const Context& ctx);

} // namespace penumbra::app
