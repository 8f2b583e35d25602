// The EPW reader: the eight header lines in the order the EnergyPlus data dictionary gives
// them, then one record per hour from 1 January hour 1 to 31 December hour 24. Field numbers
// are the dictionary's, 1-based: 1 year, 2 month, 3 day, 4 hour, 5 minute, 6 data source
// flags, 7–13 temperatures, humidity, pressure, extraterrestrial and infrared radiation,
// 14 global horizontal, 15 direct normal, 16 diffuse horizontal radiation (Wh/m²), 17 global
// horizontal, 18 direct normal, 19 diffuse horizontal illuminance (lx), 20 zenith luminance,
// … 35 liquid precipitation quantity.

#include "annual/epw.h"

#include <array>
#include <cstddef>
#include <strings.h>

#include <fmt/format.h>

#include "core/error.h"
#include "core/files.h"

#include "epw_fields.h"

namespace penumbra::annual {

namespace {

/// The header records, one per line, in the dictionary's order.
constexpr std::array<const char*, 8> k_headers = {
    "LOCATION",
    "DESIGN CONDITIONS",
    "TYPICAL/EXTREME PERIODS",
    "GROUND TEMPERATURES",
    "HOLIDAYS/DAYLIGHT SAVING", // the dictionary's spelling; files write SAVINGS (a prefix)
    "COMMENTS 1",
    "COMMENTS 2",
    "DATA PERIODS"};

// The dictionary defines 35 fields; files written before its last three fields were added end
// after field 32 (days since last snowfall), and Radiance's reader accepts them too.
constexpr std::size_t k_min_fields = 32;
constexpr std::size_t k_max_fields = 35;

// Missing-value codes: radiation at and above 9999 Wh/m², illuminance at and above 999 900 lx.
constexpr double k_missing_radiation = 9999;
constexpr double k_missing_illuminance = 999900;

constexpr int k_year_hours = 8760;
constexpr int k_leap_year_hours = 8784;

/// The lines of \p text, without their '\n'.
std::vector<std::string_view> split_lines(std::string_view text) {
    std::vector<std::string_view> lines;
    while (!text.empty()) {
        const std::size_t end = text.find('\n');
        lines.push_back(text.substr(0, end));
        if (end == std::string_view::npos)
            break;
        text.remove_prefix(end + 1);
    }
    return lines;
}

/// Whether the first field of \p line begins with \p keyword, ignoring case (as Radiance).
bool starts_with_keyword(std::string_view line, std::string_view keyword) {
    const std::string_view first = trim(split_fields(line).front());
    return first.size() >= keyword.size() &&
           strncasecmp(first.data(), keyword.data(), keyword.size()) == 0;
}

WeatherSite parse_location(const EpwLine& line) {
    if (line.field_count() != 10)
        line.fail(fmt::format("LOCATION has {} fields, expected 10 (LOCATION, city, region, "
                              "country, source, WMO, latitude, longitude, time zone, elevation)",
                              line.field_count()));
    WeatherSite site;
    site.city = trim(line.field(2));
    site.region = trim(line.field(3));
    site.country = trim(line.field(4));
    site.source = trim(line.field(5));
    site.wmo = trim(line.field(6));
    const auto in_range = [&](std::size_t number, const char* name, double lo, double hi) {
        const double value = line.number(number, name);
        if (value < lo || value > hi)
            line.fail(number, name, fmt::format("{} is outside [{}, {}]", value, lo, hi));
        return value;
    };
    site.location.latitude_deg = in_range(7, "latitude", -90, 90);
    site.location.longitude_deg = in_range(8, "longitude", -180, 180);
    // The dictionary says [-12, 12]; real zones reach +14 (Kiribati).
    site.location.time_zone_h = in_range(9, "time zone", -12, 14);
    site.elevation_m = in_range(10, "elevation", -1000, 9999.9);
    return site;
}

void check_hourly(const EpwLine& line) {
    if (line.field_count() < 3)
        line.fail("DATA PERIODS needs the number of periods and of records per hour");
    if (line.integer(3, "records per hour", 1, 60) != 1)
        line.fail(3, "records per hour", "only hourly weather files are read");
}

/// The header's eight lines: the site, and a check that the records are hourly.
WeatherSite parse_header(const std::vector<std::string_view>& lines, const std::string& file) {
    WeatherSite site;
    for (std::size_t i = 0; i < k_headers.size(); ++i) {
        const int number = int(i) + 1;
        if (i >= lines.size() || !starts_with_keyword(lines[i], k_headers[i]))
            throw InputError(
                file, "", fmt::format("expected the EPW header line '{},…'", k_headers[i]), number);
        const EpwLine line(file, number, lines[i]);
        if (i == 0)
            site = parse_location(line);
        if (i + 1 == k_headers.size())
            check_hourly(line);
    }
    return site;
}

int days_in_month(int month, bool leap) {
    constexpr int days[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    return days[month - 1] + (leap && month == 2 ? 1 : 0);
}

/// A record's place in the year, and the hour that must follow it.
struct HourOfYear {
    int month = 1, day = 1, hour = 1;

    bool operator==(const HourOfYear&) const = default;
    bool past_the_year() const { return month > 12; }
    HourOfYear next(bool leap) const {
        if (hour < 24)
            return {month, day, hour + 1};
        if (day < days_in_month(month, leap))
            return {month, day + 1, 1};
        return {month + 1, 1, 1};
    }
};

WeatherHour parse_record(const EpwLine& line) {
    if (line.field_count() < k_min_fields || line.field_count() > k_max_fields)
        line.fail(fmt::format("{} comma-separated fields, expected {} to {} (an EPW record)",
                              line.field_count(), k_min_fields, k_max_fields));
    line.number(1, "year"); // ignored, but part of the format
    WeatherHour h;
    h.line = line.line();
    h.month = line.integer(2, "month", 1, 12);
    h.day = line.integer(3, "day", 1, days_in_month(h.month, true));
    h.hour = line.integer(4, "hour", 1, 24);
    line.integer(5, "minute", 0, 60);
    h.global_horizontal_w_m2 =
        line.measurement(14, "global horizontal radiation", k_missing_radiation);
    const auto required = [&](std::size_t number, const char* name) {
        const std::optional<double> value = line.measurement(number, name, k_missing_radiation);
        if (!value)
            line.fail(number, name, "missing (blank or 9999), and the sky needs it");
        return *value;
    };
    h.direct_normal_w_m2 = required(15, "direct normal radiation");
    h.diffuse_horizontal_w_m2 = required(16, "diffuse horizontal radiation");
    h.global_horizontal_lx =
        line.measurement(17, "global horizontal illuminance", k_missing_illuminance);
    h.direct_normal_lx = line.measurement(18, "direct normal illuminance", k_missing_illuminance);
    h.diffuse_horizontal_lx =
        line.measurement(19, "diffuse horizontal illuminance", k_missing_illuminance);
    return h;
}

/// Checks that \p got is the hour after the previous record (\p expected), letting
/// 29 February in after 28 February hour 24; sets \p leap when it does.
void check_sequence(const EpwLine& line, const HourOfYear& expected, const HourOfYear& got,
                    bool& leap) {
    if (expected.past_the_year())
        line.fail("a record after 31 December hour 24: an EPW year ends there");
    if (got == expected)
        return;
    if (!leap && expected == HourOfYear{3, 1, 1} && got == HourOfYear{2, 29, 1}) {
        leap = true;
        return;
    }
    line.fail(fmt::format("the record of {}/{} hour {}, expected {}/{} hour {}: records run hour "
                          "by hour from 1/1 hour 1 to 12/31 hour 24",
                          got.month, got.day, got.hour, expected.month, expected.day,
                          expected.hour));
}

} // namespace

bool Weather::has_leap_day() const {
    return hours.size() == k_leap_year_hours;
}

Weather parse_epw(std::string_view text, const std::string& file) {
    const std::vector<std::string_view> lines = split_lines(text);
    Weather weather;
    weather.file = file;
    weather.site = parse_header(lines, file);
    weather.hours.reserve(k_year_hours);
    HourOfYear expected;
    bool leap = false;
    for (std::size_t i = k_headers.size(); i < lines.size(); ++i) {
        if (trim(lines[i]).empty() || trim(lines[i]) == "\r")
            continue;
        const EpwLine line(file, int(i) + 1, lines[i]);
        WeatherHour hour = parse_record(line);
        const HourOfYear got{hour.month, hour.day, hour.hour};
        check_sequence(line, expected, got, leap);
        expected = got.next(leap);
        weather.hours.push_back(hour);
    }
    if (!expected.past_the_year())
        throw InputError(file, "",
                         fmt::format("the file ends after {} hourly records, before {}/{} hour "
                                     "{}: an EPW year has {} ({} with 29 February)",
                                     weather.hours.size(), expected.month, expected.day,
                                     expected.hour, k_year_hours, k_leap_year_hours),
                         int(lines.size()));
    return weather;
}

Weather read_epw(const std::string& path) {
    return parse_epw(read_text_file(path), path);
}

namespace {

/// The year the file's dates are taken in (its own year field is ignored, as Radiance does):
/// one whose calendar has 29 February exactly when the file does.
int reference_year(const Weather& weather) {
    return weather.has_leap_day() ? 2024 : 2025;
}

} // namespace

int day_of_year(const Weather& weather, std::size_t index) {
    const WeatherHour& h = weather.hours.at(index);
    return penumbra::day_of_year(reference_year(weather), h.month, h.day);
}

SolarAngles sun_position(const Weather& weather, std::size_t index) {
    const WeatherHour& h = weather.hours.at(index);
    const LocalTime mid_hour{reference_year(weather), h.month, h.day, h.hour - 0.5};
    return solar_position(weather.site.location, mid_hour);
}

} // namespace penumbra::annual
