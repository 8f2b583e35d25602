// gendaylit(1) re-read: its argument syntax (Radiance's gendaylit.c), with Penumbra's own Perez
// sky and sun (perez_sky_and_sun) in place of gendaylit's computation. Radiance's axes: x east,
// y north, z up.

#include "gendaylit.h"

#include "command_words.h"

#include <array>
#include <cmath>
#include <cstdlib>
#include <optional>

#include <fmt/format.h>

#include "core/sky.h"
#include "core/solar_position.h"

#include "sky_models.h"

namespace penumbra::radiance {

namespace {

constexpr double k_pi = 3.14159265358979323846;

/// What the two numbers after -W, -L or -G are.
enum class Components { direct_normal_w_m2, direct_normal_lx, direct_horizontal_w_m2 };

struct Arguments {
    int month = 1, day = 1;
    double hour = 12;
    bool solar_time = false;
    std::optional<Components> components;
    double direct = 0, diffuse = 0;
    bool sun = true;
    double ground_reflectance = 0.2;
    // gendaylit's default site is gensky's: 0.66 rad north, 2.13 rad west, meridian 120° west.
    Location site{
        .latitude_deg = 0.66 * 180 / k_pi, .longitude_deg = -2.13 * 180 / k_pi, .time_zone_h = -8};
};

using Words = CommandWords;

/// The hour argument into \p args.
void parse_hour(const std::string& word, const Words& in, Arguments& args) {
    const CommandHour hour = parse_command_hour(word, in);
    args.hour = hour.hour;
    args.solar_time = hour.solar_time;
}

/// One option; false if \p option is not one Penumbra reads.
bool parse_option(const std::string& option, Words& in, Arguments& args) {
    const auto components = [&](Components c) {
        args.components = c;
        args.direct = in.number(option + "'s direct value");
        args.diffuse = in.number(option + "'s diffuse value");
        if (!(args.direct >= 0 && args.diffuse >= 0))
            fail(in.where(), fmt::format("!gendaylit: {}'s values must be >= 0", option));
    };
    if (option == "-W")
        components(Components::direct_normal_w_m2);
    else if (option == "-L")
        components(Components::direct_normal_lx);
    else if (option == "-G")
        components(Components::direct_horizontal_w_m2);
    else if (option == "-s")
        args.sun = false;
    else if (option == "-g")
        args.ground_reflectance = in.number("-g");
    else if (option == "-a")
        args.site.latitude_deg = in.number("-a");
    else if (option == "-o")
        args.site.longitude_deg = -in.number("-o"); // west-positive, as gensky
    else if (option == "-m")
        args.site.time_zone_h = -in.number("-m") / 15.0; // meridian, west-positive
    else
        return false;
    return true;
}

Arguments parse_arguments(const Command& command) {
    Words in(command, "gendaylit month day hour -W|-L|-G direct diffuse [options]");
    Arguments args;
    if (in.more() && command.words[1] == "-ang")
        fail(command.where, "!gendaylit: -ang is not supported (the Perez sky needs the day of "
                            "the year: give month day hour)");
    args.month = in.integer("the month", 1, 12);
    args.day = in.integer("the day", 1, 31);
    parse_hour(in.take(), in, args);
    while (in.more()) {
        const std::string option = in.take();
        if (!parse_option(option, in, args))
            fail(command.where, fmt::format("!gendaylit: option '{}' is not supported "
                                            "(supported: -W, -L, -G, -s, -g, -a, -o, -m)",
                                            option));
    }
    if (!args.components)
        fail(command.where, "!gendaylit: the sky needs -W, -L or -G (direct and diffuse)");
    if (!(args.ground_reflectance >= 0 && args.ground_reflectance <= 1))
        fail(command.where, "!gendaylit: -g must be in [0, 1]");
    return args;
}

/// Day of the year, 1 on 1 January, for a year without 29 February (as gendaylit counts).
int day_of_year(int month, int day) {
    static constexpr std::array<int, 12> days_before{0,   31,  59,  90,  120, 151,
                                                     181, 212, 243, 273, 304, 334};
    return days_before[std::size_t(month - 1)] + day;
}

/// -G gives the direct light on the horizontal: its normal value is that over sin(altitude).
SolarComponents components_of(const Arguments& args, double sin_altitude, const SourceLine& where) {
    switch (*args.components) {
    case Components::direct_normal_w_m2:
        return SolarIrradiance{args.direct, args.diffuse};
    case Components::direct_normal_lx:
        return SolarIlluminance{args.direct, args.diffuse};
    case Components::direct_horizontal_w_m2:
        break;
    }
    if (sin_altitude <= 0 && args.direct > 0)
        fail(where, "!gendaylit: -G gives direct light with the sun below the horizon");
    return SolarIrradiance{sin_altitude > 0 ? args.direct / sin_altitude : 0.0, args.diffuse};
}

/// Solid angle of a cone of full angle \p diameter_deg, sr.
double cone_solid_angle(double diameter_deg) {
    return 2 * k_pi * (1 - std::cos(diameter_deg * k_pi / 360.0));
}

/// perezlum.cal's arguments for \p sky: its radiance is A1 l_v, so A1 is the zenith radiance
/// over l_v at the zenith. A black or uniform sky is l_v = 1 (all coefficients 0).
std::vector<double> perezlum_arguments(const Sky& sky) {
    PerezCoefficients k{0, 0, 0, 0, 0};
    if (const auto* perez = std::get_if<PerezSky>(&sky.model))
        k = perez_coefficients(*perez, std::acos(std::clamp(sky.sun_direction.z, 0.0, 1.0)));
    const double zenith = perez_luminance(k, 1.0, std::acos(sky.sun_direction.z));
    const double normalisation = zenith > 0 ? sky.zenith_radiance / zenith : 0.0;
    const Vec3& d = sky.sun_direction;
    return {normalisation, sky.ground_radiance.value_or(0), k.a, k.b, k.c, k.d, k.e, d.x, d.y, d.z};
}

} // namespace

std::vector<Primitive> gendaylit_primitives(const Command& command) {
    const Arguments args = parse_arguments(command);
    const SolarAngles angles =
        solar_position_gensky(args.site, args.month, args.day, args.hour, args.solar_time);
    const Compass radiance_axes{.up = {0, 0, 1}, .north = {0, 1, 0}};
    const Vec3 sun_direction = radiance_axes.direction(angles.altitude_deg, angles.azimuth_deg);
    // The ground is perez_sky_and_sun's ρ (E_diffuse + E_direct sin h) / (π 179 lm/W).
    // gendaylit approximates the same: its Perez zenith radiance times gensky's E_h / (π L_z)
    // of a CIE sky picked by ε, plus the sun through a 6.8e-5 sr disc, times ρ.
    const PerezSkyAndSun result = perez_sky_and_sun(
        components_of(args, sun_direction.z, command.where), radiance_axes, sun_direction,
        day_of_year(args.month, args.day), args.ground_reflectance, Horizon::radiance_blend);
    std::vector<Primitive> out;
    if (args.sun && result.sun) {
        const Sun& sun = *result.sun;
        const double radiance =
            double(sun.irradiance.r) / cone_solid_angle(sun.angular_diameter_deg);
        const Vec3& d = sun.direction;
        out.push_back(
            {"void", "light", "solar", {}, {}, {radiance, radiance, radiance}, command.where});
        out.push_back({"solar",
                       "source",
                       "sun",
                       {},
                       {},
                       {d.x, d.y, d.z, sun.angular_diameter_deg},
                       command.where});
    }
    out.push_back({"void",
                   "brightfunc",
                   "skyfunc",
                   {"skybright", "perezlum.cal"},
                   {},
                   perezlum_arguments(result.sky),
                   command.where});
    return out;
}

} // namespace penumbra::radiance
