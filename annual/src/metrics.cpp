// The metrics as counts over the occupied hours, each with its edge written once: DA and the
// useful band of UDI include their thresholds, UDI's exceeded band and ASE's hours and sensors
// are strictly above theirs (docs/annual.md).

#include "annual/metrics.h"

#include <algorithm>
#include <string>

#include <fmt/format.h>

#include "core/error.h"

namespace penumbra::annual {

namespace {

void check_thresholds(const MetricThresholds& t) {
    const bool ok = t.daylight_autonomy_lx > 0 && t.udi_lower_lx >= 0 &&
                    t.udi_upper_lx >= t.udi_lower_lx && t.sda_fraction >= 0 &&
                    t.sda_fraction <= 1 && t.ase_lx >= 0 && t.ase_hours >= 0 &&
                    t.blinds_sensor_fraction >= 0 && t.blinds_sensor_fraction <= 1;
    if (!ok)
        throw ConfigError("metric thresholds: need DA > 0 lx, 0 <= UDI lower <= upper, sDA and "
                          "blinds fractions in [0, 1], ASE >= 0 lx and >= 0 hours");
}

int count_occupied(const std::vector<bool>& occupied) {
    const auto n = std::count(occupied.begin(), occupied.end(), true);
    if (n == 0)
        throw ConfigError("the occupancy schedule has no occupied hour");
    return int(n);
}

/// One sensor's sums over the occupied hours (a row of each matrix).
SensorMetrics one_sensor(const Eigen::MatrixXf& e, const Eigen::MatrixXf& sun, Eigen::Index s,
                         const std::vector<bool>& occupied, int hours, const MetricThresholds& t) {
    int da = 0, short_of = 0, exceeded = 0;
    double continuous = 0;
    SensorMetrics m;
    for (Eigen::Index h = 0; h < e.cols(); ++h) {
        if (!occupied[std::size_t(h)])
            continue;
        const double lx = e(s, h), sun_lx = sun(s, h);
        da += lx >= t.daylight_autonomy_lx;
        continuous += std::min(1.0, lx / t.daylight_autonomy_lx);
        short_of += lx < t.udi_lower_lx;
        exceeded += lx > t.udi_upper_lx;
        m.sun_hours += sun_lx > 0;
        m.ase_hours += sun_lx > t.ase_lx;
    }
    m.daylight_autonomy = double(da) / hours;
    m.continuous_daylight_autonomy = continuous / hours;
    m.udi_fell_short = double(short_of) / hours;
    m.udi_exceeded = double(exceeded) / hours;
    m.udi_useful = double(hours - short_of - exceeded) / hours;
    return m;
}

} // namespace

std::vector<bool> occupied_hours(std::size_t hours, const Occupancy& occupancy) {
    const int start = occupancy.start_hour, end = occupancy.end_hour;
    if (start < 0 || end > 24 || start >= end)
        throw ConfigError(
            fmt::format("occupancy {}:00–{}:00: need 0 <= start < end <= 24", start, end));
    std::vector<bool> occupied(hours);
    for (std::size_t i = 0; i < hours; ++i) {
        const int epw_hour = int(i % 24) + 1;
        occupied[i] = start < epw_hour && epw_hour <= end;
    }
    return occupied;
}

std::vector<SensorMetrics> sensor_metrics(const Eigen::MatrixXf& illuminance_lx,
                                          const Eigen::MatrixXf& direct_sun_lx,
                                          const std::vector<bool>& occupied,
                                          const MetricThresholds& thresholds) {
    if (illuminance_lx.rows() != direct_sun_lx.rows() ||
        illuminance_lx.cols() != direct_sun_lx.cols() ||
        std::size_t(illuminance_lx.cols()) != occupied.size())
        throw InternalError(fmt::format(
            "sensor_metrics: illuminance {} × {}, direct sun {} × {}, {} occupancy hours",
            illuminance_lx.rows(), illuminance_lx.cols(), direct_sun_lx.rows(),
            direct_sun_lx.cols(), occupied.size()));
    check_thresholds(thresholds);
    const int hours = count_occupied(occupied);
    std::vector<SensorMetrics> metrics;
    for (Eigen::Index s = 0; s < illuminance_lx.rows(); ++s)
        metrics.push_back(
            one_sensor(illuminance_lx, direct_sun_lx, s, occupied, hours, thresholds));
    return metrics;
}

GridMetrics grid_metrics(std::span<const SensorMetrics> sensors, const std::vector<bool>& occupied,
                         const MetricThresholds& thresholds) {
    check_thresholds(thresholds);
    GridMetrics grid;
    grid.occupied_hours = count_occupied(occupied);
    if (sensors.empty())
        return grid;
    int autonomous = 0, exposed = 0;
    for (const SensorMetrics& s : sensors) {
        // DA × hours is the count of hours ≥ the threshold: compare counts, not rounded ratios.
        autonomous += s.daylight_autonomy * grid.occupied_hours >=
                      thresholds.sda_fraction * grid.occupied_hours - 1e-9;
        exposed += s.ase_hours > thresholds.ase_hours;
    }
    grid.spatial_daylight_autonomy = double(autonomous) / double(sensors.size());
    grid.annual_sunlight_exposure = double(exposed) / double(sensors.size());
    return grid;
}

std::vector<bool> blinds_closed(const Eigen::MatrixXf& direct_sun_lx,
                                const MetricThresholds& thresholds) {
    check_thresholds(thresholds);
    std::vector<bool> closed(std::size_t(direct_sun_lx.cols()));
    const double sensors = double(direct_sun_lx.rows());
    for (Eigen::Index h = 0; h < direct_sun_lx.cols(); ++h) {
        const auto sunny = (direct_sun_lx.col(h).array() > float(thresholds.ase_lx)).count();
        closed[std::size_t(h)] = double(sunny) > thresholds.blinds_sensor_fraction * sensors;
    }
    return closed;
}

} // namespace penumbra::annual
