#pragma once
// Private to penumbra_pipeline: the files `penumbra annual` writes (issue #31) from a year of
// hourly illuminance at the scene's sensors and its metrics: annual.csv, summary.json, a plan
// per grid and metric, an hour × day heat map of one sensor, a .vtp per grid and, on request,
// the hourly values, and annual_mesh.vtu. write_annual() (app/annual.h) writes them. README.md and
// docs/annual.md describe each file.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "annual/metrics.h"
#include "app/annual.h"
#include "core/scene.h"

namespace penumbra::app {

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
std::string annual_csv(const Scene& scene, const AnnualResult& result);

/// \brief summary.json: hours, occupancy, thresholds, per grid sDA, ASE and the hours its
///        blinds close, the weather, patches, sun bins, coefficients' system and stage times.
std::string annual_summary_json(const Scene& scene, const AnnualResult& result);

} // namespace penumbra::app
