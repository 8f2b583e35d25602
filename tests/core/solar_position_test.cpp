// The sun's position against published values: NOAA's solar calculator spreadsheet
// (NOAA_Solar_Calculations_day.xls, its first row as shipped: 21 June 2010, 00:06 at UTC−7,
// 40° N 105° W; the same algorithm, so to 1e-4°), Meeus' worked examples, and the NREL SPA
// report's example (Reda & Andreas 2004, NREL/TP-560-34302, Table A5.1: a more accurate
// algorithm, so within 0.05°).

#include "core/solar_position.h"

#include <cmath>

#include <gtest/gtest.h>

namespace penumbra {
namespace {

TEST(SolarPosition, JulianDayMatchesMeeusExample7a) {
    // Meeus, Astronomical Algorithms, example 7.a: 1957 October 4.81 → JD 2436116.31.
    EXPECT_NEAR(julian_day({1957, 10, 4, 0.81 * 24}, 0), 2436116.31, 1e-6);
    // Example 7.b-style check across a time zone: 2000 January 1, 12:00 UT = J2000.0.
    EXPECT_NEAR(julian_day({2000, 1, 1, 13}, 1), 2451545.0, 1e-9);
}

TEST(SolarPosition, MatchesNoaaSpreadsheetRow) {
    const Location boulder{40, -105, -7};
    const LocalTime when{2010, 6, 21, 0.1};
    EXPECT_NEAR(julian_day(when, boulder.time_zone_h), 2455368.79583333, 1e-7);
    const SunEphemeris sun = sun_ephemeris(julian_day(when, boulder.time_zone_h));
    EXPECT_NEAR(sun.declination_deg, 23.4383706192869, 1e-6);
    EXPECT_NEAR(sun.equation_of_time_min, -1.71536757846953, 1e-5);
    const SolarAngles angles = solar_position(boulder, when);
    EXPECT_NEAR(angles.altitude_deg, -26.5537621191813, 1e-4); // true (unrefracted) elevation
    EXPECT_NEAR(angles.azimuth_deg, 1.09867118388445, 1e-4);
}

TEST(SolarPosition, MatchesMeeusExamples25aAnd28b) {
    // 1992 October 13.0 TD: apparent declination −7.78507° (example 25.a, the low-accuracy
    // method, as NOAA's) and Smart's equation of time +13m42.7s (example 28.b).
    const SunEphemeris sun = sun_ephemeris(2448908.5);
    EXPECT_NEAR(sun.declination_deg, -7.78507, 1e-4);
    EXPECT_NEAR(sun.equation_of_time_min, 13 + 42.7 / 60, 0.1 / 60);
}

TEST(SolarPosition, MatchesNrelSpaExampleWithinTwentiethOfADegree) {
    // 17 October 2003, 12:30:30 at UTC−7, 39.742476° N, 105.1786° W. Table A5.1 gives the
    // topocentric elevation without refraction e0 = 39.872046° and azimuth 194.340241°.
    const SolarAngles angles =
        solar_position({39.742476, -105.1786, -7}, {2003, 10, 17, 12 + 30.5 / 60});
    EXPECT_NEAR(angles.altitude_deg, 39.872046, 0.05);
    EXPECT_NEAR(angles.azimuth_deg, 194.340241, 0.05);
}

TEST(SolarPosition, SolarNoonIsOnTheMeridian) {
    const Location site{52, 0, 0};
    const LocalTime noon{2025, 3, 21, 12};
    const SolarAngles north = solar_position_at_solar_time(site, noon);
    EXPECT_NEAR(north.azimuth_deg, 180, 1e-9);
    // At solar noon the sun stands 90° − latitude + declination high; the declination is NOAA's
    // at the standard time of that noon (12:00 − the equation of time, at longitude 0).
    const double eot = sun_ephemeris(julian_day(noon, 0)).equation_of_time_min;
    const double declination =
        sun_ephemeris(julian_day({2025, 3, 21, 12 - eot / 60}, 0)).declination_deg;
    EXPECT_NEAR(north.altitude_deg, 90 - 52 + declination, 1e-4);
    const SolarAngles south = solar_position_at_solar_time({-33.9, 151.2, 10}, {2025, 6, 21, 12});
    EXPECT_NEAR(south.azimuth_deg, 0, 1e-9);
    // Morning: east of the meridian.
    const SolarAngles morning = solar_position_at_solar_time(site, {2025, 6, 21, 9});
    EXPECT_GT(morning.azimuth_deg, 0);
    EXPECT_LT(morning.azimuth_deg, 180);
}

TEST(SolarPosition, DayOfYear) {
    EXPECT_EQ(day_of_year(2025, 1, 1), 1);
    EXPECT_EQ(day_of_year(2025, 3, 21), 80);
    EXPECT_EQ(day_of_year(2024, 3, 21), 81);
    EXPECT_EQ(day_of_year(2024, 12, 31), 366);
}

} // namespace
} // namespace penumbra
