// `penumbra annual`: coefficients once, then a year as matrix products (app/annual.h).

#include "app/annual.h"

#include <chrono>

#include "annual_outputs.h"
#include "core/error.h"
#include "memory_checks.h"

#include "mesher/mesher.h"
#include "raytrace/raytrace.h"

namespace penumbra::app {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The hours whose sun is up (it has normal illuminance).
std::vector<std::size_t> sun_hours(const annual::SkyMatrix& matrix) {
    std::vector<std::size_t> out;
    for (std::size_t h = 0; h < matrix.suns.size(); ++h)
        if (matrix.suns[h].normal_lx > 0)
            out.push_back(h);
    return out;
}

std::vector<annual::GridMetrics> grid_metrics_of(const Scene& scene, const AnnualResult& r,
                                                 const annual::MetricThresholds& thresholds) {
    std::vector<annual::GridMetrics> out;
    for (const SensorGrid& grid : scene.grids) {
        std::vector<annual::SensorMetrics> mine;
        for (const auto& s : grid.sensors)
            if (s)
                mine.push_back(r.sensors[*s]);
        out.push_back(annual::grid_metrics(mine, r.occupied, thresholds));
    }
    return out;
}

} // namespace

Eigen::MatrixXf direct_sun_lx(const annual::SkyMatrix& matrix, const Eigen::MatrixXf& sun_direct) {
    Eigen::MatrixXf out = sun_direct;
    for (Eigen::Index h = 0; h < out.cols(); ++h)
        out.col(h) *= float(matrix.suns[std::size_t(h)].normal_lx);
    return out;
}

solver::PatchBinning patch_binning(const annual::SkyPatches& patches) {
    return {patches.size(), [&patches](const Vec3& dir, double weight, std::vector<double>& sums) {
                const annual::PatchWeights w = patches.interpolate(dir);
                for (int k = 0; k < w.count; ++k)
                    sums[w.patch[std::size_t(k)]] += weight * w.weight[std::size_t(k)];
            }};
}

SunBins bin_suns(const annual::SkyMatrix& matrix, const annual::SkyPatches& bins) {
    SunBins out;
    out.bin.resize(matrix.suns.size());
    std::vector<Vec3> sum(bins.size(), Vec3(0, 0, 0));
    std::vector<std::optional<std::size_t>> index(bins.size());
    for (std::size_t h : sun_hours(matrix)) // in hour order: the same bins on every run
        sum[bins.find(matrix.suns[h].direction)] += matrix.suns[h].direction;
    for (std::size_t p = 0; p < bins.size(); ++p)
        if (length(sum[p]) > 0) {
            index[p] = out.directions.size();
            out.directions.push_back(normalize(sum[p]));
        }
    for (std::size_t h : sun_hours(matrix))
        out.bin[h] = index[bins.find(matrix.suns[h].direction)];
    return out;
}

Eigen::MatrixXf hourly_illuminance_lx(const solver::DaylightCoefficients& coefficients,
                                      const annual::SkyMatrix& matrix, const SunBins& suns,
                                      const Eigen::MatrixXf& sun_direct) {
    const Eigen::MatrixXf total = coefficients.direct + coefficients.indirect;
    Eigen::MatrixXf lx = total * matrix.radiance * float(k_luminous_efficacy_lm_per_w);
    for (std::size_t h = 0; h < suns.bin.size(); ++h)
        if (suns.bin[h])
            lx.col(Eigen::Index(h)) += coefficients.sun_indirect.col(Eigen::Index(*suns.bin[h])) *
                                       float(matrix.suns[h].normal_lx);
    return lx + direct_sun_lx(matrix, sun_direct);
}

