#pragma once
// Private to penumbra_pipeline: the results of sensor grids and daylight studies (issue #30):
// per-grid statistics, grids.csv and the quantity a grid's plan shows (illuminance, or the
// daylight factor when the scene has a sky).

#include <optional>
#include <string>
#include <vector>

#include "app/pipeline.h"
#include "core/scene.h"

namespace penumbra::app {

/// \brief The daylight factor's reference: the unobstructed horizontal illuminance of the
///        scene's sky alone (lx, no sun; Sky::horizontal_illuminance_lx). None without a sky
///        (or with a black one). The ratio describes a room independently of the sky's level
///        under an overcast sky only: under a clear sky or with a sun it depends on the sun's
///        position, and the sun's light is not in the reference.
std::optional<double> daylight_reference_lx(const Scene& scene);

/// \brief Statistics of one grid's values (the arithmetic mean of its points, as EN 12464-1
///        and the daylight standards take it on a regular grid).
struct GridStats {
    std::size_t points = 0;
    double avg = 0, min = 0, max = 0;
    double uniformity = 0; ///< min / avg; 0 when avg is 0
};

/// \brief The statistics of \p values (at least one).
GridStats stats_of(const std::vector<double>& values);

/// \brief The grid's total illuminance at its present points, lx, in lattice order.
std::vector<double> grid_illuminance_lx(const SensorGrid& grid,
                                        const std::vector<SensorReading>& readings);

/// \brief What a plan shows: a name, its unit and the factor from lx to it.
struct PlanQuantity {
    std::string name;
    std::string unit;
    double per_lx = 1;
};

/// \brief Illuminance in lx, or the daylight factor in % when \p daylight_reference_lx is set.
PlanQuantity plan_quantity(std::optional<double> daylight_reference_lx);

/// \brief grids.csv text: one row per grid with its kind, point count and illuminance
///        statistics (lx), and the daylight factor's mean and minimum (%) when the scene has
///        a sky.
std::string grids_csv(const Scene& scene, const BakeResult& result);

} // namespace penumbra::app
