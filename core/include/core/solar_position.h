#pragma once
// Where the sun is: its altitude and azimuth at a place and time (issue #30). Conventions,
// written once: latitude north-positive, longitude and time zone east-positive (as EPW files
// give them), azimuth clockwise from north (east = 90°), local standard time (no daylight
// saving). Radiance's gensky uses west-positive longitudes and its own older formulas; its
// importer converts and keeps gensky's sun (solar_position_gensky).

namespace penumbra {

/// \brief A place on Earth.
struct Location {
    double latitude_deg = 0;  ///< north-positive, in [−90, 90]
    double longitude_deg = 0; ///< east-positive, in [−180, 180]
    double time_zone_h = 0;   ///< standard time's offset from UTC, hours, east-positive
};

/// \brief A moment in local standard time.
struct LocalTime {
    int year = 2025;
    int month = 1;    ///< 1–12
    int day = 1;      ///< 1–31
    double hour = 12; ///< decimal hours, [0, 24)
};

/// \brief The sun's direction seen from a place.
struct SolarAngles {
    double altitude_deg = 0; ///< above the horizon (negative below), without refraction
    double azimuth_deg = 0;  ///< clockwise from north, [0, 360)
};

/// \brief The sun's position by NOAA's solar calculator (Meeus' algorithms, as NOAA's
///        spreadsheet implements them).
SolarAngles solar_position(const Location& where, const LocalTime& when);

/// \brief The sun's position by Radiance's gensky (sun.c: its declination and equation-of-time
///        series), for \p solar_time_h local *solar* time when \p solar_time is true, else
///        local standard time at \p where. Used for scenes that come from Radiance, so that
///        they keep Radiance's sun.
SolarAngles solar_position_gensky(const Location& where, int month, int day, double hour,
                                  bool solar_time);

} // namespace penumbra
