// The outputs of `penumbra annual`: one table of metrics (annual_metrics()) drives the columns
// of annual.csv, the plans and the arrays of the .vtp, so that the three always agree.

#include "annual_outputs.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <filesystem>
#include <span>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/files.h"
#include "viewer/vtk_output.h"

#include "colour_scale.h"
#include "daylight.h"
#include "grid_plan.h"
#include "heat_map.h"

namespace penumbra::app {

namespace fs = std::filesystem;

namespace {

using annual::MetricThresholds;
using annual::SensorMetrics;
using Statistic = AnnualMetric::GridStatistic;

std::vector<AnnualMetric> make_annual_metrics() {
    return {
        {"daylight_autonomy_pct", "da", "%",
         [](const MetricThresholds& t) {
             return fmt::format("DA {:g} lx", t.daylight_autonomy_lx);
         },
         [](const SensorMetrics& m) { return 100 * m.daylight_autonomy; },
         Statistic::spatial_daylight_autonomy},
        {"continuous_daylight_autonomy_pct", "cda", "%",
         [](const MetricThresholds& t) {
             return fmt::format("cDA {:g} lx", t.daylight_autonomy_lx);
         },
         [](const SensorMetrics& m) { return 100 * m.continuous_daylight_autonomy; }},
        {"udi_fell_short_pct", "udi_fell_short", "%",
         [](const MetricThresholds& t) { return fmt::format("UDI < {:g} lx", t.udi_lower_lx); },
         [](const SensorMetrics& m) { return 100 * m.udi_fell_short; }},
        {"udi_useful_pct", "udi_useful", "%",
         [](const MetricThresholds& t) {
             return fmt::format("UDI {:g}-{:g} lx", t.udi_lower_lx, t.udi_upper_lx);
         },
         [](const SensorMetrics& m) { return 100 * m.udi_useful; }},
        {"udi_exceeded_pct", "udi_exceeded", "%",
         [](const MetricThresholds& t) { return fmt::format("UDI > {:g} lx", t.udi_upper_lx); },
         [](const SensorMetrics& m) { return 100 * m.udi_exceeded; }},
        {"sun_hours", "sun_hours", "h",
         [](const MetricThresholds&) { return std::string("hours of direct sun"); },
         [](const SensorMetrics& m) { return double(m.sun_hours); }},
        {"ase_hours", "ase_hours", "h",
         [](const MetricThresholds& t) { return fmt::format("hours of sun > {:g} lx", t.ase_lx); },
         [](const SensorMetrics& m) { return double(m.ase_hours); },
         Statistic::annual_sunlight_exposure},
    };
}

/// Letters, digits, '_', '-' and '.' as they are; anything else (a grid point's ':') as '_'.
std::string file_safe(const std::string& name) {
    std::string out = name;
    for (char& c : out)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-' && c != '.')
            c = '_';
    return out;
}

std::string plan_file(const SensorGrid& grid, const AnnualMetric& metric) {
    return fmt::format("annual_{}_{}.png", grid.name, metric.file);
}

void check_sizes(const Scene& scene, const AnnualResult& r) {
    if (r.mesh && (r.mesh->elements.size() != r.mesh->mesh.element_count() ||
                   r.mesh->mean_illuminance_lx.size() != r.mesh->mesh.element_count()))
        throw InternalError("write_annual: the mesh's metrics do not fit its elements");
    const auto sensors = Eigen::Index(scene.sensors.size());
    const auto hours = Eigen::Index(r.weather.hours.size());
    const auto fits = [&](const Eigen::MatrixXf& m) {
        return m.rows() == sensors && m.cols() == hours;
    };
    if (!fits(r.illuminance_lx) || !fits(r.direct_sun_lx) ||
        r.sensors.size() != scene.sensors.size() || r.grids.size() != scene.grids.size() ||
        r.occupied.size() != r.weather.hours.size())
        throw InternalError(fmt::format(
            "write_annual_outputs: {} sensors, {} grids, {} hours but matrices of {} × {} and "
            "{} × {}, {} sensor and {} grid metrics, {} occupancy flags",
            sensors, scene.grids.size(), hours, r.illuminance_lx.rows(), r.illuminance_lx.cols(),
            r.direct_sun_lx.rows(), r.direct_sun_lx.cols(), r.sensors.size(), r.grids.size(),
            r.occupied.size()));
}

/// \p metric at the grid's present points, in lattice order.
std::vector<double> grid_values(const AnnualResult& r, const SensorGrid& grid,
                                const AnnualMetric& metric) {
    std::vector<double> values;
    for (const auto& sensor : grid.sensors)
        if (sensor)
            values.push_back(metric.value(r.sensors[*sensor]));
    return values;
}

std::string plan_statistics_line(const AnnualMetric& metric, const annual::GridMetrics& grid,
                                 const GridStats& stats) {
    switch (metric.statistic) {
    case Statistic::spatial_daylight_autonomy:
        return fmt::format("sDA {:.1f} %  {}", 100 * grid.spatial_daylight_autonomy,
                           plan_statistics(stats));
    case Statistic::annual_sunlight_exposure:
        return fmt::format("ASE {:.1f} %  {}", 100 * grid.annual_sunlight_exposure,
                           plan_statistics(stats));
    case Statistic::none:
        break;
    }
    return plan_statistics(stats);
}

/// Percentages on 0–100 % so that plans compare; hours from 0 to the grid's maximum.
ColourScale metric_scale(const AnnualMetric& metric, const GridStats& stats) {
    return ColourScale::covering(0, metric.unit == "%" ? 100 : stats.max);
}

void write_grid_files(const Scene& scene, const AnnualResult& r, std::size_t g,
                      const std::string& dir) {
    const SensorGrid& grid = scene.grids[g];
    std::vector<viewer::GridPointArray> arrays;
    for (const AnnualMetric& metric : annual_metrics()) {
        std::vector<double> values = grid_values(r, grid, metric);
        const GridStats stats = stats_of(values);
        const PlanTitle title{fmt::format("{}: {} ({})", grid.name,
                                          metric.heading(r.options.thresholds), metric.unit),
                              plan_statistics_line(metric, r.grids[g], stats)};
        draw_grid_plan(grid, values, title, metric_scale(metric, stats))
            .write_png((fs::path(dir) / plan_file(grid, metric)).string());
        arrays.push_back({std::string(metric.column), std::string(metric.unit), std::move(values)});
    }
    viewer::write_grid_arrays_vtp((fs::path(dir) / ("annual_" + grid.name + ".vtp")).string(),
                                  scene, grid, arrays);
}

void write_heat_map(const Scene& scene, const AnnualResult& r, std::size_t sensor,
                    const std::string& path) {
    const Eigen::VectorXf row = r.illuminance_lx.row(Eigen::Index(sensor));
    const PlanTitle title{
        fmt::format("{}: illuminance (lx) by day and hour", sensor_label(scene, sensor)),
        fmt::format("max {:.0f} lx  DA {:.1f} %  UDI useful {:.1f} %", row.maxCoeff(),
                    100 * r.sensors[sensor].daylight_autonomy, 100 * r.sensors[sensor].udi_useful)};
    draw_heat_map(r.weather, std::span<const float>(row.data(), std::size_t(row.size())), title)
        .write_png(path);
}

nlohmann::json hourly_description(const Scene& scene, const AnnualResult& r) {
    nlohmann::json j;
    j["file"] = "hourly_illuminance.f32";
    j["type"] = "float32";
    j["byte_order"] = "little-endian";
    j["shape"] = {r.illuminance_lx.rows(), r.illuminance_lx.cols()};
    j["order"] = "row-major: all hours of sensor 0, then of sensor 1, ...";
    j["unit"] = "lx";
    j["quantity"] = "illuminance at each sensor, sky and sun, direct and reflected";
    nlohmann::json names = nlohmann::json::array();
    for (std::size_t i = 0; i < scene.sensors.size(); ++i)
        names.push_back(sensor_label(scene, i));
    j["sensors"] = names;
    j["hour_convention"] = "EPW: hour h (1-24) is the hour ending at h, local standard time";
    nlohmann::json hours = nlohmann::json::array();
    for (const annual::WeatherHour& h : r.weather.hours)
        hours.push_back({h.month, h.day, h.hour});
    j["hours"] = hours;
    j["hours_columns"] = {"month", "day", "hour"};
    return j;
}

void write_hourly(const Scene& scene, const AnnualResult& r, const std::string& dir) {
    static_assert(std::endian::native == std::endian::little,
                  "hourly_illuminance.f32 is written as the machine's floats: little-endian");
    // Eigen stores column-major (hours of one sensor apart): transpose to sensor-major rows.
    const Eigen::MatrixXf by_sensor = r.illuminance_lx.transpose();
    const std::string path = (fs::path(dir) / "hourly_illuminance.f32").string();
    write_atomically(path, [&](const std::string& temp) {
        FileWriter out(temp, path);
        out.write(by_sensor.data(), std::size_t(by_sensor.size()) * sizeof(float));
        out.close();
    });
    write_text_file((fs::path(dir) / "hourly_illuminance.json").string(),
                    hourly_description(scene, r).dump() + "\n");
}

/// Every metric per element, and the mean illuminance, as cell data on the leaf mesh.
void write_mesh_metrics(const Scene& scene, const MeshMetrics& m, const std::string& path) {
    std::vector<viewer::CellArray> arrays;
    for (const AnnualMetric& metric : annual_metrics()) {
        std::vector<double> values;
        values.reserve(m.elements.size());
        for (const SensorMetrics& e : m.elements)
            values.push_back(metric.value(e));
        arrays.push_back({std::string(metric.column), std::string(metric.unit), std::move(values)});
    }
    arrays.push_back(
        {"mean_illuminance_lx", "lx",
         std::vector<double>(m.mean_illuminance_lx.begin(), m.mean_illuminance_lx.end())});
    viewer::write_cell_arrays_vtu(path, scene, m.mesh, arrays);
}

/// Whether \p name is a file this module writes per grid or sensor: annual_*.png,
/// annual_*.vtp or heat_map_*.png.
bool annual_file_name(const std::string& name) {
    const std::string extension = fs::path(name).extension().string();
    return (name.starts_with("annual_") && (extension == ".png" || extension == ".vtp")) ||
           (name.starts_with("heat_map_") && extension == ".png");
}

/// Removes the files an earlier run left that this one does not write (other grids, another
/// heat-map sensor, the hourly files without --hourly, the mesh without --mesh), so that a
/// folder never mixes two runs.
void remove_stale_files(const std::string& dir, const std::vector<std::string>& keep, bool hourly,
                        bool mesh) {
    std::error_code ec;
    std::vector<fs::path> stale;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (annual_file_name(name) && it->is_regular_file(ec) &&
            std::find(keep.begin(), keep.end(), name) == keep.end())
            stale.push_back(it->path());
    }
    if (!hourly)
        for (const char* name : {"hourly_illuminance.f32", "hourly_illuminance.json"})
            stale.push_back(fs::path(dir) / name);
    if (!mesh)
        stale.push_back(fs::path(dir) / "annual_mesh.vtu");
    for (const fs::path& path : stale)
        fs::remove(path, ec);
}

} // namespace

