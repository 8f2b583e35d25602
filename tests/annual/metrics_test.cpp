// The metrics against values worked out by hand on a small hourly series whose values sit on
// and beside every threshold (docs/annual.md gives the definitions and their edges).

#include "annual/metrics.h"

#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"

namespace penumbra::annual {
namespace {

TEST(Occupancy, DefaultIsEpwHoursNineToEighteenEveryDay) {
    const std::vector<bool> year = occupied_hours(8760, {});
    EXPECT_EQ(std::count(year.begin(), year.end(), true), 3650);
    // Hour index 7 is EPW hour 8 (7:00–8:00): out; index 8 (8:00–9:00) in; index 17
    // (17:00–18:00) in; index 18 out.
    EXPECT_FALSE(year[7]);
    EXPECT_TRUE(year[8]);
    EXPECT_TRUE(year[17]);
    EXPECT_FALSE(year[18]);
    EXPECT_TRUE(year[24 + 8]);
    const std::vector<bool> leap = occupied_hours(8784, {});
    EXPECT_EQ(std::count(leap.begin(), leap.end(), true), 3660);
    const std::vector<bool> all_day = occupied_hours(48, {0, 24});
    EXPECT_EQ(std::count(all_day.begin(), all_day.end(), true), 48);
    EXPECT_THROW(occupied_hours(24, {18, 8}), ConfigError);
    EXPECT_THROW(occupied_hours(24, {8, 25}), ConfigError);
}

/// One day (24 hours) of five sensors; the occupied hours (indices 8–17) hold the values
/// below, every other hour 5 000 lx of daylight and of sun, which no metric may count.
struct Series {
    Eigen::MatrixXf illuminance = Eigen::MatrixXf::Constant(5, 24, 5000.0f);
    Eigen::MatrixXf sun = Eigen::MatrixXf::Constant(5, 24, 5000.0f);
    std::vector<bool> occupied = occupied_hours(24, {});

