// The sun's position as Radiance's gensky computes it (sun.c, 1987): a sine series for the
// declination and the equation of time, good to a few tenths of a degree. Scenes that come
// from Radiance keep this sun so that their shadows fall where Radiance's do.

#include "core/solar_position.h"

#include <array>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"

namespace penumbra {

namespace {

constexpr double k_pi = 3.14159265358979323846;
constexpr double k_rad = k_pi / 180.0;

/// Day of the year, 1 on 1 January, for a year without 29 February (as gensky counts).
int day_of_year(int month, int day) {
    static constexpr std::array<int, 12> days_before{0,   31,  59,  90,  120, 151,
                                                     181, 212, 243, 273, 304, 334};
    return days_before[std::size_t(month - 1)] + day;
}

/// Solar declination, radians: one sine over the year, zero at the March equinox (day 81).
double declination(int jd) {
    return 0.4093 * std::sin(2.0 * k_pi / 365.0 * (jd - 81));
}

/// Local solar time minus local standard time, hours: the equation of time's two sines plus
/// the longitude's offset from the time zone's meridian (4 minutes per degree).
double solar_time_offset_h(int jd, const Location& where) {
    const double equation_of_time = 0.170 * std::sin(4.0 * k_pi / 373.0 * (jd - 80)) -
                                    0.129 * std::sin(2.0 * k_pi / 355.0 * (jd - 8));
    const double meridian_deg = 15.0 * where.time_zone_h;
    return equation_of_time + (where.longitude_deg - meridian_deg) / 15.0;
}

} // namespace

SolarAngles solar_position_gensky(const Location& where, int month, int day, double hour,
                                  bool solar_time) {
    if (month < 1 || month > 12)
        throw InputError("", "month", fmt::format("must be in [1, 12], got {}", month));
    if (day < 1 || day > 31)
        throw InputError("", "day", fmt::format("must be in [1, 31], got {}", day));
    const int jd = day_of_year(month, day);
    const double delta = declination(jd);
    const double st = solar_time ? hour : hour + solar_time_offset_h(jd, where);
    const double hour_angle = st * k_pi / 12.0; // 0 at midnight, π at solar noon
    const double phi = where.latitude_deg * k_rad;
    const double altitude = std::asin(std::sin(phi) * std::sin(delta) -
                                      std::cos(phi) * std::cos(delta) * std::cos(hour_angle));
    // Measured from south, positive toward west, as gensky prints it.
    const double from_south = -std::atan2(
        std::cos(delta) * std::sin(hour_angle),
        -std::cos(phi) * std::sin(delta) - std::sin(phi) * std::cos(delta) * std::cos(hour_angle));
    double azimuth_deg = std::fmod(180.0 + from_south / k_rad, 360.0);
    if (azimuth_deg < 0)
        azimuth_deg += 360.0;
    return {.altitude_deg = altitude / k_rad, .azimuth_deg = azimuth_deg};
}

} // namespace penumbra
