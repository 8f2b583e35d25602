// A Perez all-weather sky and its sun from one hour's weather, as Radiance's gendaylit builds
// them: the sky's clearness ε and brightness Δ, and the luminous efficacies of the diffuse and
// direct light, from Perez, Ineichen, Seals, Michalsky & Stewart 1990, "Modeling daylight
// availability and irradiance components from direct and global irradiance", Solar Energy
// 44(5) 271–289 (eqs. 1–2, 7–8, Table 4); Kasten 1966's relative air mass; the eccentricity
// correction of Spencer 1971. Deviation: illuminance input iterates the efficacies to a fixed
// point (gendaylit runs nine rounds of the same iteration).

#include "sky_models.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace penumbra {

namespace {

constexpr double k_solar_constant_w_m2 = 1367;    // gendaylit's
constexpr double k_solar_constant_lx = 127500;    // gendaylit's first guess of the efficacy
constexpr double k_precipitable_water_cm = 2.0;   // gendaylit's default (dew point 10.97 °C)
constexpr double k_clearness_max = 12.01 - 0.001; // gendaylit's clamp, inside the last bin
constexpr double k_sun_angular_diameter_deg = 0.533;

struct EfficacyCoefficients {
    double a, b, c, d;
};

// Perez et al. 1990, Table 4, per clearness bin (the same bins as the sky's): diffuse
// horizontal (eq. 7: a + b W + c cos Z + d ln Δ) and direct normal (eq. 8: a + b W +
// c exp(5.73 Z − 5) + d Δ) luminous efficacy, lm/W; W the precipitable water, cm.
constexpr EfficacyCoefficients k_diffuse_efficacy[8] = {
    {97.24, -0.46, 12.00, -8.91},   {107.22, 1.15, 0.59, -3.95},    {104.97, 2.96, -5.53, -8.77},
    {102.39, 5.59, -13.95, -13.90}, {100.71, 5.94, -22.75, -23.74}, {106.42, 3.83, -36.15, -28.83},
    {141.88, 1.90, -53.24, -14.03}, {152.23, 0.35, -45.27, -7.98},
};
constexpr EfficacyCoefficients k_direct_efficacy[8] = {
    {57.20, -4.55, -2.98, 117.12}, {98.99, -3.46, -1.21, 12.38},  {109.83, -4.90, -1.71, -8.81},
    {110.34, -5.84, -1.99, -4.56}, {106.36, -3.97, -1.75, -6.16}, {107.19, -1.25, -1.51, -26.73},
    {105.75, 0.77, -1.26, -34.44}, {101.18, 1.58, -1.10, -8.29},
};

/// Kasten 1966: air mass relative to the zenith's, finite at the horizon (≈ 36.5).
double relative_air_mass(double sun_zenith) {
    const double z_deg = std::min(sun_zenith, k_pi / 2) * 180 / k_pi;
    return 1 / (std::cos(z_deg * k_pi / 180) + 0.15 * std::pow(93.885 - z_deg, -1.253));
}

/// Spencer 1971: (mean Sun–Earth distance / distance)² on \p day_of_year.
double eccentricity_correction(int day_of_year) {
    const double angle = 2 * k_pi * (day_of_year - 1) / 365.0;
    return 1.00011 + 0.034221 * std::cos(angle) + 0.00128 * std::sin(angle) +
           0.000719 * std::cos(2 * angle) + 0.000077 * std::sin(2 * angle);
}

/// The horizontal component of \p dir, unit: the sun below the horizon, lifted onto it.
Vec3 onto_horizon(const Vec3& dir, const Compass& compass) {
    const Vec3 horizontal = dir - compass.up * dot(dir, compass.up);
    return length(horizontal) > 1e-9 ? normalize(horizontal) : compass.north;
}

/// Irradiance from illuminance: the efficacies depend on ε and Δ, which depend on the
/// irradiance; iterated from 127.5 klx / 1367 W/m² until it changes by < 1e-3 W/m².
SolarIrradiance irradiance_of(const SolarIlluminance& lux, double sun_zenith, int day) {
    SolarIrradiance w{lux.direct_normal_lx * k_solar_constant_w_m2 / k_solar_constant_lx,
                      lux.diffuse_horizontal_lx * k_solar_constant_w_m2 / k_solar_constant_lx};
    for (int round = 0; round < 50; ++round) {
        const PerezSky sky = perez_clearness_and_brightness(w, sun_zenith, day);
        const double diffuse_efficacy = perez_diffuse_efficacy(sky, sun_zenith);
        const double direct_efficacy = perez_direct_efficacy(sky, sun_zenith);
        const SolarIrradiance next{direct_efficacy < 0.1 ? 0.0
                                                         : lux.direct_normal_lx / direct_efficacy,
                                   lux.diffuse_horizontal_lx / diffuse_efficacy};
        const bool settled =
            std::abs(next.direct_normal_w_m2 - w.direct_normal_w_m2) < 1e-3 &&
            std::abs(next.diffuse_horizontal_w_m2 - w.diffuse_horizontal_w_m2) < 1e-3;
        w = next;
        if (settled)
            break;
    }
    return w;
}

} // namespace

