// The sun's position by NOAA's solar calculator (NOAA Global Monitoring Laboratory,
// NOAA_Solar_Calculations_day.xls), which implements Meeus, "Astronomical Algorithms" (2nd ed.,
// 1998): the Julian day (ch. 7), the sun's low-accuracy apparent longitude and the corrected
// obliquity (ch. 25), Smart's equation of time (ch. 28). Accurate to about 0.01° for years
// 1800–2100. Deliberate deviation: no atmospheric refraction (a geometric direction, as sky
// models and daylight tools want it); the azimuth comes from atan2, not NOAA's acos branches.

#include "core/solar_position.h"

#include <algorithm>
#include <cmath>

#include "core/vec.h"

namespace penumbra {

namespace {

constexpr double k_deg = k_pi / 180.0;

double sin_deg(double a) {
    return std::sin(a * k_deg);
}
double cos_deg(double a) {
    return std::cos(a * k_deg);
}

/// Altitude and azimuth of a sun of declination \p declination_deg at hour angle
/// \p hour_angle_deg (0 on the meridian, positive in the afternoon) seen from \p latitude_deg.
SolarAngles horizon_angles(double latitude_deg, double declination_deg, double hour_angle_deg) {
    const double sin_alt =
        sin_deg(latitude_deg) * sin_deg(declination_deg) +
        cos_deg(latitude_deg) * cos_deg(declination_deg) * cos_deg(hour_angle_deg);
    const double east = -cos_deg(declination_deg) * sin_deg(hour_angle_deg);
    const double north = sin_deg(declination_deg) * cos_deg(latitude_deg) -
                         cos_deg(declination_deg) * sin_deg(latitude_deg) * cos_deg(hour_angle_deg);
    double azimuth = std::atan2(east, north) / k_deg;
    if (azimuth < 0)
        azimuth += 360;
    return {std::asin(std::clamp(sin_alt, -1.0, 1.0)) / k_deg, azimuth};
}

} // namespace

double julian_day(const LocalTime& when, double time_zone_h) {
    int year = when.year;
    int month = when.month;
    if (month <= 2) { // Meeus counts January and February as months 13 and 14 of the year before
        year -= 1;
        month += 12;
    }
    const int century = year / 100;
    const int gregorian = 2 - century + century / 4;
    const double day = when.day + (when.hour - time_zone_h) / 24.0;
    return std::floor(365.25 * (year + 4716)) + std::floor(30.6001 * (month + 1)) + day +
           gregorian - 1524.5;
}

int day_of_year(int year, int month, int day) {
    constexpr int before[] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};
    const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    return before[month - 1] + day + (leap && month > 2 ? 1 : 0);
}

SunEphemeris sun_ephemeris(double jd) {
    const double t = (jd - 2451545.0) / 36525.0; // Julian centuries since J2000.0
    const double mean_longitude = std::fmod(280.46646 + t * (36000.76983 + t * 0.0003032), 360.0);
    const double mean_anomaly = 357.52911 + t * (35999.05029 - 0.0001537 * t);
    const double eccentricity = 0.016708634 - t * (0.000042037 + 0.0000001267 * t);
    const double centre = sin_deg(mean_anomaly) * (1.914602 - t * (0.004817 + 0.000014 * t)) +
                          sin_deg(2 * mean_anomaly) * (0.019993 - 0.000101 * t) +
                          sin_deg(3 * mean_anomaly) * 0.000289;
    const double omega = 125.04 - 1934.136 * t; // longitude of the Moon's ascending node
    const double apparent_longitude = mean_longitude + centre - 0.00569 - 0.00478 * sin_deg(omega);
    const double mean_obliquity =
        23.0 + (26.0 + (21.448 - t * (46.815 + t * (0.00059 - t * 0.001813))) / 60.0) / 60.0;
    const double obliquity = mean_obliquity + 0.00256 * cos_deg(omega);

    SunEphemeris result;
    result.declination_deg = std::asin(sin_deg(obliquity) * sin_deg(apparent_longitude)) / k_deg;
    const double y = std::pow(std::tan(obliquity * k_deg / 2), 2);
    const double l0 = mean_longitude * k_deg;
    const double m = mean_anomaly * k_deg;
    const double e = eccentricity;
    const double eot_rad = y * std::sin(2 * l0) - 2 * e * std::sin(m) +
                           4 * e * y * std::sin(m) * std::cos(2 * l0) -
                           0.5 * y * y * std::sin(4 * l0) - 1.25 * e * e * std::sin(2 * m);
    result.equation_of_time_min = 4.0 * eot_rad / k_deg;
    return result;
}

SolarAngles solar_position(const Location& where, const LocalTime& when) {
    const SunEphemeris sun = sun_ephemeris(julian_day(when, where.time_zone_h));
    // True solar time, minutes: the clock corrected for longitude within the zone and the
    // equation of time.
    const double solar_min = when.hour * 60.0 + sun.equation_of_time_min +
                             4.0 * where.longitude_deg - 60.0 * where.time_zone_h;
    const double hour_angle = solar_min / 4.0 - 180.0;
    return horizon_angles(where.latitude_deg, sun.declination_deg, hour_angle);
}

SolarAngles solar_position_at_solar_time(const Location& where, const LocalTime& when) {
    // The standard time of that solar time depends on the equation of time at that moment:
    // two rounds settle it far below a second (it changes by < 30 s a day).
    LocalTime clock = when;
    SunEphemeris sun;
    for (int round = 0; round < 2; ++round) {
        sun = sun_ephemeris(julian_day(clock, where.time_zone_h));
        clock.hour = when.hour - (sun.equation_of_time_min + 4.0 * where.longitude_deg -
                                  60.0 * where.time_zone_h) /
                                     60.0;
    }
    sun = sun_ephemeris(julian_day(clock, where.time_zone_h));
    return horizon_angles(where.latitude_deg, sun.declination_deg, 15.0 * (when.hour - 12.0));
}

} // namespace penumbra
