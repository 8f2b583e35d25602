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

/// \brief A moment in local standard time (or local solar time, for
///        solar_position_at_solar_time()).
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

/// \brief The sun's declination and the equation of time at one instant.
struct SunEphemeris {
    double declination_deg = 0;
    double equation_of_time_min = 0; ///< apparent minus mean solar time, minutes
};

/// \brief The Julian day (days since noon UT, 1 January 4713 BC, Julian calendar) of \p when
///        in the standard time of \p time_zone_h (east-positive hours): Meeus ch. 7, Gregorian
///        calendar.
double julian_day(const LocalTime& when, double time_zone_h);

/// \brief Day of the year, 1 on 1 January (366 on 31 December of a leap year).
int day_of_year(int year, int month, int day);

/// \brief Declination and equation of time at Julian day \p jd by NOAA's solar calculator
///        (Meeus' low-accuracy solar coordinates, ch. 25, and Smart's equation of time, ch. 28;
///        UT taken for TT, as NOAA does).
SunEphemeris sun_ephemeris(double jd);

/// \brief The sun's position by NOAA's solar calculator (Meeus' algorithms, as NOAA's
///        spreadsheet implements them), without atmospheric refraction (which lifts the sun
///        by 0.5° at the horizon and < 0.02° above 45°): the geometric direction.
SolarAngles solar_position(const Location& where, const LocalTime& when);

/// \brief The same for \p when.hour in local apparent *solar* time (12:00 = the sun on the
///        meridian): the hour angle is 15° (hour − 12); the declination is NOAA's at the
///        standard time that solar time corresponds to.
SolarAngles solar_position_at_solar_time(const Location& where, const LocalTime& when);

/// \brief The sun's position by Radiance's gensky (sun.c: its declination and equation-of-time
///        series), for \p hour local *solar* time when \p solar_time is true, else
///        local standard time at \p where. Used for scenes that come from Radiance, so that
///        they keep Radiance's sun.
SolarAngles solar_position_gensky(const Location& where, int month, int day, double hour,
                                  bool solar_time);

} // namespace penumbra
