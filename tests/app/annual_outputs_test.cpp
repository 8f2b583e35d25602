// The files of `penumbra annual` from synthetic hourly matrices whose metrics are worked out by
// hand: a free sensor and a 2 × 3 grid, each sensor s with a factor f_s, illuminance
// 100 f_s (h − 8) lx at EPW hour h (occupied: h = 9 … 18, so 100 f_s k for k = 1 … 10) and
// direct sun of 500 lx at hour 10 every day, 2000 lx at hour 12 on the first 50 f_s days
// (f_s > 0), and 5000 lx at the unoccupied hour 20 (which must not count).

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkXMLPolyDataReader.h>

#include "common/output_files.h"
#include "common/test_util.h"
#include "core/error.h"

#include "annual_outputs.h"
#include "colour_scale.h"
#include "grid_plan.h"
#include "heat_map.h"

namespace penumbra::app {
namespace {

namespace fs = std::filesystem;

/// Sensor factors: "desk" first, then the grid's points in lattice order (wp:0:0 … wp:1:2).
const std::vector<int> k_factors{3, 0, 1, 2, 4, 5, 6};

Scene small_scene() {
    Scene scene;
    scene.sensors.push_back({"desk", {5, 5, 0.8}, {0, 0, 1}});
    SensorGrid grid;
    grid.name = "wp";
    grid.origin = {0.5, 0.5, 0.8};
    grid.spacing_m = 1;
    grid.rows = 2;
    grid.columns = 3;
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 3; ++c) {
            grid.sensors.emplace_back(std::uint32_t(scene.sensors.size()));
            scene.sensors.push_back({fmt::format("wp:{}:{}", r, c), grid.point(r, c), {0, 0, 1}});
        }
    const std::vector<Vec3> corners{{0, 0, 0.8}, {3, 0, 0.8}, {3, 2, 0.8}, {0, 2, 0.8}};
    for (std::size_t i = 0; i < 4; ++i)
        grid.outline.push_back({corners[i], corners[(i + 1) % 4]});
    scene.grids.push_back(grid);
    return scene;
}

/// A year of 365 days (366 with \p leap), hour-ending records 1 … 24.
annual::Weather calendar_year(bool leap = false) {
    const int days[12]{31, leap ? 29 : 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    annual::Weather weather;
    weather.file = "synthetic.epw";
    for (int m = 1; m <= 12; ++m)
        for (int d = 1; d <= days[m - 1]; ++d)
            for (int h = 1; h <= 24; ++h) {
                annual::WeatherHour hour;
                hour.month = m, hour.day = d, hour.hour = h;
                weather.hours.push_back(hour);
            }
    return weather;
}

float illuminance(std::size_t sensor, int hour) {
    return float(100 * k_factors[sensor] * std::max(0, hour - 8));
}

AnnualResult synthetic_results(const Scene& scene, const annual::Weather& weather) {
    AnnualResult r;
    r.weather = weather;
    r.patches = 146;
    const auto n = Eigen::Index(scene.sensors.size()), hours = Eigen::Index(weather.hours.size());
    r.illuminance_lx.resize(n, hours);
    r.direct_sun_lx.setZero(n, hours);
    for (Eigen::Index i = 0; i < hours; ++i) {
        const int hour = weather.hours[std::size_t(i)].hour;
        const int day = int(i / 24) + 1;
        for (Eigen::Index s = 0; s < n; ++s) {
            const int f = k_factors[std::size_t(s)];
            r.illuminance_lx(s, i) = illuminance(std::size_t(s), hour);
            if (f > 0 && hour == 10)
                r.direct_sun_lx(s, i) = 500;
            if (f > 0 && hour == 12 && day <= 50 * f)
                r.direct_sun_lx(s, i) = 2000;
            if (hour == 20)
                r.direct_sun_lx(s, i) = 5000;
        }
    }
    r.occupied = annual::occupied_hours(weather.hours.size(), r.options.occupancy);
    r.sensors = annual::sensor_metrics(r.illuminance_lx, r.direct_sun_lx, r.occupied);
    std::vector<annual::SensorMetrics> grid_sensors(r.sensors.begin() + 1, r.sensors.end());
    r.grids.push_back(annual::grid_metrics(grid_sensors, r.occupied));
    r.seconds = {{"coefficients", 1.5}, {"hours", 0.5}};
    return r;
}

using test::Png;
using test::read_csv;
using test::read_png;

std::size_t distinct_colours(const Png& png) {
    std::set<std::uint32_t> colours;
    for (int y = 0; y < png.height; ++y)
        for (int x = 0; x < png.width; ++x) {
            const Rgb8 c = png.at(x, y);
            colours.insert(std::uint32_t(c.r) << 16 | std::uint32_t(c.g) << 8 | c.b);
        }
    return colours.size();
}

class AnnualOutputs : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::temp_dir("annual");
        options_.directory = dir_;
        options_.hourly = true;
        options_.heat_map_sensor = "wp:1:2";
        write_annual(scene_, results_, options_, test::quiet_context());
    }
    void TearDown() override { fs::remove_all(dir_); }

