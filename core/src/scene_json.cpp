// Scene file v1 parsing with nlohmann::json. One function reads each section; a Field carries
// the dotted key path so that every message names its key, and every object checks its keys
// against the known list (pbrt's ReportUnused, Mitsuba's unreferenced-property check).
// Value ranges that also apply to scenes built in code are checked by validate_scene.

#include "scene_json.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <set>
#include <span>
#include <string_view>
#include <utility>
#include <variant>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/solar_position.h"

namespace penumbra {

namespace {

using Json = nlohmann::ordered_json; // keeps the file's order of materials

/// A JSON value with its dotted key path ("materials.white.reflectance"), for messages.
class Field {
public:
    Field(const Json& value, std::string path, const std::string& file)
        : value_(value), path_(std::move(path)), file_(file) {}

    const std::string& path() const { return path_; }
    bool is_object() const { return value_.is_object(); }
    bool is_array() const { return value_.is_array(); }
    bool has(const std::string& key) const { return value_.contains(key); }

    [[noreturn]] void fail(const std::string& what) const { throw InputError(file_, path_, what); }

    Field child(const std::string& key) const {
        return Field(value_.at(key), path_.empty() ? key : path_ + "." + key, file_);
    }

    Field required(const std::string& key) const {
        if (!has(key))
            Field(value_, path_.empty() ? key : path_ + "." + key, file_)
                .fail("missing required key");
        return child(key);
    }

    /// Checks that this is an object whose keys are all in \p known.
    void expect_keys(std::initializer_list<std::string_view> known) const {
        if (!value_.is_object())
            fail(fmt::format("expected an object, got {}", value_.type_name()));
        for (const auto& item : value_.items())
            if (std::find(known.begin(), known.end(), item.key()) == known.end())
                child(item.key())
                    .fail(fmt::format("unknown key '{}' (known: {})", item.key(),
                                      fmt::join(known, ", ")));
    }

    /// The members of an object whose keys are names (materials).
    std::vector<std::pair<std::string, Field>> members() const {
        if (!value_.is_object())
            fail(fmt::format("expected an object, got {}", value_.type_name()));
        std::vector<std::pair<std::string, Field>> result;
        for (const auto& item : value_.items())
            result.emplace_back(item.key(), child(item.key()));
        return result;
    }

    std::size_t array_size() const {
        if (!value_.is_array())
            fail(fmt::format("expected an array, got {}", value_.type_name()));
        return value_.size();
    }

    Field element(std::size_t i) const {
        return Field(value_.at(i), fmt::format("{}[{}]", path_, i), file_);
    }

    double number() const {
        if (!value_.is_number())
            fail(fmt::format("expected a number, got {}", value_.type_name()));
        const double value = value_.get<double>();
        if (!std::isfinite(value))
            fail(fmt::format("expected a finite number, got {}", value_.dump()));
        return value;
    }

    std::int64_t integer(std::int64_t lo, std::int64_t hi) const {
        const double value = number();
        if (value != std::floor(value) || value < double(lo) || value > double(hi))
            fail(fmt::format("expected an integer in [{}, {}], got {}", lo, hi, value_.dump()));
        return std::int64_t(value);
    }

    bool boolean() const {
        if (!value_.is_boolean())
            fail(fmt::format("expected true or false, got {}", value_.type_name()));
        return value_.get<bool>();
    }

    std::string string() const {
        if (!value_.is_string())
            fail(fmt::format("expected a string, got {}", value_.type_name()));
        return value_.get<std::string>();
    }

    /// Exactly \p n finite numbers; \p alternative is appended to the message ("or a number").
    std::vector<double> numbers(std::size_t n, std::string_view alternative = "") const {
        const std::string expected = fmt::format("expected {} numbers{}", n, alternative);
        if (!value_.is_array())
            fail(fmt::format("{}, got {}", expected, value_.type_name()));
        if (value_.size() != n)
            fail(fmt::format("{}, got an array of {}", expected, value_.size()));
        std::vector<double> result;
        for (std::size_t i = 0; i < n; ++i) {
            if (!value_[i].is_number())
                fail(fmt::format("{}, element {} is {}", expected, i, value_[i].type_name()));
            result.push_back(element(i).number());
        }
        return result;
    }

    Vec3 vec3() const {
        const std::vector<double> v = numbers(3);
        return {v[0], v[1], v[2]};
    }

    /// [r, g, b] or one number for grey.
    Rgb rgb() const {
        if (value_.is_number())
            return Rgb(float(number()));
        const std::vector<double> v = numbers(3, " (or one number)");
        return {float(v[0]), float(v[1]), float(v[2])};
    }

private:
    const Json& value_;
    std::string path_;
    const std::string& file_;
};

/// nlohmann keeps the last of repeated keys silently; a scene file must not rely on that.
class DuplicateKeyCheck {
public:
    explicit DuplicateKeyCheck(const std::string& file) : file_(file) {}