AnnualResult run_annual(const Scene& scene, const AnnualOptions& options, const Context& ctx) {
    if (scene.sensors.empty())
        throw InputError(scene.file, "sensors",
                         "`penumbra annual` needs sensors or grids: it computes their hourly "
                         "illuminance");
    AnnualResult r;
    r.weather = annual::read_epw(options.weather_file);
    const Scene lit = solver::coefficient_scene(scene); // the weather brings sky and sun
    const annual::SkyPatches patches(options.subdivision, lit.sky->compass);
    r.patches = patches.size();
    check_hourly_memory(scene.sensors.size(), patches.size(), r.weather.hours.size(), ctx);
    const auto ts = std::chrono::steady_clock::now();
    const annual::SkyMatrix matrix = annual::sky_matrix(r.weather, patches, options.sky, ctx);
    const double sky_seconds = seconds_since(ts);
    const SunBins suns =
        bin_suns(matrix, annual::SkyPatches(options.sun_subdivision, patches.compass()));
    r.sun_bins = suns.directions.size();
    const double diameter =
        scene.sun ? scene.sun->angular_diameter_deg : Sun{}.angular_diameter_deg;
    const auto t0 = std::chrono::steady_clock::now();
    const RadiosityMesh mesh = mesher::build_mesh(lit, ctx);
    check_coefficient_memory(mesh.element_count(), scene.sensors.size(), patches.size(),
                             suns.directions.size(), ctx);
    const raytrace::EmbreeScene embree(mesh);
    const solver::PatchBinning binning = patch_binning(patches);
    r.coefficients =
        solver::daylight_coefficients(lit, mesh, embree, binning, suns.directions, diameter, ctx);
    r.coefficient_seconds = seconds_since(t0);
    const auto t1 = std::chrono::steady_clock::now();
    const std::vector<std::size_t> up = sun_hours(matrix);
    std::vector<Vec3> directions;
    for (std::size_t h : up)
        directions.push_back(matrix.suns[h].direction);
    const Eigen::MatrixXf up_direct =
        solver::sun_direct_irradiance(lit, mesh, embree, directions, diameter, ctx);
    Eigen::MatrixXf sun_direct =
        Eigen::MatrixXf::Zero(Eigen::Index(scene.sensors.size()), matrix.radiance.cols());
    for (std::size_t k = 0; k < up.size(); ++k)
        sun_direct.col(Eigen::Index(up[k])) = up_direct.col(Eigen::Index(k));
    r.illuminance_lx = hourly_illuminance_lx(r.coefficients, matrix, suns, sun_direct);
    r.direct_sun_lx = direct_sun_lx(matrix, sun_direct);
    r.occupied = annual::occupied_hours(r.weather.hours.size(), options.occupancy);
    r.sensors =
        annual::sensor_metrics(r.illuminance_lx, r.direct_sun_lx, r.occupied, options.thresholds);
    r.grids = grid_metrics_of(scene, r, options.thresholds);
    r.hours_seconds = sky_seconds + seconds_since(t1);
    return r;
}

void check_annual_outputs(const Scene& scene, const AnnualWriteOptions& write) {
    heat_map_sensor(scene, write.heat_map_sensor);
}

void write_annual(const Scene& scene, const AnnualOptions& options, const AnnualResult& result,
                  const AnnualWriteOptions& write, const Context& ctx) {
    AnnualResults out;
    out.scene = &scene;
    out.weather = &result.weather;
    out.occupied = result.occupied;
    out.thresholds = options.thresholds;
    out.occupancy = options.occupancy;
    out.illuminance_lx = result.illuminance_lx;
    out.direct_sun_lx = result.direct_sun_lx;
    out.sensors = result.sensors;
    out.grids = result.grids;
    const Location& site = result.weather.site.location;
    out.run = {
        {"weather",
         {{"file", result.weather.file},
          {"city", result.weather.site.city},
          {"latitude_deg", site.latitude_deg},
          {"longitude_deg", site.longitude_deg},
          {"time_zone_h", site.time_zone_h}}},
        {"sky_patches", {{"subdivision", options.subdivision}, {"count", result.patches}}},
        {"sun_bins", {{"subdivision", options.sun_subdivision}, {"count", result.sun_bins}}},
        {"coefficients",
         {{"nodes", result.coefficients.nodes}, {"links", result.coefficients.links}}},
        {"seconds",
         {{"coefficients", result.coefficient_seconds}, {"hours", result.hours_seconds}}},
    };
    write_annual_outputs(out, {write.directory, write.hourly, write.heat_map_sensor}, ctx);
}

} // namespace penumbra::app
