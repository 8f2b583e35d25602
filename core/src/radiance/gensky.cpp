// gensky(1) re-read: its argument syntax and its formulas (Radiance's gensky.c), written anew.
// Radiance's axes: x east, y north, z up; gensky's azimuths are measured from south, positive
// toward west.

#include "gensky.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <optional>

#include <fmt/format.h>

#include "core/solar_position.h"

namespace penumbra::radiance {

namespace {

constexpr double k_pi = 3.14159265358979323846;
constexpr double k_rad = k_pi / 180.0;
/// Radiance's luminous efficacies (color.h): skylight is taken as D65 (203 lm/W) and the solar
/// beam as illuminant B (208 lm/W) when gensky turns its luminance formulas into radiance.
constexpr double k_sky_efficacy = 203.0;
constexpr double k_sun_efficacy = 208.0;
/// Solid angle gensky takes for the solar disc, sr (a 0.5° disc: 5.98e-5).
constexpr double k_gensky_sun_solid_angle = 6e-5;

constexpr int k_clear = 1, k_overcast = 2, k_uniform = 3, k_intermediate = 4;

/// How a radiance option was given: not at all, as a radiance (-b, -r), or as an irradiance
/// (-B, -R).
enum class Given { no, radiance, irradiance };

struct Arguments {
    std::optional<int> month, day; ///< unset with -ang
    double hour = 12;
    bool solar_time = false;
    double altitude = 0, azimuth = 0; ///< radians, gensky's azimuth (from south, west > 0)
    int sky_type = k_clear;
    bool sun = true;
    Given zenith_given = Given::no, sun_given = Given::no;
    double zenith = 0, sun_value = 0;
    double turbidity = 2.45;
    double ground_reflectance = 0.2;
    // gensky's site: 0.66 rad north, 2.13 rad west, meridian 120° west.
    Location site{.latitude_deg = 0.66 / k_rad, .longitude_deg = -2.13 / k_rad, .time_zone_h = -8};
};

class Words {
public:
    explicit Words(const Command& command) : command_(command) {}
    bool more() const { return next_ < command_.words.size(); }
    const std::string& take() {
        if (!more())
            fail(command_.where, "!gensky: too few arguments (gensky month day hour [options])");
        return command_.words[next_++];
    }
    double number(const std::string& what) {
        const std::string& word = take();
        char* end = nullptr;
        const double v = std::strtod(word.c_str(), &end);
        if (*end != '\0' || word.empty() || !std::isfinite(v))
            fail(command_.where, fmt::format("!gensky: {} must be a number, got '{}'", what, word));
        return v;
    }
    int integer(const std::string& what, int lo, int hi) {
        const double v = number(what);
        if (v != std::floor(v) || v < lo || v > hi)
            fail(command_.where, fmt::format("!gensky: {} must be an integer in [{}, {}], got {}",
                                             what, lo, hi, v));
        return int(v);
    }
    const SourceLine& where() const { return command_.where; }

private:
    const Command& command_;
    std::size_t next_ = 1; // after "gensky"
};

/// "[+]H", "[+]H.h" or "[+]H:MM"; a leading + means local solar time.
void parse_hour(const std::string& word, const SourceLine& where, Arguments& args) {
    std::string text = word;
    args.solar_time = text.starts_with('+');
    if (args.solar_time)
        text.erase(0, 1);
    const std::size_t colon = text.find(':');
    const std::string hours = text.substr(0, colon); // named: `end` points into it
    char* end = nullptr;
    double hour = std::strtod(hours.c_str(), &end);
    bool ok = *end == '\0' && !hours.empty();
    if (colon != std::string::npos) {
        const double minutes = std::strtod(text.c_str() + colon + 1, &end);
        ok = ok && *end == '\0' && minutes >= 0 && minutes < 60;
        hour += minutes / 60.0;
    }
    if (!ok || !(hour >= 0 && hour <= 24))
        fail(where, fmt::format("!gensky: the hour must be [+]H, [+]H.h or [+]H:MM in [0, 24] "
                                "(time-zone names are not supported), got '{}'",
                                word));
    args.hour = hour;
}

void parse_when(Words& in, Arguments& args) {
    const std::string& first = in.take();
    if (first == "-ang") {
        args.altitude = in.number("the solar altitude") * k_rad;
        args.azimuth = in.number("the solar azimuth") * k_rad;
        return;
    }
    char* end = nullptr;
    const double month = std::strtod(first.c_str(), &end);
    if (*end != '\0' || month != std::floor(month) || month < 1 || month > 12)
        fail(in.where(), fmt::format("!gensky: the month must be in [1, 12], got '{}'", first));
    args.month = int(month);
    args.day = in.integer("the day", 1, 31);
    parse_hour(in.take(), in.where(), args);
}

/// One option; false if \p option is not one of gensky's.
bool parse_option(const std::string& option, Words& in, Arguments& args) {
    const bool plus = option[0] == '+';
    const std::string name = option.substr(1);
    if (name == "s" || name == "i") {
        args.sky_type = name == "s" ? k_clear : k_intermediate;
        args.sun = plus;
    } else if (plus) {
        return false;
    } else if (name == "c" || name == "u") {
        args.sky_type = name == "c" ? k_overcast : k_uniform;
    } else if (name == "b" || name == "B") {
        args.zenith_given = name == "b" ? Given::radiance : Given::irradiance;
        args.zenith = in.number("-" + name);
    } else if (name == "r" || name == "R") {
        args.sun_given = name == "r" ? Given::radiance : Given::irradiance;
        args.sun_value = in.number("-" + name);
    } else if (name == "t") {
        args.turbidity = in.number("-t");
    } else if (name == "g") {
        args.ground_reflectance = in.number("-g");
    } else if (name == "a") {
        args.site.latitude_deg = in.number("-a");
    } else if (name == "o") {
        args.site.longitude_deg = -in.number("-o"); // gensky: west-positive
    } else if (name == "m") {
        args.site.time_zone_h = -in.number("-m") / 15.0; // meridian, west-positive
    } else {
        return false;
    }
    return true;
}

Arguments parse_arguments(const Command& command) {
    Words in(command);
    Arguments args;
    parse_when(in, args);
    while (in.more()) {
        const std::string option = in.take();
        if (option.size() < 2 || (option[0] != '-' && option[0] != '+') ||
            !parse_option(option, in, args))
            fail(command.where,
                 fmt::format("!gensky: option '{}' is not supported (supported: -s, +s, -c, -u, "
                             "-i, +i, -b, -B, -r, -R, -t, -g, -a, -o, -m)",
                             option));
    }
    return args;
}

/// gensky's polynomial for E0·F2/L0 of the clear (or intermediate) sky, in the altitude.
double sky_normalisation_polynomial(int sky_type, double altitude) {
    static constexpr double clear[5] = {2.766521, 0.547665, -0.369832, 0.009237, 0.059229};
    static constexpr double intermediate[5] = {3.5556, -2.7152, -1.3081, 1.0660, 0.60227};
    const double* c = sky_type == k_intermediate ? intermediate : clear;
    const double x = (altitude - k_pi / 4.0) / (k_pi / 4.0);
    return c[0] + x * (c[1] + x * (c[2] + x * (c[3] + x * c[4])));
}

/// The sky's horizontal irradiance over π times its zenith radiance ("normfactor"), and F2.
std::pair<double, double> normalisation(int sky_type, double altitude, const Vec3& sun) {
    if (sky_type == k_uniform)
        return {1.0, 0.0};
    if (sky_type == k_overcast)
        return {0.777778, 0.0}; // 7/9, rounded as gensky rounds it
    const double f2 = sky_type == k_clear
                          ? 0.274 * (0.91 + 10.0 * std::exp(-3.0 * (k_pi / 2.0 - altitude)) +
                                     0.45 * sun.z * sun.z)
                          : (2.739 + .9891 * std::sin(.3119 + 2.6 * altitude)) *
                                std::exp(-(k_pi / 2.0 - altitude) * (.4441 + 1.48 * altitude));
    return {sky_normalisation_polynomial(sky_type, altitude) / f2 / k_pi, f2};
}

/// gensky's zenith radiance without -b/-B: its luminance formulas (kcd/m²) over 203 lm/W.
double default_zenith_radiance(const Arguments& args, double altitude, const Vec3& sun) {
    const bool overcast = args.sky_type == k_overcast || args.sky_type == k_uniform;
    const double overcast_kcd = 8.6 * sun.z + .123;
    double kcd =
        overcast ? overcast_kcd : (1.376 * args.turbidity - 1.81) * std::tan(altitude) + 0.38;
    if (args.sky_type == k_intermediate)
        kcd = (kcd + overcast_kcd) / 2.0;
    return kcd < 0 ? 0.0 : kcd * 1000.0 / k_sky_efficacy;
}

double sun_radiance(const Arguments& args, const Vec3& sun) {
    if (args.sun_given == Given::irradiance)
        return args.sun_value / (k_gensky_sun_solid_angle * sun.z);
    if (args.sun_given == Given::radiance)
        return args.sun_value;
    const double b = 1.5e9 / k_sun_efficacy * (1.147 - .147 / std::max(sun.z, .16));
    return args.sky_type == k_intermediate ? b * 0.15 : b; // gensky's own "fudge factor"
}

void place_sun(Arguments& args) {
    if (!args.month)
        return;
    const SolarAngles angles =
        solar_position_gensky(args.site, *args.month, *args.day, args.hour, args.solar_time);
    args.altitude = angles.altitude_deg * k_rad;
    args.azimuth = (angles.azimuth_deg - 180.0) * k_rad;
}

} // namespace

GenskyResult run_gensky(const Command& command) {
    Arguments args = parse_arguments(command);
    place_sun(args);
    const bool overcast = args.sky_type == k_overcast || args.sky_type == k_uniform;
    if (!overcast && args.altitude > 87.0 * k_rad)
        args.altitude = 87.0 * k_rad; // gensky keeps the clear sky's formulas off the zenith
    GenskyResult r;
    r.sky_type = args.sky_type;
    r.sun_direction =
        Vec3(-std::sin(args.azimuth) * std::cos(args.altitude),
             -std::cos(args.azimuth) * std::cos(args.altitude), std::sin(args.altitude));
    const auto [norm, f2] = normalisation(args.sky_type, args.altitude, r.sun_direction);
    r.normalisation = f2;
    r.zenith_radiance = args.zenith_given == Given::irradiance ? args.zenith / (norm * k_pi)
                        : args.zenith_given == Given::radiance
                            ? args.zenith
                            : default_zenith_radiance(args, args.altitude, r.sun_direction);
    r.ambient_level = r.zenith_radiance * norm;
    double ground = r.ambient_level;
    r.sun = args.sun && !overcast && r.sun_direction.z > 0 &&
            (args.sun_given == Given::no || args.sun_value > 0);
    if (r.sun) {
        r.sun_radiance = sun_radiance(args, r.sun_direction);
        ground += k_gensky_sun_solid_angle / k_pi * r.sun_radiance * r.sun_direction.z;
    }
    r.ground_radiance = ground * args.ground_reflectance;
    return r;
}

std::vector<Primitive> gensky_primitives(const GenskyResult& r, const SourceLine& where) {
    std::vector<Primitive> out;
    const Vec3& d = r.sun_direction;
    if (r.sun) {
        const double s = r.sun_radiance;
        out.push_back({"void", "light", "solar", {}, {}, {s, s, s}, where});
        out.push_back({"solar", "source", "sun", {}, {}, {d.x, d.y, d.z, 0.5}, where});
    }
    Primitive sky{"void", "brightfunc", "skyfunc", {"skybr", "skybright.cal"}, {}, {}, where};
    sky.reals = {double(r.sky_type), r.zenith_radiance, r.ground_radiance};
    if (r.sky_type == k_clear || r.sky_type == k_intermediate)
        sky.reals.insert(sky.reals.end(), {r.normalisation, d.x, d.y, d.z});
    out.push_back(std::move(sky));
    return out;
}

} // namespace penumbra::radiance