const std::vector<AnnualMetric>& annual_metrics() {
    static const std::vector<AnnualMetric> metrics = make_annual_metrics();
    return metrics;
}

std::string sensor_label(const Scene& scene, std::size_t index) {
    const std::string& name = scene.sensors[index].name;
    return name.empty() ? fmt::format("s{}", index) : name;
}

std::optional<std::size_t> heat_map_sensor(const Scene& scene,
                                           const std::optional<std::string>& name) {
    if (name) {
        for (std::size_t i = 0; i < scene.sensors.size(); ++i)
            if (sensor_label(scene, i) == *name)
                return i;
        throw ConfigError(fmt::format("--heat-map: no sensor named '{}' (grid points are named "
                                      "GRID:ROW:COLUMN, as in annual.csv)",
                                      *name));
    }
    if (!scene.grids.empty())
        for (const auto& sensor : scene.grids.front().sensors)
            if (sensor)
                return std::size_t(*sensor);
    return scene.sensors.empty() ? std::nullopt : std::optional<std::size_t>(0);
}

std::string annual_csv(const Scene& scene, const AnnualResult& r) {
    std::string out = "name,x,y,z";
    for (const AnnualMetric& metric : annual_metrics())
        out += fmt::format(",{}", metric.column);
    out += "\n";
    for (std::size_t i = 0; i < scene.sensors.size(); ++i) {
        const Vec3& p = scene.sensors[i].position;
        out += fmt::format("{},{:.6g},{:.6g},{:.6g}", sensor_label(scene, i), p.x, p.y, p.z);
        for (const AnnualMetric& metric : annual_metrics())
            out += fmt::format(",{:.6g}", metric.value(r.sensors[i]));
        out += "\n";
    }
    return out;
}