PerezSky perez_clearness_and_brightness(const SolarIrradiance& irradiance, double sun_zenith,
                                        int day_of_year) {
    const double z = std::clamp(sun_zenith, 0.0, k_pi / 2);
    const double diffuse = irradiance.diffuse_horizontal_w_m2;
    PerezSky sky;
    sky.clearness = k_clearness_max;
    if (diffuse > 0) {
        const double kz3 = 1.041 * z * z * z;
        sky.clearness = ((diffuse + irradiance.direct_normal_w_m2) / diffuse + kz3) / (1 + kz3);
    }
    sky.clearness = std::clamp(sky.clearness, 1.0, k_clearness_max);
    sky.brightness = diffuse * relative_air_mass(z) /
                     (k_solar_constant_w_m2 * eccentricity_correction(day_of_year));
    sky.brightness = std::clamp(sky.brightness, 0.01, 0.6);
    return sky;
}

double perez_diffuse_efficacy(const PerezSky& sky, double sun_zenith) {
    const EfficacyCoefficients& k = k_diffuse_efficacy[perez_clearness_bin(sky.clearness)];
    return k.a + k.b * k_precipitable_water_cm + k.c * std::cos(sun_zenith) +
           k.d * std::log(sky.brightness);
}

double perez_direct_efficacy(const PerezSky& sky, double sun_zenith) {
    const EfficacyCoefficients& k = k_direct_efficacy[perez_clearness_bin(sky.clearness)];
    return std::max(0.0, k.a + k.b * k_precipitable_water_cm +
                             k.c * std::exp(5.73 * sun_zenith - 5) + k.d * sky.brightness);
}

PerezSkyAndSun perez_sky_and_sun(const SolarComponents& weather, const Compass& compass,
                                 const Vec3& sun_direction, int day_of_year,
                                 std::optional<double> ground_reflectance, Horizon horizon) {
    if (day_of_year < 1 || day_of_year > 366)
        throw InternalError("perez_sky_and_sun: day of year " + std::to_string(day_of_year) +
                            " is outside [1, 366]");
    const double sin_altitude = dot(sun_direction, compass.up);
    const double sun_zenith = std::acos(std::clamp(sin_altitude, 0.0, 1.0));
    const bool negative = std::visit(
        [](const auto& given) {
            const auto [direct, diffuse] = given;
            return !(direct >= 0 && diffuse >= 0);
        },
        weather);
    if (negative)
        throw InternalError("perez_sky_and_sun: negative or NaN irradiance or illuminance");
    SolarIrradiance w;
    SolarIlluminance lux;
    if (const auto* given = std::get_if<SolarIrradiance>(&weather)) {
        w = *given;
    } else {
        lux = std::get<SolarIlluminance>(weather);
        w = irradiance_of(lux, sun_zenith, day_of_year);
    }
    const PerezSky perez = perez_clearness_and_brightness(w, sun_zenith, day_of_year);
    if (std::holds_alternative<SolarIrradiance>(weather))
        lux = {w.direct_normal_w_m2 * perez_direct_efficacy(perez, sun_zenith),
               w.diffuse_horizontal_w_m2 * perez_diffuse_efficacy(perez, sun_zenith)};

    SkyDescription description;
    description.model = perez;
    description.compass = compass;
    description.sun_direction =
        sin_altitude > 0 ? sun_direction : onto_horizon(sun_direction, compass);
    description.level = HorizontalIlluminance{lux.diffuse_horizontal_lx};
    description.ground_reflectance = ground_reflectance;
    description.horizon = horizon;

    PerezSkyAndSun result;
    const double sun_horizontal_lx = lux.direct_normal_lx * std::max(0.0, sin_altitude);
    result.sky = make_sky(description, sun_horizontal_lx);
    if (lux.diffuse_horizontal_lx > 0 && !(result.sky.zenith_radiance > 0)) {
        description.model = UniformSky{}; // a sky the fit makes black everywhere (gendaymtx)
        result.sky = make_sky(description, sun_horizontal_lx);
    }
    if (sin_altitude > 0 && lux.direct_normal_lx > 0)
        result.sun = Sun{sun_direction, from_photometric(lux.direct_normal_lx, Rgb(1.0f)),
                         k_sun_angular_diameter_deg};
    return result;
}

} // namespace penumbra
