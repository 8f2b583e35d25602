// `penumbra annual`: coefficients once, then a year as matrix products (app/annual.h).

#include "app/annual.h"

#include <chrono>

#include "annual_mesh.h"
#include "annual_outputs.h"
#include "core/error.h"
#include "memory_checks.h"

#include "mesher/mesher.h"
#include "raytrace/raytrace.h"

namespace penumbra::app {

namespace {

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

/// Appends the time since the last lap to a result's stages.
class Stopwatch {
public:
    explicit Stopwatch(std::vector<std::pair<std::string, double>>& stages) : stages_(stages) {}
    void lap(const std::string& stage) {
        const auto now = std::chrono::steady_clock::now();
        stages_.emplace_back(stage, std::chrono::duration<double>(now - last_).count());
        last_ = now;
    }

private:
    std::vector<std::pair<std::string, double>>& stages_;
    std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

void check_blinds(const Scene& scene, const AnnualOptions& options) {
    if (options.blinds && scene.annual.blinds.empty())
        throw InputError(scene.file, "annual.blinds",
                         "--blinds needs the shaded state: give 'annual.blinds' (the materials "
                         "that change when the blinds close)");
}

double sun_diameter_deg(const Scene& scene) {
    return scene.sun ? scene.sun->angular_diameter_deg : Sun{}.angular_diameter_deg;
}

/// \p lit with the blinds' materials in place of the scene's of the same name.
Scene shaded_scene(const Scene& lit) {
    Scene shaded = lit;
    for (const Material& blind : lit.annual.blinds)
        for (Material& m : shaded.materials)
            if (m.name == blind.name)
                m = blind;
    return shaded;
}

/// The year's skies and suns.
struct YearSky {
    const annual::SkyMatrix& matrix;
    const SunBins& suns;
    double sun_diameter_deg = 0;
};

/// One state of the scene's materials (open, or with the blinds closed) through the year.
struct StateYear {
    solver::DaylightCoefficients coefficients;
    Eigen::MatrixXf illuminance_lx, direct_sun_lx; ///< sensors × hours
};

/// The sun's direct light at the sensors in every hour (unit normal irradiance).
Eigen::MatrixXf year_sun_direct(const Scene& lit, const RadiosityMesh& mesh,
                                const VisibilityQuery& visibility, const YearSky& year,
                                const Context& ctx) {
    const std::vector<std::size_t> up = sun_hours(year.matrix);
    std::vector<Vec3> directions;
    for (std::size_t h : up)
        directions.push_back(year.matrix.suns[h].direction);
    const Eigen::MatrixXf up_direct = solver::sun_direct_irradiance(
        lit, mesh, visibility, directions, year.sun_diameter_deg, ctx);
    Eigen::MatrixXf out =
        Eigen::MatrixXf::Zero(Eigen::Index(lit.sensors.size()), year.matrix.radiance.cols());
    for (std::size_t k = 0; k < up.size(); ++k)
        out.col(Eigen::Index(up[k])) = up_direct.col(Eigen::Index(k));
    return out;
}

/// Meshes \p lit, computes its coefficients and the year at its sensors; stages named with
/// \p prefix.
StateYear state_year(const Scene& lit, const annual::SkyPatches& patches, const YearSky& year,
                     solver::CoefficientTargets targets, const std::string& prefix,
                     Stopwatch& clock, const Context& ctx) {
    const RadiosityMesh mesh = mesher::build_mesh(lit, ctx);
    const std::size_t elements =
        targets == solver::CoefficientTargets::with_elements ? mesh.element_count() : 0;
    check_coefficient_memory(mesh.element_count(), lit.sensors.size() + elements, patches.size(),
                             year.suns.directions.size(), ctx);
    const raytrace::EmbreeScene embree(mesh);
    clock.lap(prefix + "mesh");
    StateYear s;
    s.coefficients =
        solver::daylight_coefficients(lit, mesh, embree, patch_binning(patches),
                                      year.suns.directions, year.sun_diameter_deg, ctx, targets);
    clock.lap(prefix + "coefficients");
    const Eigen::MatrixXf sun_direct = year_sun_direct(lit, mesh, embree, year, ctx);
    clock.lap(prefix + "direct sun");
    s.illuminance_lx = hourly_illuminance_lx(s.coefficients, year.matrix, year.suns, sun_direct);
    s.direct_sun_lx = direct_sun_lx(year.matrix, sun_direct);
    clock.lap(prefix + "hours");
    return s;
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

std::vector<BlindsGroup> blinds_groups(const Scene& scene) {
    std::vector<BlindsGroup> out;
    std::vector<bool> in_grid(scene.sensors.size(), false);
    for (const SensorGrid& grid : scene.grids) {
        BlindsGroup group{grid.name, {}, {}};
        for (const auto& s : grid.sensors)
            if (s) {
                group.sensors.push_back(*s);
                in_grid[*s] = true;
            }
        out.push_back(std::move(group));
    }
    BlindsGroup rest;
    for (std::size_t s = 0; s < scene.sensors.size(); ++s)
        if (!in_grid[s])
            rest.sensors.push_back(std::uint32_t(s));
    if (!rest.sensors.empty())
        out.push_back(std::move(rest));
    return out;
}

void apply_blinds(std::vector<BlindsGroup>& groups, const Eigen::MatrixXf& direct_sun_lx,
                  const Eigen::MatrixXf& shaded_lx, const annual::MetricThresholds& thresholds,
                  Eigen::MatrixXf& illuminance_lx) {
    for (BlindsGroup& group : groups) {
        Eigen::MatrixXf sun(Eigen::Index(group.sensors.size()), direct_sun_lx.cols());
        for (std::size_t k = 0; k < group.sensors.size(); ++k)
            sun.row(Eigen::Index(k)) = direct_sun_lx.row(Eigen::Index(group.sensors[k]));
        group.closed = annual::blinds_closed(sun, thresholds);
        for (std::size_t h = 0; h < group.closed.size(); ++h)
            if (group.closed[h])
                for (std::uint32_t s : group.sensors)
                    illuminance_lx(Eigen::Index(s), Eigen::Index(h)) =
                        shaded_lx(Eigen::Index(s), Eigen::Index(h));
    }
}

void check_annual_run(const Scene& scene, const AnnualOptions& options,
                      const AnnualWriteOptions& write) {
    heat_map_sensor(scene, write.heat_map_sensor);
    check_blinds(scene, options);
}

AnnualResult run_annual(const Scene& scene, const AnnualOptions& options, const Context& ctx) {
    if (scene.sensors.empty())
        throw InputError(scene.file, "sensors",
                         "`penumbra annual` needs sensors or grids: it computes their hourly "
                         "illuminance");
    check_blinds(scene, options);
    AnnualResult r;
    r.options = options;
    Stopwatch clock(r.seconds);
    r.weather = annual::read_epw(options.weather_file);
    const Scene lit = solver::coefficient_scene(scene); // the weather brings sky and sun
    const annual::SkyPatches patches(options.subdivision, lit.sky->compass);
    r.patches = patches.size();
    check_hourly_memory(scene.sensors.size(), patches.size(), r.weather.hours.size(), ctx);
    const annual::SkyMatrix matrix = annual::sky_matrix(r.weather, patches, options.sky, ctx);
    const SunBins suns =
        bin_suns(matrix, annual::SkyPatches(options.sun_subdivision, patches.compass()));
    r.sun_bins = suns.directions.size();
    clock.lap("weather and sky vectors");
    const YearSky year{matrix, suns, sun_diameter_deg(scene)};
    const auto targets = options.mesh ? solver::CoefficientTargets::with_elements
                                      : solver::CoefficientTargets::sensors;
    StateYear open = state_year(lit, patches, year, targets, "", clock, ctx);
    r.coefficients = std::move(open.coefficients);
    r.illuminance_lx = std::move(open.illuminance_lx);
    r.direct_sun_lx = std::move(open.direct_sun_lx);
    if (options.blinds) {
        const StateYear shaded =
            state_year(shaded_scene(lit), patches, year, solver::CoefficientTargets::sensors,
                       "shaded ", clock, ctx);
        r.blinds = blinds_groups(scene);
        apply_blinds(r.blinds, r.direct_sun_lx, shaded.illuminance_lx, options.thresholds,
                     r.illuminance_lx);
    }
    r.occupied = annual::occupied_hours(r.weather.hours.size(), options.occupancy);
    r.sensors =
        annual::sensor_metrics(r.illuminance_lx, r.direct_sun_lx, r.occupied, options.thresholds);
    r.grids = grid_metrics_of(scene, r, options.thresholds);
    clock.lap("metrics");
    if (options.mesh) {
        r.mesh = mesh_metrics(*r.coefficients.elements, matrix, suns, r.occupied,
                              options.thresholds, ctx);
        r.coefficients.elements.reset(); // elements × patches floats, no longer needed
        clock.lap("mesh metrics");
    }
    return r;
}

} // namespace penumbra::app
