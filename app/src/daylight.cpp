#include "daylight.h"

#include <algorithm>
#include <numeric>

#include <fmt/format.h>

namespace penumbra::app {

std::optional<double> daylight_reference_lx(const Scene& scene) {
    if (!scene.sky)
        return std::nullopt;
    const double lx = scene.sky->horizontal_illuminance_lx();
    return lx > 0 ? std::optional(lx) : std::nullopt;
}

GridStats stats_of(const std::vector<double>& values) {
    GridStats s;
    s.points = values.size();
    s.min = *std::min_element(values.begin(), values.end());
    s.max = *std::max_element(values.begin(), values.end());
    s.avg = std::accumulate(values.begin(), values.end(), 0.0) / double(values.size());
    s.uniformity = s.avg > 0 ? s.min / s.avg : 0;
    return s;
}

std::vector<double> grid_illuminance_lx(const SensorGrid& grid,
                                        const std::vector<SensorReading>& readings) {
    std::vector<double> lx;
    for (const auto& sensor : grid.sensors)
        if (sensor)
            lx.push_back(readings[*sensor].illuminance_total_lx);
    return lx;
}

PlanQuantity plan_quantity(std::optional<double> daylight_reference_lx) {
    if (daylight_reference_lx)
        return {"daylight factor", "%", 100 / *daylight_reference_lx};
    return {"illuminance", "lx", 1};
}

std::string grids_csv(const Scene& scene, const BakeResult& result) {
    const std::optional<double> daylight_reference_lx = app::daylight_reference_lx(scene);
    std::string out = "grid,kind,points,illuminance_avg_lx,illuminance_min_lx,"
                      "illuminance_max_lx,uniformity_min_avg";
    out += daylight_reference_lx ? ",daylight_factor_avg_pct,daylight_factor_min_pct\n" : "\n";
    for (const SensorGrid& grid : scene.grids) {
        const GridStats s = stats_of(grid_illuminance_lx(grid, result.sensors));
        out += fmt::format("{},{},{},{:.6g},{:.6g},{:.6g},{:.6g}", grid.name, enum_name(grid.kind),
                           s.points, s.avg, s.min, s.max, s.uniformity);
        if (daylight_reference_lx) {
            const double per_lx = 100 / *daylight_reference_lx;
            out += fmt::format(",{:.6g},{:.6g}", s.avg * per_lx, s.min * per_lx);
        }
        out += "\n";
    }
    return out;
}

} // namespace penumbra::app
