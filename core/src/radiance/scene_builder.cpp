// Radiance primitives to scene data. Surfaces are polygons of a material; `source` primitives
// are the sun (a light or glow disc of at most 10°) or a hemisphere of 180° toward the zenith
// (the sky) or the nadir (the ground), of constant radiance or driven by skybright.cal.

#include "scene_builder.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "core/rgb.h"

namespace penumbra::radiance {

namespace {

constexpr double k_pi = 3.14159265358979323846;
/// The widest source taken as the sun, degrees (Sun::angular_diameter_deg's range).
constexpr double k_max_sun_diameter_deg = 10;

/// Radiance's grey value of a colour: its luminance over 179 lm/W (rgb.h).
double grey(const Rgb& c) {
    return to_photometric(c) / k_luminous_efficacy_lm_per_w;
}

bool same_arguments(const Primitive& a, const Primitive& b) {
    return a.modifier == b.modifier && a.type == b.type && a.strings == b.strings &&
           a.integers == b.integers && a.reals == b.reals;
}

/// Solid angle of a cone of full angle \p diameter_deg, sr.
double cone_solid_angle(double diameter_deg) {
    return 2 * k_pi * (1 - std::cos(diameter_deg * k_pi / 360.0));
}

Sky sky_of_constant_glow(const Material& glow, const Affine& xf) {
    Sky sky;
    sky.model = UniformSky{};
    sky.compass = {.up = xf.direction({0, 0, 1}), .north = xf.direction({0, 1, 0})};
    sky.sun_direction = sky.compass.up;
    sky.zenith_radiance = grey(glow.emission);
    if (sky.zenith_radiance > 0)
        sky.colour = glow.emission / float(sky.zenith_radiance);
    sky.horizon = Horizon::sharp;
    return sky;
}

Sky sky_of_function(const SkyGlow& glow) {
    const SkyFunction& f = glow.function;
    Sky sky;
    sky.model = f.model;
    sky.compass = f.compass;
    sky.sun_direction = f.sun_direction;
    const double scale = grey(glow.colour);
    sky.zenith_radiance = f.zenith_radiance * scale;
    if (scale > 0)
        sky.colour = glow.colour / float(scale);
    sky.horizon = Horizon::radiance_blend; // skybright.cal's weighted mean near the horizon
    return sky;
}

} // namespace

void SceneBuilder::add(const Primitive& p, const Affine& xf, bool invert) {
    if (p.type == "polygon")
        return add_polygon(p, xf, invert);
    if (p.type == "source")
        return add_source(p, xf);
    if (p.type == "brightfunc") {
        if (p.modifier != "void")
            fail(p.where, fmt::format("brightfunc '{}': its modifier must be void, got '{}'", p.id,
                                      p.modifier));
        return define(p, sky_function_from(p, xf));
    }
    std::optional<SurfaceMaterial> material = material_from(p);
    if (!material)
        fail(p.where,
             fmt::format("primitive '{}' of type '{}' is not supported (supported: polygon, "
                         "source, plastic, metal, glass, trans, light, glow, illum, brightfunc)",
                         p.id, p.type));
    if (p.modifier == "void")
        return define(p, std::move(*material));
    const auto* function =
        p.type == "glow" ? std::get_if<SkyFunction>(&modifier_of(p).modifier) : nullptr;
    if (!function)
        fail(p.where, fmt::format("{} '{}': its modifier must be void (patterns and textures are "
                                  "not supported), got '{}'",
                                  p.type, p.id, p.modifier));
    define(p, SkyGlow{*function, material->material.emission});
}

void SceneBuilder::define(const Primitive& p, Modifier modifier) {
    const auto [it, added] = modifiers_.try_emplace(p.id, Definition{std::move(modifier), p});
    if (!added && !same_arguments(it->second.primitive, p))
        fail(p.where, fmt::format("{} '{}' is defined again differently (first at {}): a name "
                                  "names one modifier",
                                  p.type, p.id, describe(it->second.primitive.where)));
}

const SceneBuilder::Definition& SceneBuilder::modifier_of(const Primitive& p) const {
    if (p.modifier == "void")
        fail(p.where,
             fmt::format("{} '{}' has no modifier (void): give it a material", p.type, p.id));
    const auto it = modifiers_.find(p.modifier);
    if (it == modifiers_.end())
        fail(p.where, fmt::format("{} '{}': unknown modifier '{}' (modifiers must be defined "
                                  "before their use, in the same or an earlier geometry file)",
                                  p.type, p.id, p.modifier));
    return it->second;
}

void SceneBuilder::add_polygon(const Primitive& p, const Affine& xf, bool invert) {
    if (!p.strings.empty() || !p.integers.empty() || p.reals.size() < 9 || p.reals.size() % 3)
        fail(p.where, fmt::format("polygon '{}': expects 0 string, 0 integer and 3 × n ≥ 9 real "
                                  "arguments (the vertices), got {}, {} and {}",
                                  p.id, p.strings.size(), p.integers.size(), p.reals.size()));
    const auto* surface = std::get_if<SurfaceMaterial>(&modifier_of(p).modifier);
    if (!surface)
        fail(p.where,
             fmt::format("polygon '{}': modifier '{}' is not a material", p.id, p.modifier));
    const Material& material = surface->material;
    auto [it, added] =
        geometry_materials_.try_emplace(material.name, std::uint32_t(geometry_.materials.size()));
    if (added)
        geometry_.materials.push_back(material);
    Polygon polygon{.material = it->second, .name = p.id, .source = describe(p.where)};
    for (std::size_t i = 0; i < p.reals.size(); i += 3)
        polygon.vertices.push_back(xf.point(Vec3(p.reals[i], p.reals[i + 1], p.reals[i + 2])) *
                                   metres_per_unit_);
    if (xf.mirrors() != invert)
        std::reverse(polygon.vertices.begin(), polygon.vertices.end());
    geometry_.polygons.push_back(std::move(polygon));
}

void SceneBuilder::add_source(const Primitive& p, const Affine& xf) {
    expect_arguments(p, 0, {4}, "x y z angle");
    const Vec3 axis(p.reals[0], p.reals[1], p.reals[2]);
    const double angle = p.reals[3];
    if (!(length(axis) > 0) || !(angle > 0 && angle <= 360))
        fail(p.where, fmt::format("source '{}': the direction must be non-zero and the angle in "
                                  "(0, 360], got {}",
                                  p.id, angle));
    const Vec3 direction = xf.direction(axis);
    const Modifier& modifier = modifier_of(p).modifier;
    const auto* emitter = std::get_if<SurfaceMaterial>(&modifier);
    if (emitter && emitter->emitter && angle <= k_max_sun_diameter_deg)
        return add_sun(p, direction, emitter->material);
    const bool hemisphere = angle == 180 && axis.x == 0 && axis.y == 0;
    if (emitter && emitter->emitter && hemisphere)
        return add_hemisphere(p, axis.z > 0, sky_of_constant_glow(emitter->material, xf),
                              grey(emitter->material.emission));
    const auto* glow = std::get_if<SkyGlow>(&modifier);
    // The function's zenith is where its own file's `!xform` put it.
    const double along_zenith = glow ? dot(direction, glow->function.compass.up) : 0;
    if (glow && angle == 180 && std::abs(along_zenith) > 1 - 1e-9)
        return add_hemisphere(p, along_zenith > 0, sky_of_function(*glow),
                              glow->function.ground_radiance * grey(glow->colour));
    fail(p.where,
         fmt::format("source '{}': a source is the sun (a light or glow of at most {}°) or a sky "
                     "or ground hemisphere (a glow, 180°, toward 0 0 1 or 0 0 −1); got {}° of "
                     "modifier '{}'",
                     p.id, k_max_sun_diameter_deg, angle, p.modifier));
}

void SceneBuilder::add_sun(const Primitive& p, const Vec3& direction, const Material& light) {
    if (sources_.sun)
        fail(p.where, fmt::format("source '{}': a second sun (the first at {})", p.id,
                                  describe(sources_.sun_where)));
    const double diameter_deg = p.reals[3];
    // The disc's uniform radiance times its solid angle: its normal irradiance.
    sources_.sun = Sun{.direction = direction,
                       .irradiance = light.emission * float(cone_solid_angle(diameter_deg)),
                       .angular_diameter_deg = diameter_deg};
    sources_.sun_where = p.where;
}

void SceneBuilder::add_hemisphere(const Primitive& p, bool up, Sky sky, double ground_radiance) {
    if (up) {
        if (sources_.sky)
            fail(p.where, fmt::format("source '{}': a second sky hemisphere (the first at {})",
                                      p.id, describe(sources_.sky_where)));
        sources_.sky = std::move(sky);
        sources_.sky_where = p.where;
        return;
    }
    if (ground_)
        fail(p.where, fmt::format("source '{}': a second ground hemisphere (the first at {})", p.id,
                                  describe(ground_->where)));
    ground_ = Ground{ground_radiance, p.where};
}

ImportedGeometry SceneBuilder::take_geometry() {
    geometry_materials_.clear();
    return std::exchange(geometry_, ImportedGeometry{});
}

Sources SceneBuilder::sources() const {
    Sources result = sources_;
    if (!ground_)
        return result;
    if (!result.sky)
        fail(ground_->where, "a ground hemisphere needs a sky hemisphere (a source of 180° "
                             "toward 0 0 1)");
    result.sky->ground_radiance = ground_->radiance;
    return result;
}

} // namespace penumbra::radiance
