// The EPW reader: the shipped Chicago file's header and records at known lines (values read
// from data/weather/chicago_ohare_tmy3.epw with awk, line numbers 1-based), the sun of an hour
// against Radiance's gensky formulas (an independent algorithm), and every refusal on small
// edits of a synthetic year.

#include "annual/epw.h"

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/error.h"

#include "common/test_util.h"

namespace penumbra::annual {
namespace {

const Weather& chicago() {
    static const Weather weather =
        read_epw(test::source_path("data/weather/chicago_ohare_tmy3.epw"));
    return weather;
}

TEST(Epw, ReadsTheShippedFilesLocation) {
    const WeatherSite& site = chicago().site;
    // Line 1: LOCATION,Chicago Ohare Intl Ap,IL,USA,TMY3,725300,41.98,-87.92,-6.0,201.0
    EXPECT_EQ(site.city, "Chicago Ohare Intl Ap");
    EXPECT_EQ(site.region, "IL");
    EXPECT_EQ(site.country, "USA");
    EXPECT_EQ(site.source, "TMY3");
    EXPECT_EQ(site.wmo, "725300");
    EXPECT_DOUBLE_EQ(site.location.latitude_deg, 41.98);
    EXPECT_DOUBLE_EQ(site.location.longitude_deg, -87.92);
    EXPECT_DOUBLE_EQ(site.location.time_zone_h, -6);
    EXPECT_DOUBLE_EQ(site.elevation_m, 201);
    EXPECT_EQ(chicago().hours.size(), 8760u);
    EXPECT_FALSE(chicago().has_leap_day());
}

TEST(Epw, ReadsTheShippedFilesRecordsAtKnownLines) {
    const std::vector<WeatherHour>& hours = chicago().hours;
    // Line 9, 1/1 hour 1: night, every solar field 0.
    EXPECT_EQ(hours[0].line, 9);
    EXPECT_EQ(hours[0].direct_normal_w_m2, 0);
    EXPECT_EQ(hours[0].diffuse_horizontal_lx, 0);
    // Line 20, 1/1 hour 12: 364, 521, 144 W/m²; 38026, 50467, 16854 lx.
    const WeatherHour& noon = hours[11];
    EXPECT_EQ(noon.line, 20);
    EXPECT_EQ(noon.month, 1);
    EXPECT_EQ(noon.day, 1);
    EXPECT_EQ(noon.hour, 12);
    EXPECT_EQ(noon.global_horizontal_w_m2, 364);
    EXPECT_EQ(noon.direct_normal_w_m2, 521);
    EXPECT_EQ(noon.diffuse_horizontal_w_m2, 144);
    EXPECT_EQ(noon.global_horizontal_lx, 38026);
    EXPECT_EQ(noon.direct_normal_lx, 50467);
    EXPECT_EQ(noon.diffuse_horizontal_lx, 16854);
    // Line 4125, 6/21 hour 13: 895, 734, 205 W/m²; 96600, 75500, 25700 lx.
    const WeatherHour& summer = hours[4116];
    EXPECT_EQ(summer.line, 4125);
    EXPECT_EQ(summer.month, 6);
    EXPECT_EQ(summer.day, 21);
    EXPECT_EQ(summer.hour, 13);
    EXPECT_EQ(summer.direct_normal_w_m2, 734);
    EXPECT_EQ(summer.diffuse_horizontal_w_m2, 205);
    EXPECT_EQ(summer.direct_normal_lx, 75500);
    EXPECT_EQ(summer.diffuse_horizontal_lx, 25700);
    // Line 8768, the last: 12/31 hour 24.
    EXPECT_EQ(hours.back().line, 8768);
    EXPECT_EQ(hours.back().month, 12);
    EXPECT_EQ(hours.back().day, 31);
    EXPECT_EQ(hours.back().hour, 24);
}

TEST(Epw, TakesTheSunAtMidHourInStandardTime) {
    // gensky's own declination and equation-of-time series (Radiance sun.c), at the same
    // mid-hour in standard time: an independent algorithm, but a coarse one (its declination
    // is 0.85° low on 21 March: the sun 0.64° apart at 6:30), so within 1°. A wrong time zone
    // or longitude sign, or the hour's end instead of its middle, moves the sun by 2–15°.
    const Weather& w = chicago();
    for (std::size_t index : {11u, 1902u, 4116u, 6177u}) {
        const WeatherHour& h = w.hours[index];
        const SolarAngles ours = sun_position(w, index);
        const SolarAngles gensky =
            solar_position_gensky(w.site.location, h.month, h.day, h.hour - 0.5, false);
        SCOPED_TRACE(fmt::format("{}/{} hour {}", h.month, h.day, h.hour));
        EXPECT_NEAR(ours.altitude_deg, gensky.altitude_deg, 1.0);
        EXPECT_NEAR(ours.azimuth_deg, gensky.azimuth_deg, 1.0);
    }
    // 1/1 hour 12 is 11:30 CST, about 11:35 solar time at 87.92° W: the sun just east of
    // south, at 90° − 41.98° − 23.0° ≈ 25° (its declination then).
    const SolarAngles noon = sun_position(w, 11);
    EXPECT_NEAR(noon.altitude_deg, 24.9, 0.3);
    EXPECT_GT(noon.azimuth_deg, 170);
    EXPECT_LT(noon.azimuth_deg, 180);
    EXPECT_EQ(day_of_year(w, 4116), 172);
}

// ---- A synthetic year, edited line by line ---------------------------------------------------

constexpr const char* k_header = "LOCATION,Somewhere,XX,YYY,test,000000,40.0,-105.0,-7.0,1600.0\n"
                                 "DESIGN CONDITIONS,0\n"
                                 "TYPICAL/EXTREME PERIODS,0\n"
                                 "GROUND TEMPERATURES,0\n"
                                 "HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0\n"
                                 "COMMENTS 1,synthetic\n"
                                 "COMMENTS 2,synthetic\n"
                                 "DATA PERIODS,1,1,Data,Sunday, 1/ 1,12/31\n";

/// One record of 35 fields with the given date and radiation.
std::string record(int month, int day, int hour, const std::string& dni = "100",
                   const std::string& dhi = "50") {
    return fmt::format("1999,{},{},{},0,?9?9,10.0,5.0,70,99000,0,0,300,120,{},{},13000,9000,6000,"
                       "2000,180,2.0,5,5,16.0,77777,9,999999999,10,0.1,0,88,0.2,0.0,1.0",
                       month, day, hour, dni, dhi);
}

/// The records of a whole year, 29 February included if \p leap.
std::vector<std::string> year_records(bool leap = false) {
    constexpr int days[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    std::vector<std::string> lines;
    for (int month = 1; month <= 12; ++month)
        for (int day = 1; day <= days[month - 1] + (leap && month == 2); ++day)
            for (int hour = 1; hour <= 24; ++hour)
                lines.push_back(record(month, day, hour));
    return lines;
}

std::string epw_text(const std::vector<std::string>& records, const std::string& header = k_header,
                     const char* newline = "\n") {
    std::string text = header;
    for (const std::string& line : records)
        text += line + newline;
    return text;
}

/// The InputError \p text raises, with its line and key checked.
void expect_refused(const std::string& text, int line, const std::string& key,
                    const std::string& fragment) {
    try {
        parse_epw(text, "test.epw");
        ADD_FAILURE() << "accepted; expected an error at line " << line;
    } catch (const InputError& e) {
        EXPECT_EQ(e.line(), line) << e.what();
        EXPECT_EQ(e.key(), key) << e.what();
        EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line";
        EXPECT_EQ(std::string(e.what()).rfind("test.epw:", 0), 0u) << e.what();
    }
}

TEST(Epw, ReadsASyntheticYearWithCrLfLineEnds) {
    const Weather w = parse_epw(epw_text(year_records(), k_header, "\r\n"), "test.epw");
    ASSERT_EQ(w.hours.size(), 8760u);
    EXPECT_EQ(w.site.location.longitude_deg, -105);
    EXPECT_EQ(w.hours[5].direct_normal_w_m2, 100);
    EXPECT_EQ(w.hours[5].diffuse_horizontal_lx, 6000);
}

TEST(Epw, ReadsALeapYearAsRadianceDoes) {
    const Weather w = parse_epw(epw_text(year_records(true)), "leap.epw");
    ASSERT_EQ(w.hours.size(), 8784u);
    EXPECT_TRUE(w.has_leap_day());
    const std::size_t feb29 = (31 + 28) * 24, march1 = feb29 + 24;
    EXPECT_EQ(w.hours[feb29].day, 29);
    EXPECT_EQ(day_of_year(w, feb29), 60);
    EXPECT_EQ(day_of_year(w, march1), 61); // gendaymtx: jdate(3, 1) + 1 after a leap day
    const SolarAngles sun = sun_position(w, feb29 + 12);
    const SolarAngles expected = solar_position(w.site.location, LocalTime{2024, 2, 29, 12.5});
    EXPECT_DOUBLE_EQ(sun.altitude_deg, expected.altitude_deg);
}

TEST(Epw, KeepsMissingOptionalFieldsUnset) {
    std::vector<std::string> records = year_records();
    // Global horizontal radiation 9999, direct illuminance 999999, diffuse illuminance blank.
    records[3] = "1999,1,1,4,0,?,10,5,70,99000,0,0,300,9999,100,50,13000,999999,,2000,180,2,5,5,"
                 "16,77777,9,999999999,10,0.1,0,88,0.2,0.0,1.0";
    const Weather w = parse_epw(epw_text(records), "test.epw");
    EXPECT_FALSE(w.hours[3].global_horizontal_w_m2);
    EXPECT_FALSE(w.hours[3].direct_normal_lx);
    EXPECT_FALSE(w.hours[3].diffuse_horizontal_lx);
    EXPECT_EQ(w.hours[3].global_horizontal_lx, 13000);
}

TEST(Epw, AcceptsRecordsWithoutTheLastThreeFields) {
    std::vector<std::string> records = year_records();
    records[0] = record(1, 1, 1);
    records[0].resize(records[0].rfind(",0.2,0.0,1.0")); // 32 fields, as older files
    EXPECT_NO_THROW(parse_epw(epw_text(records), "test.epw"));
}

struct RecordEdit {
    std::string name;
    std::size_t record;   ///< 0-based record index
    std::string replaced; ///< the new line
    std::string key;      ///< the error's key
    std::string fragment; ///< in the message
};

class EpwRecordErrors : public testing::TestWithParam<RecordEdit> {};

TEST_P(EpwRecordErrors, NameTheLineAndField) {
    const RecordEdit& edit = GetParam();
    std::vector<std::string> records = year_records();
    records[edit.record] = edit.replaced;
    expect_refused(epw_text(records), int(edit.record) + 9, edit.key, edit.fragment);
}

INSTANTIATE_TEST_SUITE_P(
    Epw, EpwRecordErrors,
    testing::Values(
        RecordEdit{"too_few_fields", 99, "1999,1,5,4,0,?,10,5,70", "", "9 comma-separated fields"},
        RecordEdit{"too_many_fields", 99, record(1, 5, 4) + ",1,2", "", "37 comma-separated"},
        RecordEdit{"dni_not_a_number", 99, record(1, 5, 4, "abc"),
                   "field 15 (direct normal radiation)", "'abc' is not a number"},
        RecordEdit{"dni_missing", 99, record(1, 5, 4, "9999"), "field 15 (direct normal radiation)",
                   "missing"},
        RecordEdit{"dhi_blank", 99, record(1, 5, 4, "100", ""),
                   "field 16 (diffuse horizontal radiation)", "missing"},
        RecordEdit{"dhi_negative", 99, record(1, 5, 4, "100", "-3"),
                   "field 16 (diffuse horizontal radiation)", "negative"},
        RecordEdit{"month_13", 99, record(13, 5, 4), "field 2 (month)", "[1, 12]"},
        RecordEdit{"february_30", 60 * 24, record(2, 30, 1), "field 3 (day)", "[1, 29]"},
        RecordEdit{"hour_0", 99, record(1, 5, 0), "field 4 (hour)", "[1, 24]"},
        RecordEdit{"hour_25", 99, record(1, 5, 25), "field 4 (hour)", "[1, 24]"},
        RecordEdit{"hour_fraction", 99, record(1, 5, 4).replace(9, 1, "4.5"), "field 4 (hour)",
                   "whole number"},
        RecordEdit{"out_of_sequence", 99, record(1, 5, 5), "", "expected 1/5 hour 4"},
        RecordEdit{"a_duplicate", 99, record(1, 5, 3), "", "expected 1/5 hour 4"},
        RecordEdit{"leap_day_out_of_place", 99, record(2, 29, 1), "", "expected 1/5 hour 4"}),
    [](const auto& info) { return info.param.name; });

TEST(Epw, RefusesAShortOrLongYear) {
    std::vector<std::string> records = year_records();
    records.pop_back();
    expect_refused(epw_text(records), 8767, "", "ends after 8759 hourly records");
    records = year_records();
    records.push_back(record(12, 31, 24));
    expect_refused(epw_text(records), 8769, "", "after 31 December hour 24");
}

TEST(Epw, RefusesABadHeader) {
    const std::vector<std::string> records = year_records();
    std::string header = k_header;
    expect_refused(epw_text(records, header.substr(header.find('\n') + 1)), 1, "",
                   "expected the EPW header line 'LOCATION");
    header = k_header;
    header.replace(header.find("40.0"), 4, "95");
    expect_refused(epw_text(records, header), 1, "field 7 (latitude)", "outside [-90, 90]");
    header = k_header;
    header.replace(header.find(",1600.0"), 7, "");
    expect_refused(epw_text(records, header), 1, "", "LOCATION has 9 fields");
    header = k_header;
    header.replace(header.find("DATA PERIODS,1,1"), 16, "DATA PERIODS,1,4");
    expect_refused(epw_text(records, header), 8, "field 3 (records per hour)", "only hourly");
    header = k_header;
    header.replace(header.find("COMMENTS 2"), 10, "REMARKS");
    expect_refused(epw_text(records, header), 7, "", "'COMMENTS 2");
}

TEST(Epw, RefusesAFileThatIsNotThere) {
    EXPECT_THROW(read_epw(test::temp_dir("epw") + "/absent.epw"), InputError);
}

} // namespace
} // namespace penumbra::annual