    Scene scene_ = small_scene();
    annual::Weather weather_ = calendar_year();
    AnnualResult results_ = synthetic_results(scene_, weather_);
    AnnualWriteOptions options_;
    fs::path dir_;
};

/// Per sensor factor 0 … 6, by hand over k = 1 … 10 (E = 100 f k): DA counts f k ≥ 3, cDA
/// averages min(1, f k / 3), UDI fell short E < 100, exceeded f k > 30; sun hours are 365 at
/// hour 10 plus 50 f at noon, ASE hours 50 f.
struct Expected {
    double da, cda, fell_short, useful, exceeded;
    int sun_hours, ase_hours;
};
const Expected k_by_factor[7]{
    {0, 0, 100, 0, 0, 0, 0},
    {80, 90, 0, 100, 0, 365 + 50, 50},
    {90, 100 * (2.0 / 3 + 9) / 10, 0, 100, 0, 365 + 100, 100},
    {100, 100, 0, 100, 0, 365 + 150, 150},
    {100, 100, 0, 70, 30, 365 + 200, 200},
    {100, 100, 0, 60, 40, 365 + 250, 250},
    {100, 100, 0, 50, 50, 365 + 300, 300},
};

TEST_F(AnnualOutputs, CsvHoldsEachSensorsMetricsComputedByHand) {
    const auto rows = read_csv(dir_ / "annual.csv");
    ASSERT_EQ(rows.size(), 1u + 7);
    EXPECT_EQ(rows[0], (std::vector<std::string>{"name", "x", "y", "z", "daylight_autonomy_pct",
                                                 "continuous_daylight_autonomy_pct",
                                                 "udi_fell_short_pct", "udi_useful_pct",
                                                 "udi_exceeded_pct", "sun_hours", "ase_hours"}));
    for (std::size_t s = 0; s < 7; ++s) {
        const auto& row = rows[s + 1];
        ASSERT_EQ(row.size(), 11u);
        EXPECT_EQ(row[0], scene_.sensors[s].name);
        EXPECT_DOUBLE_EQ(std::stod(row[1]), scene_.sensors[s].position.x);
        EXPECT_DOUBLE_EQ(std::stod(row[3]), 0.8);
        const Expected& e = k_by_factor[k_factors[s]];
        // Six significant digits in the file.
        const std::vector<double> expected{e.da,
                                           e.cda,
                                           e.fell_short,
                                           e.useful,
                                           e.exceeded,
                                           double(e.sun_hours),
                                           double(e.ase_hours)};
        for (std::size_t m = 0; m < expected.size(); ++m)
            EXPECT_NEAR(std::stod(row[4 + m]), expected[m], 1e-5 * std::max(1.0, expected[m]))
                << row[0] << " " << rows[0][4 + m];
    }
}

