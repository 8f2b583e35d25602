#pragma once
// EnergyPlus weather files (EPW) for annual daylight (issue #31): the site from the LOCATION
// header and the year's hourly solar records, as the EnergyPlus "Auxiliary Programs" data
// dictionary defines them. Only the fields daylight needs are read and checked; docs/annual.md
// lists the rules (missing values, leap years, the hour's sun).

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/solar_position.h"

namespace penumbra::annual {

/// \brief The site of an EPW file, from its LOCATION header line.
struct WeatherSite {
    std::string city, region, country, source, wmo;
    /// Latitude north-positive, longitude and time zone east-positive (EPW's conventions, and
    /// core's solar_position()).
    Location location;
    double elevation_m = 0;
};

/// \brief One hourly record: the hour ending at \p hour (1–24) of \p month / \p day, local
///        standard time (EPW files carry no daylight saving). Radiometric values are the hour's
///        mean irradiance (W/m²; EPW gives Wh/m² per hour), photometric ones its mean lx.
struct WeatherHour {
    int line = 0; ///< 1-based line of the record in its file
    int month = 1, day = 1, hour = 1;
    std::optional<double> global_horizontal_w_m2; ///< field 14; unset if missing
    double direct_normal_w_m2 = 0;                ///< field 15 (required)
    double diffuse_horizontal_w_m2 = 0;           ///< field 16 (required)
    std::optional<double> global_horizontal_lx;   ///< field 17; unset if missing
    std::optional<double> direct_normal_lx;       ///< field 18; unset if missing
    std::optional<double> diffuse_horizontal_lx;  ///< field 19; unset if missing
};

/// \brief A year of hourly weather: 8 760 records from 1 January hour 1 to 31 December hour
///        24, or 8 784 when the file includes 29 February.
struct Weather {
    std::string file; ///< as given to read_epw(), for messages
    WeatherSite site;
    std::vector<WeatherHour> hours;

    /// \brief True for a year of 8 784 hours (29 February included).
    bool has_leap_day() const;
};

/// \brief Reads the EPW file \p path.
/// \throws InputError with the file, line and field for anything the rules of docs/annual.md
///         refuse: a missing or misplaced header line, a wrong field count, a field that is not
///         a number or is out of range, a missing direct-normal or diffuse-horizontal
///         radiation, records out of sequence, not a whole year.
Weather read_epw(const std::string& path);

/// \brief The same for the text \p text of a file named \p file (for messages).
Weather parse_epw(std::string_view text, const std::string& file);

/// \brief The sun's position at the middle of hour \p index of \p weather (hour − 0.5, local
///        standard time, as Radiance's epw2wea and gendaymtx take it), at the site. The file's
///        year field is ignored: the date is taken in 2025, or in 2024 for a file with
///        29 February, so that the calendar matches.
SolarAngles sun_position(const Weather& weather, std::size_t index);

/// \brief Day of the year of hour \p index (1 = 1 January; 60 = 29 February or 1 March).
int day_of_year(const Weather& weather, std::size_t index);

} // namespace penumbra::annual