    void set(int sensor, const std::vector<float>& lx, const std::vector<float>& sun_lx) {
        for (int k = 0; k < 10; ++k) {
            illuminance(sensor, 8 + k) = lx[std::size_t(k)];
            sun(sensor, 8 + k) = sun_lx[std::size_t(k)];
        }
    }
};

Series hand_series() {
    Series s;
    // Sensor 0: each threshold's edge. ≥ 300: 300, 301, 3000, 3001, 600 (5 of 10).
    // < 100: 99, 0; > 3000: 3001; useful: the other 7. Sun > 0: 1000, 1000.5, 1, 2000, 1001
    // (5); sun > 1000: 1000.5, 2000, 1001 (3).
    s.set(0, {299, 300, 301, 99, 100, 3000, 3001, 0, 150, 600},
          {0, 1000, 1000.5f, 1, 0, 2000, 0, 0, 0, 1001});
    // Sensor 1: 300 lx all day, sun at exactly 1000 lx: DA 1, no ASE hour.
    s.set(1, std::vector<float>(10, 300), std::vector<float>(10, 1000));
    // Sensor 2: dark, no sun.
    s.set(2, std::vector<float>(10, 0), std::vector<float>(10, 0));
    // Sensor 3: 4 hours at 300 (DA 0.4), two hours of sun > 1000.
    s.set(3, {300, 300, 300, 300, 0, 0, 0, 0, 0, 0}, {1500, 1500, 0, 0, 0, 0, 0, 0, 0, 0});
    // Sensor 4: 6 hours at 10 000 (DA 0.6, UDI exceeded 0.6), four hours of sun > 1000.
    s.set(4, {1e4f, 1e4f, 1e4f, 1e4f, 1e4f, 1e4f, 50, 50, 50, 50},
          {2e3f, 2e3f, 2e3f, 2e3f, 0, 0, 0, 0, 0, 0});
    return s;
}

TEST(Metrics, PerSensorMatchHandCounts) {
    const Series s = hand_series();
    const std::vector<SensorMetrics> m = sensor_metrics(s.illuminance, s.sun, s.occupied);
    ASSERT_EQ(m.size(), 5u);
    EXPECT_DOUBLE_EQ(m[0].daylight_autonomy, 0.5);
    // cDA: five hours at 1, then (299 + 99 + 100 + 0 + 150) / 300 = 2.16: 7.16 / 10.
    EXPECT_NEAR(m[0].continuous_daylight_autonomy, 0.716, 1e-12);
    EXPECT_DOUBLE_EQ(m[0].udi_fell_short, 0.2);
    EXPECT_DOUBLE_EQ(m[0].udi_useful, 0.7);
    EXPECT_DOUBLE_EQ(m[0].udi_exceeded, 0.1);
    EXPECT_EQ(m[0].sun_hours, 5);
    EXPECT_EQ(m[0].ase_hours, 3);

    EXPECT_DOUBLE_EQ(m[1].daylight_autonomy, 1);
    EXPECT_DOUBLE_EQ(m[1].continuous_daylight_autonomy, 1);
    EXPECT_DOUBLE_EQ(m[1].udi_useful, 1);
    EXPECT_EQ(m[1].sun_hours, 10);
    EXPECT_EQ(m[1].ase_hours, 0);

    EXPECT_DOUBLE_EQ(m[2].daylight_autonomy, 0);
    EXPECT_DOUBLE_EQ(m[2].continuous_daylight_autonomy, 0);
    EXPECT_DOUBLE_EQ(m[2].udi_fell_short, 1);
    EXPECT_EQ(m[2].sun_hours, 0);

    EXPECT_DOUBLE_EQ(m[3].daylight_autonomy, 0.4);
    EXPECT_DOUBLE_EQ(m[3].continuous_daylight_autonomy, 0.4);
    EXPECT_EQ(m[3].ase_hours, 2);

    EXPECT_DOUBLE_EQ(m[4].daylight_autonomy, 0.6);
    // cDA: six hours at 1, four at 50 / 300: (6 + 4/6) / 10.
    EXPECT_NEAR(m[4].continuous_daylight_autonomy, (6 + 4.0 / 6) / 10, 1e-12);
    EXPECT_DOUBLE_EQ(m[4].udi_fell_short, 0.4);
    EXPECT_DOUBLE_EQ(m[4].udi_exceeded, 0.6);
    EXPECT_DOUBLE_EQ(m[4].udi_useful, 0);
    EXPECT_EQ(m[4].ase_hours, 4);
}

TEST(Metrics, GridCountsSensorsOnTheirEdges) {
    const Series s = hand_series();
    const std::vector<SensorMetrics> m = sensor_metrics(s.illuminance, s.sun, s.occupied);
    // sDA: DA ≥ 0.5 for sensors 0 (0.5 exactly), 1, 4: 3 of 5.
    // ASE with 2 hours instead of 250: more than 2 hours > 1000 lx for sensors 0 (3) and 4
    // (4); sensor 3 has exactly 2: 2 of 5.
    MetricThresholds t;
    t.ase_hours = 2;
    const GridMetrics grid = grid_metrics(m, s.occupied, t);
    EXPECT_DOUBLE_EQ(grid.spatial_daylight_autonomy, 0.6);
    EXPECT_DOUBLE_EQ(grid.annual_sunlight_exposure, 0.4);
    EXPECT_EQ(grid.occupied_hours, 10);
    // LM-83's 250 hours: no sensor of one day exceeds it.
    EXPECT_DOUBLE_EQ(grid_metrics(m, s.occupied).annual_sunlight_exposure, 0);
}

TEST(Metrics, ThresholdsAreConfigurable) {
    const Series s = hand_series();
    MetricThresholds t;
    t.daylight_autonomy_lx = 150;
    t.udi_lower_lx = 300;
    t.udi_upper_lx = 600;
    t.ase_lx = 1;
    const std::vector<SensorMetrics> m = sensor_metrics(s.illuminance, s.sun, s.occupied, t);
    // Sensor 0 ≥ 150: 299, 300, 301, 3000, 3001, 150, 600 (7). < 300: 299, 99, 100, 0, 150
    // (5); > 600: 3000, 3001 (2); sun > 1: 1000, 1000.5, 2000, 1001 (4).
    EXPECT_DOUBLE_EQ(m[0].daylight_autonomy, 0.7);
    EXPECT_DOUBLE_EQ(m[0].udi_fell_short, 0.5);
    EXPECT_DOUBLE_EQ(m[0].udi_exceeded, 0.2);
    EXPECT_DOUBLE_EQ(m[0].udi_useful, 0.3);
    EXPECT_EQ(m[0].ase_hours, 4);
}

TEST(Metrics, BlindsCloseWhenMoreThanTwoPercentSeeSun) {
    // 100 sensors, three hours: 2 sensors > 1000 lx (2 %: open), 3 (closed), 5 at exactly
    // 1000 lx (not above: open).
    Eigen::MatrixXf sun = Eigen::MatrixXf::Zero(100, 3);
    sun.block(0, 0, 2, 1).setConstant(1500);
    sun.block(0, 1, 3, 1).setConstant(1500);
    sun.block(0, 2, 5, 1).setConstant(1000);
    EXPECT_EQ(blinds_closed(sun), (std::vector<bool>{false, true, false}));
}

TEST(Metrics, RefuseMismatchedInputs) {
    const Series s = hand_series();
    EXPECT_THROW(sensor_metrics(s.illuminance, s.sun.leftCols(23), s.occupied), InternalError);
    EXPECT_THROW(sensor_metrics(s.illuminance, s.sun, std::vector<bool>(24, false)), ConfigError);
    MetricThresholds t;
    t.udi_upper_lx = 50;
    EXPECT_THROW(sensor_metrics(s.illuminance, s.sun, s.occupied, t), ConfigError);
}

} // namespace
} // namespace penumbra::annual