// sDA: grid factors 0, 1, 2, 4, 5, 6 have DA 0, 80, 90, 100, 100, 100 %: 5 of 6 reach 50 %.
// ASE: only factor 6 has more than 250 hours above 1000 lx (factor 5 has exactly 250): 1 of 6.
TEST_F(AnnualOutputs, SummaryHasGridStatisticsThresholdsAndTheRun) {
    std::ifstream in(dir_ / "summary.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["hours"], 8760);
    EXPECT_EQ(j["occupied_hours"], 3650);
    EXPECT_EQ(j["occupancy"]["start_hour"], 8);
    EXPECT_EQ(j["occupancy"]["end_hour"], 18);
    EXPECT_EQ(j["thresholds"]["daylight_autonomy_lx"], 300);
    EXPECT_EQ(j["thresholds"]["ase_hours"], 250);
    EXPECT_EQ(j["thresholds"]["sda_pct"], 50);
    ASSERT_EQ(j["grids"].size(), 1u);
    EXPECT_EQ(j["grids"][0]["name"], "wp");
    EXPECT_EQ(j["grids"][0]["points"], 6);
    EXPECT_NEAR(j["grids"][0]["sda_pct"].get<double>(), 100.0 * 5 / 6, 1e-9);
    EXPECT_NEAR(j["grids"][0]["ase_pct"].get<double>(), 100.0 / 6, 1e-9);
    EXPECT_EQ(j["weather"]["file"], "synthetic.epw");
    EXPECT_EQ(j["sky_patches"]["count"], 146);
    EXPECT_EQ(j["seconds"]["coefficients"], 1.5);
    EXPECT_FALSE(j.contains("blinds"));
    EXPECT_FALSE(j.contains("mesh"));
}

TEST_F(AnnualOutputs, OnePlanPerGridAndMetricOfThePlansSize) {
    const PlanLayout layout = PlanLayout::of(scene_.grids[0]);
    ASSERT_EQ(annual_metrics().size(), 7u);
    for (const AnnualMetric& metric : annual_metrics()) {
        const Png png = read_png(dir_ / fmt::format("annual_wp_{}.png", metric.file));
        EXPECT_EQ(png.width, layout.width) << metric.file;
        EXPECT_EQ(png.height, layout.height) << metric.file;
        EXPECT_GT(distinct_colours(png), 10u) << metric.file;
    }
}

// On DA's plan (0–100 %), the cell around wp:1:2 (DA 100 %) is the scale's top colour and
// the one around wp:0:0 (DA 0 %) its bottom colour: a quarter spacing beyond each point, where
// the plan holds the outermost points' values.
TEST_F(AnnualOutputs, DaPlanColoursThePointsValues) {
    const SensorGrid& grid = scene_.grids[0];
    const PlanLayout layout = PlanLayout::of(grid);
    const Png png = read_png(dir_ / "annual_wp_da.png");
    const auto colour_at = [&](double row, double column) {
        const auto [x, y] = layout.pixel_at(grid, row, column);
        return png.at(int(std::lround(x)), int(std::lround(y)));
    };
    EXPECT_EQ(colour_at(1.25, 2.25), viridis(1));
    EXPECT_EQ(colour_at(-0.25, -0.25), viridis(0));
}

// Day 100 at EPW hour 12 (E = 600 × 4 = 2400 lx) on a scale of decades 1 … 10 000 lx (the
// maximum is 600 × 16 = 9600 lx); at night (hour 3, 0 lx) the bottom colour.
TEST_F(AnnualOutputs, HeatMapCellHasTheColourOfItsHoursValue) {
    const HeatMapLayout layout = HeatMapLayout::of(365);
    const Png png = read_png(dir_ / "heat_map_wp_1_2.png");
    ASSERT_EQ(png.width, layout.width);
    ASSERT_EQ(png.height, layout.height);
    EXPECT_EQ(layout.map_width, 730);
    EXPECT_EQ(layout.map_height, 240);
    const ColourScale scale = heat_map_scale(9600);
    EXPECT_EQ(scale.levels, (std::vector<double>{1, 10, 100, 1000, 10000}));
    const auto [x, y] = layout.cell(100, 12);
    EXPECT_EQ(png.at(x + 1, y + 5), viridis(std::log10(2400.0) / 4));
    EXPECT_EQ(png.at(x, y), png.at(x + 1, y + 9)); // the whole cell
    const auto [xn, yn] = layout.cell(100, 3);
    EXPECT_EQ(png.at(xn + 1, yn + 5), viridis(0));
    EXPECT_GT(distinct_colours(png), 10u);
}

// With 29 February the map has 366 columns: 29 February is day 60, 31 December day 366.
TEST(HeatMap, LeapYearHas366Days) {
    const annual::Weather weather = calendar_year(true);
    ASSERT_EQ(weather.hours.size(), 8784u);
    std::vector<float> lx(weather.hours.size(), 0);
    lx[59 * 24 + 11] = 1000; // 29 February, hour 12
    lx[365 * 24 + 11] = 100; // 31 December, hour 12
    const Canvas canvas = draw_heat_map(weather, lx, {"leap", ""});
    const HeatMapLayout layout = HeatMapLayout::of(366);
    EXPECT_EQ(canvas.width(), layout.width);
    EXPECT_EQ(layout.map_width, 732);
    const ColourScale scale = heat_map_scale(1000); // 1 … 1000 lx in 1-2-5 levels
    const auto [x, y] = layout.cell(60, 12);
    EXPECT_EQ(canvas.at(x, y), viridis(1));
    EXPECT_EQ(canvas.at(x - 1, y), viridis(0)); // 28 February
    const auto [xe, ye] = layout.cell(366, 12);
    EXPECT_EQ(canvas.at(xe + 1, ye), scale.colour(100));
    EXPECT_NEAR(scale.fraction(100), 2.0 / 3, 1e-12);
}

vtkSmartPointer<vtkPolyData> read_vtp(const fs::path& path) {
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    return vtkSmartPointer<vtkPolyData>(reader->GetOutput());
}

TEST_F(AnnualOutputs, VtpHoldsEveryMetricAtTheGridsPoints) {
    const auto data = read_vtp(dir_ / "annual_wp.vtp");
    ASSERT_EQ(data->GetNumberOfPoints(), 6);
    EXPECT_EQ(data->GetNumberOfPolys(), 2); // the quads between four neighbours
    vtkPointData* pd = data->GetPointData();
    for (vtkIdType i = 0; i < 6; ++i) {
        const Expected& e = k_by_factor[k_factors[std::size_t(i) + 1]];
        double p[3];
        data->GetPoint(i, p);
        EXPECT_DOUBLE_EQ(p[0], scene_.sensors[std::size_t(i) + 1].position.x);
        EXPECT_NEAR(pd->GetArray("daylight_autonomy_pct")->GetTuple1(i), e.da, 1e-9);
        EXPECT_NEAR(pd->GetArray("continuous_daylight_autonomy_pct")->GetTuple1(i), e.cda, 1e-9);
        EXPECT_NEAR(pd->GetArray("udi_exceeded_pct")->GetTuple1(i), e.exceeded, 1e-9);
        EXPECT_EQ(pd->GetArray("ase_hours")->GetTuple1(i), e.ase_hours);
        EXPECT_EQ(pd->GetArray("sun_hours")->GetTuple1(i), e.sun_hours);
        EXPECT_EQ(pd->GetArray("column")->GetTuple1(i), double(i % 3));
    }
    auto* units = vtkStringArray::SafeDownCast(data->GetFieldData()->GetAbstractArray("units"));
    ASSERT_NE(units, nullptr);
    EXPECT_EQ(units->GetValue(0), "daylight_autonomy_pct=%");
    EXPECT_EQ(units->GetValue(6), "ase_hours=h");
}

TEST_F(AnnualOutputs, HourlyValuesRoundTrip) {
    std::ifstream in(dir_ / "hourly_illuminance.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["shape"], (nlohmann::json{7, 8760}));
    EXPECT_EQ(j["type"], "float32");
    EXPECT_EQ(j["unit"], "lx");
    EXPECT_EQ(j["sensors"][6], "wp:1:2");
    ASSERT_EQ(j["hours"].size(), 8760u);
    EXPECT_EQ(j["hours"][24 * 59 + 11], (nlohmann::json{3, 1, 12})); // 1 March, hour 12
    EXPECT_EQ(fs::file_size(dir_ / "hourly_illuminance.f32"), 7u * 8760 * 4);
    std::ifstream raw(dir_ / "hourly_illuminance.f32", std::ios::binary);
    std::vector<float> values(7 * 8760);
    raw.read(reinterpret_cast<char*>(values.data()), std::streamsize(values.size() * 4));
    for (std::size_t s = 0; s < 7; ++s)
        for (std::size_t i = 0; i < 8760; i += 7)
            ASSERT_EQ(values[s * 8760 + i], illuminance(s, weather_.hours[i].hour))
                << s << " " << i;
}

TEST_F(AnnualOutputs, UnknownHeatMapSensorIsAOneLineErrorBeforeAnyFile) {
    const std::string other = test::temp_dir("annual_bad");
    AnnualWriteOptions bad{other, false, "wp:9:9"};
    try {
        write_annual(scene_, results_, bad, test::quiet_context());
        FAIL() << "no error";
    } catch (const ConfigError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("--heat-map"), std::string::npos) << what;
        EXPECT_NE(what.find("'wp:9:9'"), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
    EXPECT_FALSE(fs::exists(fs::path(other) / "annual.csv"));
    fs::remove_all(other);
}

// The default heat-map sensor is the first point of the first grid (wp:0:0, sensor 1); a
// second run without --hourly and with another sensor removes the first run's hourly files
// and heat map, and leaves the user's files.
TEST_F(AnnualOutputs, RerunRemovesFilesItNoLongerWrites) {
    EXPECT_EQ(heat_map_sensor(scene_, std::nullopt), std::optional<std::size_t>(1));
    std::ofstream(dir_ / "annual_notes.txt") << "mine";
    write_annual(scene_, results_, {dir_, false, std::nullopt}, test::quiet_context());
    EXPECT_TRUE(fs::exists(dir_ / "heat_map_wp_0_0.png"));
    EXPECT_FALSE(fs::exists(dir_ / "heat_map_wp_1_2.png"));
    EXPECT_FALSE(fs::exists(dir_ / "hourly_illuminance.f32"));
    EXPECT_FALSE(fs::exists(dir_ / "hourly_illuminance.json"));
    EXPECT_TRUE(fs::exists(dir_ / "annual_wp_da.png"));
    EXPECT_TRUE(fs::exists(dir_ / "annual_notes.txt"));
}

// LM-83's blinds on the synthetic year: a group closes them when more than 2 % of its sensors
// get direct sun over 1000 lx. The grid (6 points, so one is enough; largest factor 6) closes
// at hour 12 on days 1 … 300 and at hour 20 every day (5000 lx): 665 hours, 300 occupied; the
// desk, a group of its own (factor 3), at hour 12 on days 1 … 150 and at hour 20: 515 and 150.
// In those hours the shaded values (here 7 lx everywhere) replace the group's own.
TEST(AnnualBlinds, ClosedHoursAndValuesOnAHandBuiltYear) {
    const Scene scene = small_scene();
    const annual::Weather weather = calendar_year();
    AnnualResult r = synthetic_results(scene, weather);
    r.options.blinds = true;
    r.blinds = blinds_groups(scene);
    ASSERT_EQ(r.blinds.size(), 2u);
    EXPECT_EQ(r.blinds[0].name, "wp");
    EXPECT_EQ(r.blinds[0].sensors, (std::vector<std::uint32_t>{1, 2, 3, 4, 5, 6}));
    EXPECT_EQ(r.blinds[1].name, "");
    EXPECT_EQ(r.blinds[1].sensors, (std::vector<std::uint32_t>{0}));
    const Eigen::MatrixXf open = r.illuminance_lx;
    const Eigen::MatrixXf shaded = Eigen::MatrixXf::Constant(open.rows(), open.cols(), 7.0f);
    apply_blinds(r.blinds, r.direct_sun_lx, shaded, {}, r.illuminance_lx);
    const auto closed_by_hand = [](int factor, int day, int hour) {
        return hour == 20 || (hour == 12 && day <= 50 * factor);
    };
    for (std::size_t i = 0; i < weather.hours.size(); ++i) {
        const int day = int(i / 24) + 1, hour = weather.hours[i].hour;
        const bool grid_closed = closed_by_hand(6, day, hour);
        const bool desk_closed = closed_by_hand(3, day, hour);
        ASSERT_EQ(r.blinds[0].closed[i], grid_closed) << i;
        ASSERT_EQ(r.blinds[1].closed[i], desk_closed) << i;
        for (Eigen::Index s = 0; s < 7; ++s) {
            const bool closed = s == 0 ? desk_closed : grid_closed;
            ASSERT_EQ(r.illuminance_lx(s, Eigen::Index(i)),
                      closed ? 7.0f : open(s, Eigen::Index(i)))
                << s << " " << i;
        }
    }
    const nlohmann::json j = nlohmann::json::parse(annual_summary_json(scene, r));
    ASSERT_EQ(j["blinds"].size(), 2u);
    EXPECT_EQ(j["blinds"][0]["group"], "wp");
    EXPECT_EQ(j["blinds"][0]["closed_hours"], 665);
    EXPECT_EQ(j["blinds"][0]["closed_occupied_hours"], 300);
    EXPECT_EQ(j["blinds"][1]["sensors"], 1);
    EXPECT_EQ(j["blinds"][1]["closed_hours"], 515);
    EXPECT_EQ(j["blinds"][1]["closed_occupied_hours"], 150);
}

TEST(AnnualOutputsSizes, MatricesThatDoNotFitTheSceneAreAnInternalError) {
    const Scene scene = small_scene();
    const annual::Weather weather = calendar_year();
    AnnualResult r = synthetic_results(scene, weather);
    r.direct_sun_lx.conservativeResize(6, Eigen::NoChange);
    EXPECT_THROW(write_annual(scene, r, {test::temp_dir("annual_sizes")}, test::quiet_context()),
                 InternalError);
}

} // namespace
} // namespace penumbra::app