    bool operator()(int, Json::parse_event_t event, Json& parsed) {
        if (event == Json::parse_event_t::object_start)
            open_.emplace_back();
        else if (event == Json::parse_event_t::object_end)
            open_.pop_back();
        else if (event == Json::parse_event_t::key &&
                 !open_.back().insert(parsed.get<std::string>()).second)
            throw InputError(file_, parsed.get<std::string>(), "key given twice in one object");
        return true;
    }

private:
    const std::string& file_;
    std::vector<std::set<std::string>> open_;
};

Json parse_json(const std::string& text, const std::string& file) {
    try {
        return Json::parse(text, DuplicateKeyCheck(file));
    } catch (const Json::parse_error& e) {
        const std::size_t end = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
        const auto line = 1 + std::count(text.begin(), text.begin() + std::ptrdiff_t(end), '\n');
        std::string what = e.what(); // "[json.exception...] parse error at line L, column C: ..."
        const std::size_t detail = what.find(": ", what.find("column"));
        if (detail != std::string::npos)
            what = what.substr(detail + 2);
        throw InputError(file, "", "invalid JSON: " + what, int(line));
    } catch (const Json::exception& e) { // e.g. out_of_range for 1e999, which has no position
        const std::string what = e.what();
        throw InputError(file, "", "invalid JSON: " + what.substr(what.find("] ") + 2));
    }
}

double parse_units(const Field& root) {
    constexpr std::pair<std::string_view, double> units[] = {
        {"m", 1.0}, {"cm", 0.01}, {"mm", 0.001}, {"in", 0.0254}, {"ft", 0.3048}};
    if (!root.has("units"))
        return 1.0;
    const Field field = root.child("units");
    const std::string unit = field.string();
    for (const auto& [name, metres] : units)
        if (unit == name)
            return metres;
    field.fail(fmt::format("unknown unit '{}' (known: m, cm, mm, in, ft)", unit));
}

Vec3 parse_up(const Field& root) {
    if (!root.has("up"))
        return {0, 0, 1};
    const Field field = root.child("up");
    const Vec3 up = field.vec3();
    if (length(up) == 0)
        field.fail("expected a non-zero vector");
    return normalize(up);
}

std::vector<std::string> parse_geometry_list(const Field& root) {
    if (!root.has("geometry"))
        return {};
    const Field field = root.child("geometry");
    if (!field.is_array())
        return {field.string()};
    std::vector<std::string> files;
    for (std::size_t i = 0; i < field.array_size(); ++i)
        files.push_back(field.element(i).string());
    return files;
}

/// Transmissivity tn (one crossing of the pane) of thin glass that transmits \p tn_normal at
/// normal incidence: the root of T = (1 − r)² tn / (1 − r² tn²), r the Fresnel reflectance of
/// one face. At n = 1.52 this is Radiance's formula (sqrt(.8402528435 + .0072522239 T²) −
/// .9166530661) / .0036261119 / T, whose constants are (1 − r)⁴, 4r², (1 − r)² and 2r².
double transmissivity_from_normal(double tn_normal, double ior) {
    const double r = (ior - 1) * (ior - 1) / ((ior + 1) * (ior + 1));
    const double k = (1 - r) * (1 - r);
    if (tn_normal == 0)
        return 0;
    return (std::sqrt(k * k + 4 * r * r * tn_normal * tn_normal) - k) / (2 * r * r * tn_normal);
}

// "type": "thin_glass" with "transmissivity" (Radiance's glass input) or
// "transmittance_normal" (what a glazing's data sheet gives), per channel, and "ior".
ThinGlass parse_thin_glass(const Field& field) {
    for (const char* key :
         {"reflectance", "diffuse_transmittance", "emission", "emission_flux_lm", "emission_color"})
        if (field.has(key))
            field.child(key).fail("a thin_glass material has no diffuse part or emission");
    ThinGlass glass;
    if (field.has("ior")) {
        const Field ior = field.child("ior");
        glass.ior = ior.number();
        if (!(glass.ior > 1 && glass.ior <= 10))
            ior.fail(fmt::format("must be in (1, 10], got {}", glass.ior));
    }
    if (field.has("transmissivity") == field.has("transmittance_normal"))
        field.fail("a thin_glass material takes exactly one of 'transmissivity' and "
                   "'transmittance_normal'");
    const bool direct = field.has("transmissivity");
    const Field value = field.child(direct ? "transmissivity" : "transmittance_normal");
    const Rgb given = value.rgb();
    const double most = direct ? 1.0 : thin_glass_response(1.0, glass.ior, 1.0).transmittance;
    for (int c = 0; c < 3; ++c) {
        if (!(given[c] >= 0 && given[c] <= most))
            value.fail(fmt::format("must be in [0, {:.6g}] per channel{}, got ({}, {}, {})", most,
                                   direct ? "" : " (clear glass of this ior)", given.r, given.g,
                                   given.b));
        glass.transmissivity[c] =
            direct ? given[c] : float(transmissivity_from_normal(given[c], glass.ior));
    }
    return glass;
}

double number_in(const Field& field, double lo, double hi, const char* range); // defined below

// ---- Material types (issue #28) ---------------------------------------------------------------

/// The keys that only some material types take; each type lists its own.
constexpr std::string_view k_type_keys[] = {"reflectance",    "diffuse_transmittance",
                                            "alpha",          "specular",
                                            "fresnel",        "ior",
                                            "solid",          "transmittance",
                                            "transmissivity", "transmittance_normal"};

struct MaterialType {
    std::string_view name;
    std::span<const std::string_view> keys; ///< of k_type_keys
};

constexpr std::string_view k_diffuse_keys[] = {"reflectance", "diffuse_transmittance"};
constexpr std::string_view k_ggx_keys[] = {"alpha", "specular", "fresnel", "ior"};
constexpr std::string_view k_plastic_keys[] = {"reflectance", "alpha", "specular", "fresnel",
                                               "ior"};
constexpr std::string_view k_mirror_keys[] = {"specular"};
constexpr std::string_view k_glass_keys[] = {"ior", "solid", "transmittance"};
constexpr std::string_view k_thin_glass_keys[] = {"transmissivity", "transmittance_normal", "ior"};

constexpr MaterialType k_material_types[] = {
    {"diffuse", k_diffuse_keys}, {"ggx", k_ggx_keys},     {"plastic", k_plastic_keys},
    {"mirror", k_mirror_keys},   {"glass", k_glass_keys}, {"thin_glass", k_thin_glass_keys},
};

const MaterialType& material_type(const Field& field) {
    const std::string name = field.has("type") ? field.child("type").string() : "diffuse";
    for (const MaterialType& type : k_material_types)
        if (type.name == name)
            return type;
    std::vector<std::string_view> names;
    for (const MaterialType& type : k_material_types)
        names.push_back(type.name);
    field.child("type").fail(
        fmt::format("unknown material type '{}' (known: {})", name, fmt::join(names, ", ")));
}

/// Each key of k_type_keys that \p field gives must be one of its type's.
void check_type_keys(const Field& field, const MaterialType& type) {
    for (const std::string_view key : k_type_keys) {
        const std::string k(key);
        if (field.has(k) && std::find(type.keys.begin(), type.keys.end(), key) == type.keys.end())
            field.child(k).fail(fmt::format(
                "is not a key of a '{}' material{} (its keys: {})", type.name,
                field.has("type") ? "" : " (the default type)", fmt::join(type.keys, ", ")));
    }
}

/// A colour with every channel in [0, 1].
Rgb unit_rgb(const Field& field) {
    const Rgb c = field.rgb();
    for (int i = 0; i < 3; ++i)
        if (!(c[i] >= 0 && c[i] <= 1))
            field.fail(
                fmt::format("must be in [0, 1] per channel, got ({}, {}, {})", c.r, c.g, c.b));
    return c;
}

double ior_of(const Field& field, double fallback) {
    return field.has("ior") ? number_in(field.child("ior"), 1.0, 10.0, "[1, 10]") : fallback;
}

/// `fresnel`: "none", "schlick" or "dielectric" (with `ior`, default 1.5); \p fallback when
/// absent.
Fresnel parse_fresnel(const Field& field, std::string_view fallback) {
    const std::string name =
        field.has("fresnel") ? field.child("fresnel").string() : std::string(fallback);
    if (name != "dielectric" && field.has("ior"))
        field.child("ior").fail("is only used with \"fresnel\": \"dielectric\"");
    if (name == "none")
        return FresnelNone{};
    if (name == "schlick")
        return FresnelSchlick{};
    if (name == "dielectric")
        return FresnelDielectric{ior_of(field, 1.5)};
    field.child("fresnel").fail(
        fmt::format("unknown fresnel '{}' (known: none, schlick, dielectric)", name));
}

/// "ggx" (a metal) and "plastic" (a coat over the diffuse `reflectance`).
GgxGlossy parse_glossy(const Field& field, bool plastic) {
    GgxGlossy g;
    if (field.has("alpha")) {
        const Field alpha = field.child("alpha");
        g.alpha = alpha.number();
        if (!(g.alpha > 0 && g.alpha <= 1))
            alpha.fail(fmt::format("must be in (0, 1] (GGX's α), got {}", g.alpha));
    }
    if (field.has("specular"))
        g.specular = unit_rgb(field.child("specular"));
    g.fresnel = parse_fresnel(field, plastic ? "dielectric" : "none");
    g.diffuse_base = plastic;
    return g;
}

Dielectric parse_glass(const Field& field) {
    Dielectric glass;
    glass.ior = ior_of(field, glass.ior);
    if (field.has("solid"))
        glass.solid = field.child("solid").boolean();
    if (field.has("transmittance"))
        glass.transmittance = unit_rgb(field.child("transmittance"));
    return glass;
}

/// The lobe of a `type`; none for "diffuse".
std::optional<Lobe> parse_lobe(const Field& field, const MaterialType& type) {
    if (type.name == "ggx" || type.name == "plastic")
        return parse_glossy(field, type.name == "plastic");
    if (type.name == "mirror")
        return Mirror{field.has("specular") ? unit_rgb(field.child("specular")) : Rgb(1.0f)};
    if (type.name == "glass")
        return parse_glass(field);
    if (type.name == "thin_glass")
        return parse_thin_glass(field);
    return std::nullopt;
}

// `lightmap_mode` of a light or an emitting material (issue #29): "all" unless given.
std::optional<LightmapMode> parse_lightmap_mode(const Field& parent) {
    if (!parent.has("lightmap_mode"))
        return std::nullopt;
    const Field field = parent.child("lightmap_mode");
    const std::optional<LightmapMode> mode = parse_enum<LightmapMode>(field.string());
    if (!mode)
        field.fail(fmt::format("unknown lightmap mode '{}' (known: {})", field.string(),
                               enum_name_list<LightmapMode>()));
    return mode;
}

MaterialSpec parse_material(const Field& field, const std::string& name) {
    field.expect_keys({"type", "reflectance", "emission", "emission_flux_lm", "emission_color",
                       "two_sided", "emission_two_sided", "transmissivity", "transmittance_normal",
                       "ior", "alpha", "specular", "fresnel", "solid", "transmittance",
                       "diffuse_transmittance", "lightmap_mode"});
    if (name.empty())
        field.fail("a material name must not be empty");
    MaterialSpec spec;
    spec.name = name;
    const MaterialType& type = material_type(field);
    check_type_keys(field, type);
    if (field.has("type"))
        spec.lobe = parse_lobe(field, type);
    if (field.has("reflectance"))
        spec.reflectance = field.child("reflectance").rgb();
    if (field.has("diffuse_transmittance"))
        spec.diffuse_transmittance = field.child("diffuse_transmittance").rgb();
    if (field.has("emission"))
        spec.emission = field.child("emission").rgb();
    if (field.has("emission_flux_lm"))
        spec.emission_flux_lm = field.child("emission_flux_lm").number();
    if (field.has("emission_color"))
        spec.emission_color = field.child("emission_color").rgb();
    if (field.has("two_sided"))
        spec.two_sided = field.child("two_sided").boolean();
    if (field.has("emission_two_sided"))
        spec.emission_two_sided = field.child("emission_two_sided").boolean();
    spec.lightmap_mode = parse_lightmap_mode(field);
    if (spec.emission && spec.emission_flux_lm)
        field.child("emission_flux_lm").fail("give 'emission' or 'emission_flux_lm', not both");
    if (spec.emission_color && !spec.emission_flux_lm)
        field.child("emission_color").fail("is only used with 'emission_flux_lm'");
    return spec;
}

PolygonSpec parse_polygon(const Field& field, double metres_per_unit) {
    field.expect_keys({"name", "material", "vertices"});
    PolygonSpec spec;
    spec.key = field.path();
    spec.name = field.has("name") ? field.child("name").string() : field.path();
    spec.material = field.required("material").string();
    const Field vertices = field.required("vertices");
    const std::size_t count = vertices.array_size();
    if (count < 3)
        vertices.fail(fmt::format("expected at least 3 vertices, got {}", count));
    for (std::size_t i = 0; i < count; ++i)
        spec.vertices.push_back(vertices.element(i).vec3() * metres_per_unit);
    return spec;
}

/// A direction: any non-zero vector, not scaled by the units, normalised; \p what follows
/// "expected a non-zero vector" in the error.
Vec3 unit_direction(const Field& field, const char* what) {
    const Vec3 d = field.vec3();
    if (length(d) == 0)
        field.fail(std::string("expected a non-zero vector") + what);
    return normalize(d);
}

// "spot": {"direction": [x, y, z], "beam_deg": a, "cutoff_deg": b}, half-angles with
// 0 ≤ a ≤ b ≤ 180 and b > 0; the direction is not scaled by the units and is normalised.
SpotCone parse_spot(const Field& field) {
    field.expect_keys({"direction", "beam_deg", "cutoff_deg"});
    SpotCone spot;
    spot.direction = unit_direction(field.required("direction"), "");
    const Field cutoff = field.required("cutoff_deg");
    spot.cutoff_deg = cutoff.number();
    if (!(spot.cutoff_deg > 0 && spot.cutoff_deg <= 180))
        cutoff.fail(fmt::format("must be in (0, 180] (a half-angle), got {}", spot.cutoff_deg));
    const Field beam = field.required("beam_deg");
    spot.beam_deg = beam.number();
    if (!(spot.beam_deg >= 0 && spot.beam_deg <= spot.cutoff_deg))
        beam.fail(fmt::format("must be in [0, cutoff_deg = {}] (a half-angle), got {}",
                              spot.cutoff_deg, spot.beam_deg));
    return spot;
}

/// `color` of a light or the sun: non-negative with non-zero luminance; white if absent.
Rgb parse_light_color(const Field& parent) {
    if (!parent.has("color"))
        return Rgb(1.0f);
    const Field field = parent.child("color");
    const Rgb color = field.rgb();
    if (color.r < 0 || color.g < 0 || color.b < 0 || to_photometric(color) <= 0)
        field.fail("expected a non-negative colour with non-zero luminance");
    return color;
}

PointLight parse_point_light(const Field& field, double metres_per_unit) {
    field.expect_keys(
        {"name", "position", "intensity_cd", "flux_lm", "color", "spot", "lightmap_mode"});
    PointLight light;
    light.lightmap_mode = parse_lightmap_mode(field).value_or(LightmapMode::all);
    light.name = field.has("name") ? field.child("name").string() : field.path();
    light.position = field.required("position").vec3() * metres_per_unit;
    if (field.has("spot"))
        light.spot = parse_spot(field.child("spot"));
    const bool by_intensity = field.has("intensity_cd");
    if (by_intensity == field.has("flux_lm"))
        field.fail("give exactly one of 'intensity_cd' and 'flux_lm'");
    const Field amount = field.child(by_intensity ? "intensity_cd" : "flux_lm");
    const double value = amount.number();
    if (value < 0)
        amount.fail(fmt::format("must be >= 0, got {}", value));
    // flux_lm is what leaves the light: 4π I for an isotropic light, the cone's for a spot.
    const double intensity_cd = by_intensity ? value : value / light.profile_solid_angle();
    light.intensity = from_photometric(intensity_cd, parse_light_color(field));
    return light;
}

// ---- Daylight: site, sun positions from dates, sky (issue #30) --------------------------------

/// The scene's compass and, if given, its site: what sun positions from dates and times need.
struct Daylight {
    Compass compass;
    std::optional<Location> site;
};

/// Where the sun is, and on which day of the year (0 when given as a direction).
struct SunPlacement {
    Vec3 direction;
    int day_of_year = 0;
};

/// The default north: +y made perpendicular to \p up, or −z when up is ±y (glTF's y-up scenes).
Vec3 default_north(const Vec3& up) {
    const Vec3 y(0, 1, 0);
    return std::abs(up.y) > 0.999 ? Vec3(0, 0, -1) : normalize(y - up * up.y);
}

Daylight parse_daylight_frame(const Field& root, const Vec3& up) {
    Daylight daylight;
    daylight.compass.up = up;
    daylight.compass.north = default_north(up);
    if (!root.has("site"))
        return daylight;
    const Field site = root.child("site");
    site.expect_keys({"latitude_deg", "longitude_deg", "time_zone_h", "north"});
    Location where;
    where.latitude_deg = number_in(site.required("latitude_deg"), -90, 90, "[-90, 90]");
    where.longitude_deg =
        number_in(site.required("longitude_deg"), -180, 180, "[-180, 180] (east-positive)");
    where.time_zone_h =
        number_in(site.required("time_zone_h"), -12, 14, "[-12, 14] (hours east of UTC)");
    daylight.site = where;
    if (site.has("north")) {
        const Field field = site.child("north");
        const Vec3 north = field.vec3();
        const Vec3 level = north - up * dot(north, up);
        if (!(length(level) > 1e-6 * length(north)))
            field.fail("expected a non-zero vector not parallel to 'up'");
        daylight.compass.north = normalize(level);
    }
    return daylight;
}

/// `time`: {"month", "day", "hour", "solar_time", "year"}, with the top-level `site`.
SunPlacement parse_time(const Field& field, const Daylight& daylight) {
    field.expect_keys({"year", "month", "day", "hour", "solar_time"});
    if (!daylight.site)
        field.fail("a sun position from a date and time needs the top-level 'site'");
    LocalTime when;
    if (field.has("year"))
        when.year = int(field.child("year").integer(1800, 2200));
    when.month = int(field.required("month").integer(1, 12));
    constexpr int month_days[] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    when.day = int(field.required("day").integer(1, month_days[when.month - 1]));
    if (when.month == 2 && when.day == 29 && day_of_year(when.year, 3, 1) == 60)
        field.child("day").fail(fmt::format("{} is not a leap year", when.year));
    const Field hour = field.required("hour");
    when.hour = hour.number();
    if (!(when.hour >= 0 && when.hour < 24))
        hour.fail(fmt::format("must be in [0, 24), got {}", when.hour));
    const bool solar = field.has("solar_time") && field.child("solar_time").boolean();
    const SolarAngles angles = solar ? solar_position_at_solar_time(*daylight.site, when)
                                     : solar_position(*daylight.site, when);
    return {daylight.compass.direction(angles.altitude_deg, angles.azimuth_deg),
            day_of_year(when.year, when.month, when.day)};
}

/// The sun's position under \p parent: exactly one of \p direction_key and `time`, or neither.
std::optional<SunPlacement> parse_sun_placement(const Field& parent, const char* direction_key,
                                                const Daylight& daylight) {
    const bool by_direction = parent.has(direction_key), by_time = parent.has("time");
    if (by_direction && by_time)
        parent.fail(fmt::format("give '{}' or 'time', not both", direction_key));
    if (by_time)
        return parse_time(parent.child("time"), daylight);
    if (by_direction)
        return SunPlacement{unit_direction(parent.child(direction_key), " (toward the sun)")};
    return std::nullopt;
}

double altitude_deg(const Vec3& direction, const Compass& compass) {
    return std::asin(std::clamp(dot(direction, compass.up), -1.0, 1.0)) * 180 / k_pi;
}

SkyModel parse_sky_model(const Field& sky) {
    const Field model = sky.required("model");
    const std::string name = model.string();
    if (sky.has("type") && name != "cie_general")
        sky.child("type").fail("is only used with \"model\": \"cie_general\"");
    if (name == "uniform")
        return UniformSky{};
    if (name == "cie_overcast")
        return CieOvercastSky{};
    if (name == "cie_general")
        return CieGeneralSky{int(sky.required("type").integer(1, 15))};
    if (name == "perez")
        return PerezSky{};
    model.fail(fmt::format("unknown sky model '{}' (known: uniform, cie_overcast, cie_general, "
                           "perez)",
                           name));
}

/// Exactly one of `horizontal_illuminance_lx` and `zenith_luminance_cd_m2`.
SkyLevel parse_sky_level(const Field& sky) {
    const bool by_illuminance = sky.has("horizontal_illuminance_lx");
    if (by_illuminance == sky.has("zenith_luminance_cd_m2"))
        sky.fail("give exactly one of 'horizontal_illuminance_lx' and 'zenith_luminance_cd_m2'");
    if (by_illuminance)
        return HorizontalIlluminance{
            number_in(sky.child("horizontal_illuminance_lx"), 0, 1e9, "[0, 1e9]")};
    return ZenithLuminance{number_in(sky.child("zenith_luminance_cd_m2"), 0, 1e9, "[0, 1e9]")};
}

/// A Perez sky's weather: the W/m² pair or the lx pair (at most the extraterrestrial values).
SolarComponents parse_solar_components(const Field& sky) {
    const bool radiometric = sky.has("direct_normal_w_m2") || sky.has("diffuse_horizontal_w_m2");
    const bool photometric = sky.has("direct_normal_lx") || sky.has("diffuse_horizontal_lx");
    if (radiometric == photometric)
        sky.fail("a 'perez' sky needs 'direct_normal_w_m2' and 'diffuse_horizontal_w_m2', or "
                 "'direct_normal_lx' and 'diffuse_horizontal_lx'");
    if (radiometric)
        return SolarIrradiance{
            number_in(sky.required("direct_normal_w_m2"), 0, 1415, "[0, 1415]"),
            number_in(sky.required("diffuse_horizontal_w_m2"), 0, 1415, "[0, 1415]")};
    return SolarIlluminance{
        number_in(sky.required("direct_normal_lx"), 0, 132000, "[0, 132000]"),
        number_in(sky.required("diffuse_horizontal_lx"), 0, 132000, "[0, 132000]")};
}

/// `ground_reflectance` (default 0.2) or `"ground": "geometry"` (none).
std::optional<double> parse_ground(const Field& sky) {
    if (!sky.has("ground"))
        return sky.has("ground_reflectance")
                   ? number_in(sky.child("ground_reflectance"), 0, 1, "[0, 1]")
                   : 0.2;
    const Field ground = sky.child("ground");
    if (ground.string() != "geometry")
        ground.fail(fmt::format("expected \"geometry\", got \"{}\"", ground.string()));
    if (sky.has("ground_reflectance"))
        sky.child("ground_reflectance").fail("give 'ground_reflectance' or 'ground', not both");
    return std::nullopt;
}

Horizon parse_horizon(const Field& sky, bool has_ground) {
    if (!sky.has("horizon"))
        return Horizon::sharp;
    const Field field = sky.child("horizon");
    const std::string name = field.string();
    if (name == "sharp")
        return Horizon::sharp;
    if (name != "radiance_blend")
        field.fail(fmt::format("unknown horizon '{}' (known: sharp, radiance_blend)", name));
    if (!has_ground)
        field.fail("\"radiance_blend\" blends the sky with the ground hemisphere: not with "
                   "\"ground\": \"geometry\"");
    return Horizon::radiance_blend;
}

/// No position for a sky that does not need one; an error for one that does.
std::optional<SunPlacement> no_sun_needed(const Field& sky, bool uses_sun) {
    if (uses_sun)
        sky.fail("this sky needs the sun's position: give 'time' (with 'site'), 'sun_direction', "
                 "or a top-level 'sun'");
    return std::nullopt;
}

/// Where the sky's sun is: the sky's own `sun_direction` or `time`, else the top-level sun's.
/// The uniform and overcast skies take none.
std::optional<SunPlacement> parse_sky_sun(const Field& sky, const SkyModel& model,
                                          const Daylight& daylight, const Scene& scene) {
    std::optional<SunPlacement> own = parse_sun_placement(sky, "sun_direction", daylight);
    const bool uses_sun =
        std::holds_alternative<CieGeneralSky>(model) || std::holds_alternative<PerezSky>(model);
    if (!own)
        return scene.sun && uses_sun ? std::optional(SunPlacement{scene.sun->direction})
                                     : no_sun_needed(sky, uses_sun);
    const Field key = sky.child(sky.has("time") ? "time" : "sun_direction");
    if (!uses_sun)
        key.fail("is only used by the 'cie_general' and 'perez' skies");
    if (scene.sun) {
        const double apart =
            std::acos(std::clamp(dot(own->direction, scene.sun->direction), -1.0, 1.0)) * 180 /
            k_pi;
        if (apart > 0.1)
            key.fail(fmt::format("puts the sun {:.2f}° from 'sun': give the sun's position once "
                                 "(the sky takes the top-level sun's)",
                                 apart));
    }
    return own;
}

/// `"model": "perez"`: the sky and its sun from one hour's weather (perez_sky_and_sun).
void parse_perez_sky(const Field& sky, const Daylight& daylight, const SunPlacement& placement,
                     Scene& scene) {
    for (const char* key : {"horizontal_illuminance_lx", "zenith_luminance_cd_m2", "color"})
        if (sky.has(key))
            sky.child(key).fail("is not used by a 'perez' sky (its weather sets its level)");
    if (scene.sun)
        sky.fail("a 'perez' sky brings its own sun (from its direct-normal value): remove the "
                 "top-level 'sun' and give the position as the sky's 'time' or 'sun_direction'");
    int day = placement.day_of_year;
    if (sky.has("day_of_year")) {
        if (day != 0)
            sky.child("day_of_year").fail("the sky's 'time' already gives the day");
        day = int(sky.child("day_of_year").integer(1, 366));
    }
    if (day == 0)
        sky.fail("a 'perez' sky with 'sun_direction' needs 'day_of_year' (or give 'time')");
    const std::optional<double> ground = parse_ground(sky);
    PerezSkyAndSun result =
        perez_sky_and_sun(parse_solar_components(sky), daylight.compass, placement.direction, day,
                          ground, parse_horizon(sky, ground.has_value()));
    scene.sky = result.sky;
    scene.sun = result.sun;
}

/// `sky`: see docs/scene-format.md. Runs after `sun`, whose position and light it can use.
void parse_sky(const Field& sky, const Daylight& daylight, Scene& scene) {
    sky.expect_keys({"model", "type", "horizontal_illuminance_lx", "zenith_luminance_cd_m2",
                     "ground_reflectance", "ground", "horizon", "time", "sun_direction", "color",
                     "direct_normal_w_m2", "diffuse_horizontal_w_m2", "direct_normal_lx",
                     "diffuse_horizontal_lx", "day_of_year", "lightmap_mode"});
    const SkyModel model = parse_sky_model(sky);
    const std::optional<SunPlacement> placement = parse_sky_sun(sky, model, daylight, scene);
    if (std::holds_alternative<PerezSky>(model))
        return parse_perez_sky(sky, daylight, *placement, scene);
    for (const char* key : {"direct_normal_w_m2", "diffuse_horizontal_w_m2", "direct_normal_lx",
                            "diffuse_horizontal_lx", "day_of_year"})
        if (sky.has(key))
            sky.child(key).fail("is only used by a 'perez' sky");
    SkyDescription description;
    description.model = model;
    description.compass = daylight.compass;
    if (placement) {
        const double altitude = altitude_deg(placement->direction, daylight.compass);
        if (altitude < 0)
            sky.fail(fmt::format("the sun is {:.2f}° below the horizon: the CIE general skies "
                                 "need it above",
                                 -altitude));
        description.sun_direction = placement->direction;
    }
    description.level = parse_sky_level(sky);
    description.ground_reflectance = parse_ground(sky);
    description.horizon = parse_horizon(sky, description.ground_reflectance.has_value());
    description.colour = parse_light_color(sky);
    const double sun_lx = scene.sun ? horizontal_illuminance_lx(*scene.sun, daylight.compass) : 0;
    scene.sky = make_sky(description, sun_lx);
}

// "sun": {"direction": [x, y, z] or "time": {...}, "illuminance_lx": E or "irradiance_w_m2": E
// or [r, g, b], "color": [r, g, b], "angular_diameter_deg": d}. The direction points toward the
// sun (from `time`: its position at the site), is not scaled by the units and is normalised; E is
// the direct normal irradiance (on a surface facing the sun). `color` goes with `illuminance_lx`
// only: radiometric input carries its colour in its channels.
Sun parse_sun(const Field& field, const Daylight& daylight) {
    field.expect_keys({"direction", "time", "illuminance_lx", "irradiance_w_m2", "color",
                       "angular_diameter_deg", "lightmap_mode"});
    Sun sun;
    sun.lightmap_mode = parse_lightmap_mode(field).value_or(LightmapMode::all);
    const std::optional<SunPlacement> placement = parse_sun_placement(field, "direction", daylight);
    sun.direction = placement ? placement->direction : field.required("direction").vec3();
    if (field.has("time") && altitude_deg(sun.direction, daylight.compass) <= 0)
        field.child("time").fail(fmt::format("the sun is {:.2f}° below the horizon then",
                                             -altitude_deg(sun.direction, daylight.compass)));
    const bool photometric = field.has("illuminance_lx");
    if (photometric == field.has("irradiance_w_m2"))
        field.fail("give exactly one of 'illuminance_lx' and 'irradiance_w_m2'");
    if (photometric) {
        const Field amount = field.child("illuminance_lx");
        const double lx = amount.number();
        if (lx < 0)
            amount.fail(fmt::format("must be >= 0, got {}", lx));
        sun.irradiance = from_photometric(lx, parse_light_color(field));
    } else {
        if (field.has("color"))
            field.child("color").fail(
                "is only used with 'illuminance_lx' (give 'irradiance_w_m2' as [r, g, b])");
        const Field amount = field.child("irradiance_w_m2");
        sun.irradiance = amount.rgb();
        const Rgb& e = sun.irradiance;
        if (!e.is_finite() || e.r < 0 || e.g < 0 || e.b < 0)
            amount.fail(fmt::format("must be finite and >= 0 per channel, got ({}, {}, {})", e.r,
                                    e.g, e.b));
    }
    if (field.has("angular_diameter_deg")) {
        const Field diameter = field.child("angular_diameter_deg");
        sun.angular_diameter_deg = diameter.number();
        if (!(sun.angular_diameter_deg >= 0 && sun.angular_diameter_deg <= 10))
            diameter.fail(fmt::format("must be in [0, 10] degrees (the sun: 0.533), got {}",
                                      sun.angular_diameter_deg));
    }
    return sun;
}

Vec3 sensor_normal(const Field& field, const Vec3& normal) {
    if (length(normal) == 0)
        field.fail("the sensor normal must be a non-zero vector");
    return normalize(normal);
}

Sensor parse_sensor(const Field& field, double metres_per_unit) {
    Sensor sensor;
    if (field.is_array()) {
        const std::vector<double> v = field.numbers(6, " [x, y, z, nx, ny, nz]");
        sensor.position = Vec3(v[0], v[1], v[2]) * metres_per_unit;
        sensor.normal = sensor_normal(field, Vec3(v[3], v[4], v[5]));
        return sensor;
    }
    field.expect_keys({"name", "position", "normal"});
    if (field.has("name"))
        sensor.name = field.child("name").string();
    sensor.position = field.required("position").vec3() * metres_per_unit;
    const Field normal = field.required("normal");
    sensor.normal = sensor_normal(normal, normal.vec3());
    return sensor;
}

void parse_sensors(const Field& field, double metres_per_unit, SceneSpec& spec) {
    if (field.is_object()) {
        field.expect_keys({"file"});
        spec.sensor_file = field.required("file").string();
        return;
    }
    const std::size_t count = field.array_size();
    for (std::size_t i = 0; i < count; ++i)
        spec.scene.sensors.push_back(parse_sensor(field.element(i), metres_per_unit));
}

/// A length of the scene file in metres: a finite number >= 0 (> 0 when \p positive).
double length_m(const Field& field, double metres_per_unit, bool positive) {
    const double value = field.number();
    if (positive ? !(value > 0) : !(value >= 0))
        field.fail(fmt::format("must be {} 0, got {}", positive ? ">" : ">=", value));
    return value * metres_per_unit;
}

/// A grid's `floor` or `wall`: the name of the scene's polygons, or inline vertices.
std::variant<std::string, std::vector<Vec3>> parse_grid_polygon(const Field& field,
                                                                double metres_per_unit) {
    if (field.is_object())
        field.fail("expected a polygon name or an array of [x, y, z] vertices, got an object");
    if (!field.is_array())
        return field.string();
    const std::size_t count = field.array_size();
    if (count < 3)
        field.fail(fmt::format("expected at least 3 vertices, got {}", count));
    std::vector<Vec3> vertices;
    for (std::size_t i = 0; i < count; ++i)
        vertices.push_back(field.element(i).vec3() * metres_per_unit);
    return vertices;
}

// "grids": {"NAME": {"floor": POLYGON, "height": h, "spacing": s, "wall_offset": w}} for a
// work plane, or {"wall": POLYGON, "distance": d, "spacing": s, "wall_offset": w} for points
// on a wall; POLYGON is a polygon name or [[x, y, z], ...]. Expanded by sensor_grids.cpp.
GridSpec parse_grid(const Field& field, const std::string& name, double metres_per_unit,
                    const Vec3& up) {
    field.expect_keys({"floor", "wall", "height", "distance", "spacing", "wall_offset"});
    const bool floor = field.has("floor");
    if (floor == field.has("wall"))
        field.fail("give exactly one of 'floor' (a work plane) and 'wall' (points on a wall)");
    const char* other = floor ? "distance" : "height";
    if (field.has(other))
        field.child(other).fail(fmt::format("is only used with '{}'", floor ? "wall" : "floor"));
    GridSpec spec;
    spec.key = field.path();
    spec.name = name;
    spec.kind = floor ? GridKind::work_plane : GridKind::wall;
    spec.up = up;
    spec.polygon = parse_grid_polygon(field.child(floor ? "floor" : "wall"), metres_per_unit);
    if (floor)
        spec.offset_m = length_m(field.required("height"), metres_per_unit, false);
    else if (field.has("distance"))
        spec.offset_m = length_m(field.child("distance"), metres_per_unit, false);
    spec.spacing_m = length_m(field.required("spacing"), metres_per_unit, true);
    if (field.has("wall_offset"))
        spec.wall_offset_m = length_m(field.child("wall_offset"), metres_per_unit, false);
    return spec;
}

void parse_grids(const Field& root, const Vec3& up, SceneSpec& spec) {
    if (!root.has("grids"))
        return;
    for (const auto& [name, field] : root.child("grids").members())
        spec.grids.push_back(parse_grid(field, name, spec.metres_per_unit, up));
}

// A camera's keys, checked by the caller (the named cameras of "cameras" add "name").
Camera parse_camera_keys(const Field& field, double metres_per_unit, const Vec3& scene_up) {
    if (field.has("type")) {
        const Field type = field.child("type");
        if (type.string() != "pinhole")
            type.fail(fmt::format("unknown camera type '{}' (known: pinhole)", type.string()));
    }
    Camera camera;
    camera.eye = field.required("eye").vec3() * metres_per_unit;
    camera.look_at = field.required("look_at").vec3() * metres_per_unit;
    camera.up = field.has("up") ? field.child("up").vec3() : scene_up;
    if (field.has("fov_deg"))
        camera.fov_deg = field.child("fov_deg").number();
    if (field.has("fov_axis")) {
        const Field axis = field.child("fov_axis");
        const std::string value = axis.string();
        if (value != "x" && value != "y")
            axis.fail(fmt::format("expected \"x\" or \"y\", got \"{}\"", value));
        camera.fov_axis_x = value == "x";
    }
    if (field.has("aperture_radius"))
        camera.aperture_radius_m = field.child("aperture_radius").number() * metres_per_unit;
    if (field.has("focus_distance"))
        camera.focus_distance_m = field.child("focus_distance").number() * metres_per_unit;
    return camera;
}

Camera parse_camera(const Field& field, double metres_per_unit, const Vec3& scene_up) {
    field.expect_keys({"type", "eye", "look_at", "up", "fov_deg", "fov_axis", "aperture_radius",
                       "focus_distance"});
    return parse_camera_keys(field, metres_per_unit, scene_up);
}

// "cameras": [{"name": "top", <the keys of "camera">}, ...]: cameras besides "camera", chosen
// by name (`--camera NAME`); "image" sets their image as the main camera's.
void parse_cameras(const Field& field, double metres_per_unit, const Vec3& scene_up, Scene& scene) {
    for (std::size_t i = 0; i < field.array_size(); ++i) {
        const Field entry = field.element(i);
        entry.expect_keys({"name", "type", "eye", "look_at", "up", "fov_deg", "fov_axis",
                           "aperture_radius", "focus_distance"});
        NamedCamera named{entry.required("name").string(),
                          parse_camera_keys(entry, metres_per_unit, scene_up)};
        if (named.name.empty())
            entry.child("name").fail("must not be empty");
        for (const NamedCamera& other : scene.cameras)
            if (other.name == named.name)
                entry.child("name").fail(fmt::format("camera '{}' named twice", named.name));
        scene.cameras.push_back(std::move(named));
    }
}

void parse_image(const Field& field, Camera& camera) {
    field.expect_keys({"width", "height", "spp", "exposure"});
    if (field.has("width"))
        camera.width = int(field.child("width").integer(1, 16384));
    if (field.has("height"))
        camera.height = int(field.child("height").integer(1, 16384));
    if (field.has("spp"))
        camera.samples_per_pixel = int(field.child("spp").integer(1, 1 << 20));
    if (field.has("exposure"))
        camera.exposure = field.child("exposure").number();
}

DiscontinuitySettings parse_discontinuity(const Field& field) {
    field.expect_keys({"enabled", "max_order"});
    DiscontinuitySettings d;
    if (field.has("enabled"))
        d.enabled = field.child("enabled").boolean();
    if (field.has("max_order"))
        d.max_order = int(field.child("max_order").integer(0, 2));
    return d;
}

MesherSettings parse_mesher(const Field& field, double metres_per_unit) {
    field.expect_keys({"max_edge_length", "planarity_tolerance", "split_contacts",
                       "contact_tolerance", "element_budget", "discontinuity"});
    MesherSettings mesher;
    if (field.has("max_edge_length"))
        mesher.max_edge_length = field.child("max_edge_length").number() * metres_per_unit;
    if (field.has("planarity_tolerance"))
        mesher.planarity_tolerance = field.child("planarity_tolerance").number();
    if (field.has("split_contacts"))
        mesher.split_contacts = field.child("split_contacts").boolean();
    if (field.has("contact_tolerance"))
        mesher.contact_tolerance = field.child("contact_tolerance").number() * metres_per_unit;
    if (field.has("element_budget"))
        mesher.element_budget = field.child("element_budget").integer(0, std::int64_t(1) << 40);
    if (field.has("discontinuity"))
        mesher.discontinuity = parse_discontinuity(field.child("discontinuity"));
    return mesher;
}

double number_in(const Field& field, double lo, double hi, const char* range) {
    const double v = field.number();
    if (!(v >= lo && v <= hi))
        field.fail(fmt::format("{} must be in {}", v, range));
    return v;
}

/// The value of a settings enum spelled by \p field (its name table, core/enum_names.h).
template <class E> E enum_value(const Field& field, const char* what) {
    const std::string name = field.string();
    const std::optional<E> value = parse_enum<E>(name);
    if (!value)
        field.fail(fmt::format("unknown {} '{}' (known: {})", what, name, enum_name_list<E>()));
    return *value;
}

SolverSettings parse_solver(const Field& field, double metres_per_unit) {
    field.expect_keys({"method", "oracle", "clustering", "iteration", "residual", "epsilon",
                       "min_area", "max_sweeps", "ambient", "max_shots", "visibility_rays",
                       "row_cache_mb"});
    SolverSettings solver;
    if (field.has("method"))
        solver.method = enum_value<SolverMethod>(field.child("method"), "method");
    if (field.has("oracle"))
        solver.oracle = enum_value<RefinementOracle>(field.child("oracle"), "oracle");
    if (field.has("clustering"))
        solver.clustering = enum_value<Clustering>(field.child("clustering"), "clustering");
    if (field.has("iteration"))
        solver.iteration = enum_value<SolverIteration>(field.child("iteration"), "iteration");
    if (field.has("residual"))
        solver.residual = number_in(field.child("residual"), 1e-12, 0.5, "[1e-12, 0.5]");
    if (field.has("epsilon"))
        solver.epsilon = number_in(field.child("epsilon"), 1e-12, 1.0, "[1e-12, 1]");
    if (field.has("min_area"))
        solver.min_area = number_in(field.child("min_area"), 0.0, 1e30, "[0, 1e30]") *
                          metres_per_unit * metres_per_unit;
    if (field.has("max_sweeps"))
        solver.max_sweeps = int(field.child("max_sweeps").integer(1, 1 << 24));
    if (field.has("ambient"))
        solver.ambient = field.child("ambient").boolean();
    if (field.has("max_shots"))
        solver.max_shots = field.child("max_shots").integer(0, std::int64_t(1) << 53);
    if (field.has("visibility_rays"))
        solver.visibility_rays = int(field.child("visibility_rays").integer(1, 1 << 16));
    if (field.has("row_cache_mb"))
        solver.row_cache_mb = number_in(field.child("row_cache_mb"), 0.0, 1e9, "[0, 1e9]");
    return solver;
}

// "irradiance_cache": true, false, or {"rays": n, "error": a} (on, with these settings).
std::optional<IrradianceCacheSettings> parse_irradiance_cache(const Field& field) {
    if (!field.is_object())
        return field.boolean() ? std::optional(IrradianceCacheSettings{}) : std::nullopt;
    field.expect_keys({"rays", "error"});
    IrradianceCacheSettings cache;
    if (field.has("rays"))
        cache.rays = int(field.child("rays").integer(16, 1 << 16));
    if (field.has("error"))
        cache.error = number_in(field.child("error"), 1e-3, 1.0, "[0.001, 1]");
    return cache;
}

// "render": {"spp": n, "max_bounces": n, "pixel_filter": "box", "filter_width_px": w,
// "caustic_photons": n, "caustic_radius": r, "light_samples": n, "gather_rays": n,
// "edge_tolerance": t, "irradiance_cache": …}; spp is the camera's (as image.spp: give one of
// them); caustic_radius is in scene units.
void parse_render(const Field& root, double metres_per_unit, Scene& scene) {
    const Field field = root.child("render");
    field.expect_keys({"spp", "max_bounces", "pixel_filter", "filter_width_px", "caustic_photons",
                       "caustic_radius", "light_samples", "gather_rays", "edge_tolerance",
                       "irradiance_cache"});
    if (field.has("spp")) {
        if (!scene.camera)
            field.child("spp").fail("needs a 'camera'");
        if (root.has("image") && root.child("image").has("spp"))
            field.child("spp").fail("give 'image.spp' or 'render.spp', not both");
        scene.camera->samples_per_pixel = int(field.child("spp").integer(1, 1 << 20));
        for (NamedCamera& named : scene.cameras)
            named.camera.samples_per_pixel = scene.camera->samples_per_pixel;
    }
    RenderSettings& render = scene.render;
    if (field.has("max_bounces"))
        render.max_bounces = int(field.child("max_bounces").integer(0, 1024));
    if (field.has("pixel_filter"))
        render.pixel_filter = enum_value<PixelFilter>(field.child("pixel_filter"), "pixel filter");
    if (field.has("filter_width_px"))
        render.filter_width_px =
            number_in(field.child("filter_width_px"), 0.01, 16.0, "[0.01, 16] pixels");
    if (field.has("caustic_photons"))
        render.caustic_photons = int(field.child("caustic_photons").integer(0, 100'000'000));
    if (field.has("caustic_radius"))
        render.caustic_radius_m =
            number_in(field.child("caustic_radius"), 1e-9, 1e9, "(0, 1e9]") * metres_per_unit;
    if (field.has("irradiance_cache"))
        render.irradiance_cache = parse_irradiance_cache(field.child("irradiance_cache"));
    if (field.has("light_samples"))
        render.light_samples = int(field.child("light_samples").integer(1, 1024));
    if (field.has("gather_rays"))
        render.gather_rays = int(field.child("gather_rays").integer(1, 1024));
    if (field.has("edge_tolerance"))
        render.edge_tolerance = number_in(field.child("edge_tolerance"), 0.0, 1e9, "[0, 1e9]");
}

LightmapSettings parse_lightmap(const Field& field) {
    field.expect_keys({"size", "directional", "gather"});
    LightmapSettings lightmap;
    if (field.has("gather"))
        lightmap.gather = int(field.child("gather").integer(0, 1 << 16));
    if (field.has("size"))
        lightmap.atlas_size = int(field.child("size").integer(16, 16384));
    if (field.has("directional"))
        lightmap.directional = field.child("directional").boolean();
    return lightmap;
}

// "probes": {"points": [[x, y, z], ...], "grid": {"min": [...], "max": [...], "spacing": s},
// "rays": n}: at least one point or a grid; at most 10⁶ probes in all.
ProbeSettings parse_probes(const Field& field, double metres_per_unit) {
    field.expect_keys({"points", "grid", "rays"});
    ProbeSettings probes;
    if (field.has("points")) {
        const Field points = field.child("points");
        for (std::size_t i = 0; i < points.array_size(); ++i)
            probes.points.push_back(points.element(i).vec3() * metres_per_unit);
    }
    if (field.has("grid")) {
        const Field grid = field.child("grid");
        grid.expect_keys({"min", "max", "spacing"});
        ProbeGrid g;
        g.min = grid.required("min").vec3() * metres_per_unit;
        g.max = grid.required("max").vec3() * metres_per_unit;
        g.spacing_m = length_m(grid.required("spacing"), metres_per_unit, true);
        if (!(g.min.x <= g.max.x && g.min.y <= g.max.y && g.min.z <= g.max.z))
            grid.child("max").fail("must be >= min on every axis");
        const std::array<int, 3> n = g.counts();
        if (double(n[0]) * n[1] * n[2] > 1e6)
            grid.child("spacing").fail(
                fmt::format("gives {} x {} x {} probes, more than 10^6", n[0], n[1], n[2]));
        probes.grid = g;
    }
    if (field.has("rays"))
        probes.rays = int(field.child("rays").integer(16, 1 << 20));
    if (probes.points.empty() && !probes.grid)
        field.fail("needs 'points' or a 'grid'");
    return probes;
}

Rgb parse_background(const Field& field) {
    const Rgb c = field.rgb();
    if (!(c.r >= 0 && c.g >= 0 && c.b >= 0))
        field.fail(
            fmt::format("must be >= 0 per channel (W/(sr·m²)), got ({}, {}, {})", c.r, c.g, c.b));
    return c;
}

/// `smooth_objects`: object names, each at most once.
std::vector<std::string> parse_smooth_objects(const Field& field) {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < field.array_size(); ++i) {
        const Field name = field.element(i);
        names.push_back(name.string());
        if (std::count(names.begin(), names.end(), names.back()) > 1)
            name.fail(fmt::format("'{}' is listed twice", names.back()));
    }
    return names;
}

/// materials and polygons: what the geometry files are merged with.
void parse_surfaces(const Field& root, SceneSpec& spec) {
    spec.geometry = parse_geometry_list(root);
    if (root.has("materials"))
        for (const auto& [name, field] : root.child("materials").members())
            spec.materials.push_back(parse_material(field, name));
    if (root.has("emission_two_sided"))
        spec.emission_two_sided = root.child("emission_two_sided").boolean();
    if (root.has("smooth_objects"))
        spec.smooth_objects = parse_smooth_objects(root.child("smooth_objects"));
    if (root.has("polygons")) {
        const Field polygons = root.child("polygons");
        for (std::size_t i = 0; i < polygons.array_size(); ++i)
            spec.polygons.push_back(parse_polygon(polygons.element(i), spec.metres_per_unit));
    }
    if (spec.geometry.empty() && spec.polygons.empty())
        Field(Json(), "geometry", spec.scene.file)
            .fail("the scene has no geometry: give 'geometry' files or inline 'polygons'");
}

/// `annual`: the blinds' materials, overrides of the scene's, parsed as `materials` entries.
void parse_annual(const Field& field, SceneSpec& spec) {
    field.expect_keys({"blinds"});
    if (field.has("blinds"))
        for (const auto& [name, entry] : field.child("blinds").members())
            spec.blinds.push_back(parse_material(entry, name));
}

/// The sky's `lightmap_mode`, on the sky and on the sun of a Perez sky (which makes its own).
void apply_sky_lightmap_mode(const Field& sky, Scene& scene) {
    const std::optional<LightmapMode> mode = parse_lightmap_mode(sky);
    if (!mode)
        return;
    scene.sky->lightmap_mode = *mode;
    const bool perez = sky.has("direct_normal_w_m2") || sky.has("direct_normal_lx");
    if (perez && scene.sun)
        scene.sun->lightmap_mode = *mode;
}

/// point_lights, site, sun, sky, sensors, camera and image, mesher, solver.
void parse_settings(const Field& root, const Vec3& up, SceneSpec& spec) {
    const double scale = spec.metres_per_unit;
    Scene& scene = spec.scene;
    if (root.has("point_lights")) {
        const Field lights = root.child("point_lights");
        for (std::size_t i = 0; i < lights.array_size(); ++i)
            scene.point_lights.push_back(parse_point_light(lights.element(i), scale));
    }
    const Daylight daylight = parse_daylight_frame(root, up);
    if (root.has("sun"))
        scene.sun = parse_sun(root.child("sun"), daylight);
    if (root.has("sky"))
        parse_sky(root.child("sky"), daylight, scene);
    if (root.has("sky"))
        apply_sky_lightmap_mode(root.child("sky"), scene);
    if (root.has("sensors"))
        parse_sensors(root.child("sensors"), scale, spec);
    if (root.has("camera"))
        scene.camera = parse_camera(root.child("camera"), scale, up);
    if (root.has("cameras"))
        parse_cameras(root.child("cameras"), scale, up, scene);
    if (root.has("image")) {
        if (!scene.camera)
            root.child("image").fail("'image' needs a 'camera'");
        parse_image(root.child("image"), *scene.camera);
        for (NamedCamera& named : scene.cameras)
            parse_image(root.child("image"), named.camera);
    }
    if (root.has("mesher"))
        scene.mesher = parse_mesher(root.child("mesher"), scale);
    if (root.has("solver"))
        scene.solver = parse_solver(root.child("solver"), scale);
    if (root.has("render"))
        parse_render(root, scale, scene);
    if (root.has("lightmap"))
        scene.lightmap = parse_lightmap(root.child("lightmap"));
    if (root.has("annual"))
        parse_annual(root.child("annual"), spec);
    if (root.has("probes"))
        scene.probes = parse_probes(root.child("probes"), scale);
    if (root.has("background")) {
        if (root.has("sky"))
            root.child("background")
                .fail("give 'background' or 'sky', not both (the sky is "
                      "what rays leaving the scene see)");
        scene.background = parse_background(root.child("background"));
    }
}

} // namespace

SceneSpec parse_scene_json(const std::string& text, const std::string& file_name) {
    const Json json = parse_json(text, file_name);
    const Field root(json, "", file_name);
    root.expect_keys({"name",           "units",     "up",           "geometry",
                      "polygons",       "materials", "point_lights", "sun",
                      "site",           "sky",       "sensors",      "grids",
                      "camera",         "image",     "mesher",       "solver",
                      "render",         "lightmap",  "background",   "emission_two_sided",
                      "smooth_objects", "annual",    "probes",       "cameras"});
    SceneSpec spec;
    spec.scene.file = file_name;
    if (root.has("name"))
        spec.scene.name = root.child("name").string();
    spec.metres_per_unit = parse_units(root);
    const Vec3 up = parse_up(root);
    spec.scene.up = up;
    parse_surfaces(root, spec);
    parse_settings(root, up, spec);
    parse_grids(root, up, spec);
    return spec;
}

} // namespace penumbra
