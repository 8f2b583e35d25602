// summary.json of `penumbra annual`: the run's settings, per grid sDA, ASE and its blinds, the
// weather, the coefficients' system and the stages' times (README.md, docs/annual.md).

#include "annual_outputs.h"

#include <algorithm>

#include <nlohmann/json.hpp>

namespace penumbra::app {

namespace {

nlohmann::ordered_json thresholds_json(const annual::MetricThresholds& t) {
    return {{"daylight_autonomy_lx", t.daylight_autonomy_lx},
            {"udi_lower_lx", t.udi_lower_lx},
            {"udi_upper_lx", t.udi_upper_lx},
            {"sda_pct", 100 * t.sda_fraction},
            {"ase_lx", t.ase_lx},
            {"ase_hours", t.ase_hours},
            {"blinds_sensor_pct", 100 * t.blinds_sensor_fraction}};
}

int count_true(const std::vector<bool>& flags) {
    return int(std::count(flags.begin(), flags.end(), true));
}

/// Hours set in both \p a and \p b.
int count_both(const std::vector<bool>& a, const std::vector<bool>& b) {
    int n = 0;
    for (std::size_t i = 0; i < a.size() && i < b.size(); ++i)
        n += a[i] && b[i] ? 1 : 0;
    return n;
}

nlohmann::ordered_json blinds_json(const AnnualResult& r) {
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (const BlindsGroup& group : r.blinds)
        out.push_back({{"group", group.name.empty() ? "(sensors of no grid)" : group.name},
                       {"sensors", group.sensors.size()},
                       {"closed_hours", count_true(group.closed)},
                       {"closed_occupied_hours", count_both(group.closed, r.occupied)}});
    return out;
}

nlohmann::ordered_json grids_json(const Scene& scene, const AnnualResult& r) {
    nlohmann::ordered_json grids = nlohmann::ordered_json::array();
    for (std::size_t g = 0; g < scene.grids.size(); ++g) {
        const SensorGrid& grid = scene.grids[g];
        grids.push_back({{"name", grid.name},
                         {"points", std::count_if(grid.sensors.begin(), grid.sensors.end(),
                                                  [](const auto& s) { return s.has_value(); })},
                         {"sda_pct", 100 * r.grids[g].spatial_daylight_autonomy},
                         {"ase_pct", 100 * r.grids[g].annual_sunlight_exposure}});
    }
    return grids;
}

} // namespace

std::string annual_summary_json(const Scene& scene, const AnnualResult& r) {
    nlohmann::ordered_json j;
    j["sensors"] = scene.sensors.size();
    j["hours"] = r.weather.hours.size();
    j["occupied_hours"] = count_true(r.occupied);
    j["occupancy"] = {{"start_hour", r.options.occupancy.start_hour},
                      {"end_hour", r.options.occupancy.end_hour}};
    j["thresholds"] = thresholds_json(r.options.thresholds);
    j["grids"] = grids_json(scene, r);
    if (r.options.blinds)
        j["blinds"] = blinds_json(r);
    const Location& site = r.weather.site.location;
    j["weather"] = {{"file", r.weather.file},
                    {"city", r.weather.site.city},
                    {"latitude_deg", site.latitude_deg},
                    {"longitude_deg", site.longitude_deg},
                    {"time_zone_h", site.time_zone_h}};
    j["sky_patches"] = {{"subdivision", r.options.subdivision}, {"count", r.patches}};
    j["sun_bins"] = {{"subdivision", r.options.sun_subdivision}, {"count", r.sun_bins}};
    j["coefficients"] = {{"nodes", r.coefficients.nodes}, {"links", r.coefficients.links}};
    if (r.mesh)
        j["mesh"] = {{"file", "annual_mesh.vtu"}, {"elements", r.mesh->mesh.element_count()}};
    nlohmann::ordered_json seconds = nlohmann::ordered_json::object();
    for (const auto& [stage, s] : r.seconds)
        seconds[stage] = s;
    j["seconds"] = seconds;
    return j.dump(2) + "\n";
}

} // namespace penumbra::app
