#pragma once
// Climate-based daylight metrics from hourly illuminance (issue #31): per sensor Daylight
// Autonomy, continuous DA, Useful Daylight Illuminance and hours of direct sun; per grid IES
// LM-83-12's spatial Daylight Autonomy and Annual Sunlight Exposure, and its blinds rule.
// Definitions, edges (≥ or >) and references: docs/annual.md.

#include <cstddef>
#include <span>
#include <vector>

#include <Eigen/Core>

namespace penumbra::annual {

/// \brief The occupied part of every day, in whole clock hours of local standard time: an
///        EPW record of hour h (the hour ending at h) is occupied when start_hour < h ≤
///        end_hour. The default, 8:00–18:00, is LM-83's: EPW hours 9–18, 3 650 hours a year.
struct Occupancy {
    int start_hour = 8; ///< in [0, 24)
    int end_hour = 18;  ///< in (start_hour, 24]
};

/// \brief Which hours of a year of \p hours records (8 760 or 8 784, hour i being EPW hour
///        i mod 24 + 1) are occupied.
/// \throws ConfigError for hours outside [0, 24] or an empty period.
std::vector<bool> occupied_hours(std::size_t hours, const Occupancy& occupancy);

/// \brief The thresholds of the metrics (lx, hours, fractions); the defaults are LM-83's and
///        the usual UDI bounds.
struct MetricThresholds {
    double daylight_autonomy_lx = 300;    ///< DA counts hours with E ≥ this
    double udi_lower_lx = 100;            ///< UDI fell short: E < this
    double udi_upper_lx = 3000;           ///< UDI exceeded: E > this
    double sda_fraction = 0.5;            ///< sDA counts sensors with DA ≥ this
    double ase_lx = 1000;                 ///< ASE counts hours of direct sun > this
    int ase_hours = 250;                  ///< ASE counts sensors with more such hours than this
    double blinds_sensor_fraction = 0.02; ///< blinds close when more sensors than this see ASE sun
};

/// \brief The metrics of one sensor over the occupied hours; fractions in [0, 1].
struct SensorMetrics {
    double daylight_autonomy = 0;            ///< hours with E ≥ DA threshold / occupied hours
    double continuous_daylight_autonomy = 0; ///< mean of min(1, E / DA threshold)
    double udi_fell_short = 0;               ///< hours with E < lower bound / occupied hours
    double udi_useful = 0;                   ///< lower ≤ E ≤ upper
    double udi_exceeded = 0;                 ///< E > upper
    int sun_hours =
        0; ///< occupied hours whose direct-sun illuminance is > 0 (the sensor sees the sun)
    int ase_hours = 0; ///< occupied hours whose direct-sun illuminance is > the ASE threshold
};

/// \brief The metrics of a grid of sensors.
struct GridMetrics {
    double spatial_daylight_autonomy = 0; ///< fraction of sensors with DA ≥ sda_fraction
    double annual_sunlight_exposure = 0;  ///< fraction of sensors with ase_hours > ase_hours
    int occupied_hours = 0;
};

/// \brief Each sensor's metrics from \p illuminance_lx (sensors × hours, every light) and
///        \p direct_sun_lx (sensors × hours, the sun's direct light only: no sky, no
///        reflections, as LM-83's ASE wants it), over the hours \p occupied marks.
/// \throws InternalError for matrices or a mask of different sizes; ConfigError for bad
///         thresholds or no occupied hour.
std::vector<SensorMetrics> sensor_metrics(const Eigen::MatrixXf& illuminance_lx,
                                          const Eigen::MatrixXf& direct_sun_lx,
                                          const std::vector<bool>& occupied,
                                          const MetricThresholds& thresholds = {});

/// \brief sDA and ASE of the sensors \p sensors (one grid).
GridMetrics grid_metrics(std::span<const SensorMetrics> sensors, const std::vector<bool>& occupied,
                         const MetricThresholds& thresholds = {});

/// \brief LM-83's blinds rule for one group of windows: the hours in which more than
///        blinds_sensor_fraction of the sensors receive direct sun above the ASE threshold
///        (\p direct_sun_lx, sensors × hours); in those hours the shaded state's illuminance
///        counts for sDA.
std::vector<bool> blinds_closed(const Eigen::MatrixXf& direct_sun_lx,
                                const MetricThresholds& thresholds = {});

} // namespace penumbra::annual
