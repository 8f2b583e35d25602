// A year of sky vectors: one Perez sky per hour and its patches' means (patch_quadrature.h),
// hours in parallel, each writing its own column.

#include "annual/sky_matrix.h"

#include <string>

#include <fmt/format.h>

#include "core/error.h"
#include "core/parallel.h"
#include "core/rgb.h"

#include "patch_quadrature.h"

namespace penumbra::annual {

namespace {

/// The hour's solar components from the fields \p input names.
SolarComponents components(const Weather& weather, const WeatherHour& h, WeatherInput input) {
    if (input == WeatherInput::irradiance)
        return SolarIrradiance{h.direct_normal_w_m2, h.diffuse_horizontal_w_m2};
    const auto required = [&](const std::optional<double>& value, int field, const char* name) {
        if (!value)
            throw InputError(weather.file, fmt::format("field {} ({})", field, name),
                             "missing (blank or 999900), and the illuminance sky needs it", h.line);
        return *value;
    };
    return SolarIlluminance{
        required(h.direct_normal_lx, 18, "direct normal illuminance"),
        required(h.diffuse_horizontal_lx, 19, "diffuse horizontal illuminance")};
}

bool has_daylight(const SolarComponents& c) {
    return std::visit(
        [](const auto& given) {
            const auto [direct, diffuse] = given;
            return direct + diffuse > 0;
        },
        c);
}

} // namespace

Eigen::VectorXf sky_vector(const Sky& sky, const SkyPatches& patches) {
    Eigen::VectorXf vector(Eigen::Index(patches.size()));
    PatchQuadrature(patches).mean_radiance(sky, {vector.data(), patches.size()});
    return vector;
}

SkyMatrix sky_matrix(const Weather& weather, const SkyPatches& patches,
                     const SkyMatrixOptions& options, const Context& ctx) {
    if (!(options.ground_reflectance >= 0 && options.ground_reflectance <= 1))
        throw ConfigError(
            fmt::format("ground reflectance {} is outside [0, 1]", options.ground_reflectance));
    const std::size_t hours = weather.hours.size();
    std::vector<SolarComponents> weather_of_hour;
    for (const WeatherHour& h : weather.hours) // serially: the first bad line is the one named
        weather_of_hour.push_back(components(weather, h, options.input));

    const PatchQuadrature quadrature(patches);
    const Compass& compass = patches.compass();
    SkyMatrix m;
    m.radiance = Eigen::MatrixXf::Zero(Eigen::Index(patches.size()), Eigen::Index(hours));
    m.suns.resize(hours);
    run_in_arena(ctx, [&] {
        parallel_for_index(hours, 8, [&](std::size_t i) {
            HourSun& sun = m.suns[i];
            sun.angles = sun_position(weather, i);
            sun.direction = compass.direction(sun.angles.altitude_deg, sun.angles.azimuth_deg);
            if (!has_daylight(weather_of_hour[i]))
                return; // night: the column stays zero
            const PerezSkyAndSun hour =
                perez_sky_and_sun(weather_of_hour[i], compass, sun.direction,
                                  day_of_year(weather, i), options.ground_reflectance);
            if (hour.sun)
                sun.normal_lx = to_photometric(hour.sun->irradiance);
            quadrature.mean_radiance(hour.sky,
                                     {m.radiance.col(Eigen::Index(i)).data(), patches.size()});
        });
    });
    return m;
}

} // namespace penumbra::annual