void write_annual(const Scene& scene, const AnnualResult& r, const AnnualWriteOptions& options,
                  const Context& ctx) {
    check_sizes(scene, r);
    const std::optional<std::size_t> heat_map = heat_map_sensor(scene, options.heat_map_sensor);
    const std::string& dir = options.directory;
    check_output_dir(dir);
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec)
        throw ConfigError(fmt::format("cannot create output folder '{}': {}", dir, ec.message()));
    const auto path = [&](const std::string& name) { return (fs::path(dir) / name).string(); };
    write_text_file(path("annual.csv"), annual_csv(scene, r));
    write_text_file(path("summary.json"), annual_summary_json(scene, r));
    std::vector<std::string> written;
    for (std::size_t g = 0; g < scene.grids.size(); ++g) {
        write_grid_files(scene, r, g, dir);
        for (const AnnualMetric& metric : annual_metrics())
            written.push_back(plan_file(scene.grids[g], metric));
        written.push_back("annual_" + scene.grids[g].name + ".vtp");
    }
    if (heat_map) {
        written.push_back("heat_map_" + file_safe(sensor_label(scene, *heat_map)) + ".png");
        write_heat_map(scene, r, *heat_map, path(written.back()));
    }
    if (options.hourly)
        write_hourly(scene, r, dir);
    if (r.mesh)
        write_mesh_metrics(scene, *r.mesh, path("annual_mesh.vtu"));
    remove_stale_files(dir, written, options.hourly, r.mesh.has_value());
    ctx.info("annual: wrote annual.csv, summary.json and {} pictures and point files to {}",
             written.size(), dir);
}

} // namespace penumbra::app
