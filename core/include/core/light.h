#pragma once
// The light sources of a scene: one closed set of kinds, and the ids that name a source.
// Emissive polygons (area sources) are described by their material (core/scene.h); point
// lights and the sun here. Every stage that names a source (the mesher's shadow boundaries,
// the solver's light links) names it with a LightSource, or with its packed form LightId in
// arrays too large for the variant.

#include <compare>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>

#include "core/lightmap_mode.h"
#include "core/rgb.h"
#include "core/vec.h"

namespace penumbra {

/// \brief The cone of a spot light: full intensity within the beam half-angle, none beyond
///        the cut-off half-angle, and between them a smoothstep in cos θ (as pbrt-v4's
///        SpotLight), so that the intensity and its slope are continuous.
struct SpotCone {
    Vec3 direction{0, 0, -1}; ///< unit beam axis
    double beam_deg = 30;     ///< half-angle of full intensity, in [0, cutoff_deg]
    double cutoff_deg = 45;   ///< half-angle beyond which nothing is emitted, in (0, 180]
};

/// \brief A point light: isotropic, or a spot when \p spot is set. Its profile is the
///        intensity relative to \p intensity by direction; a goniometric (IES) table will be a
///        third kind of profile beside the isotropic one and the spot's cone, answering the
///        same profile functions.
struct PointLight {
    std::string name;
    Vec3 position; ///< metres
    Rgb intensity; ///< radiant intensity (on the axis for a spot), W/sr per channel
    std::optional<SpotCone> spot;
    LightmapMode lightmap_mode = LightmapMode::all; ///< what lightmaps bake of it (issue #29)

    /// \brief Intensity toward the unit direction \p unit_dir (from the light) relative to
    ///        \p intensity: 1 for an isotropic light, in [0, 1] for a spot.
    double profile(const Vec3& unit_dir) const;
    /// \brief The same as a function of cos θ to the spot's axis (1 for an isotropic light).
    double profile_cos(double cos_theta) const;
    /// \brief ∫ profile dω over the sphere, sr: 4π for an isotropic light, and for a spot
    ///        2π [(1 − cos beam) + (cos beam − cos cutoff) / 2] (the smoothstep integrates to
    ///        half its interval).
    double profile_solid_angle() const;
    /// \brief Total radiant flux, W per channel: intensity × profile_solid_angle().
    RgbD power() const;
};

/// \brief The sun: a disc of uniform radiance at infinity. Its direct irradiance on a surface
///        point of unit normal n is irradiance · max(0, cos θ) · V, with θ the angle between
///        n and \p direction and V the visible fraction of the disc (exact where the disc is
///        wholly above the surface's horizon: the cosine-weighted integral of a uniform disc is
///        its normal irradiance times the cosine to its centre).
struct Sun {
    Vec3 direction{0, 0, 1};             ///< unit, from the scene toward the disc's centre
    Rgb irradiance;                      ///< direct normal irradiance, W/m² per channel
    double angular_diameter_deg = 0.533; ///< in [0, 10]; 0 = parallel light (hard shadows)
    LightmapMode lightmap_mode = LightmapMode::all; ///< what lightmaps bake of it (issue #29)

    /// \brief Angular radius of the disc, radians.
    double angular_radius() const;
    /// \brief irradiance · max(0, dot(n, direction)): the unoccluded direct irradiance on a
    ///        surface of unit normal \p n, W/m² per channel.
    Rgb unoccluded(const Vec3& n) const;
};

/// \brief An emissive polygon (its material emits): the area source of Scene::polygons[polygon].
struct AreaSource {
    std::uint32_t polygon = 0;
    auto operator<=>(const AreaSource&) const = default;
};

/// \brief The point light Scene::point_lights[index].
struct PointSource {
    std::uint32_t index = 0;
    auto operator<=>(const PointSource&) const = default;
};

/// \brief The sun, Scene::sun.
struct SunSource {
    auto operator<=>(const SunSource&) const = default;
};

/// \brief The sky and its ground, Scene::sky: a source at infinity over the whole sphere of
///        directions (core/sky.h).
struct SkySource {
    auto operator<=>(const SkySource&) const = default;
};

/// \brief Names one light source of a scene.
using LightSource = std::variant<AreaSource, PointSource, SunSource, SkySource>;

/// \brief Whether \p source is at infinity (the sun, the sky): its features are directions.
bool at_infinity(const LightSource& source);

/// \brief "polygon 3", "point light 0", "the sun" or "the sky", for messages.
std::string describe(const LightSource& source);

/// \brief The integer discontinuities.vtp writes for \p source (its `source` cell array, as
///        documented in README.md): the polygon's index, −1 for the sun, −2 − i for point
///        light i. \throws InternalError for the sky, which has no code yet.
int source_code(const LightSource& source);

/// \brief A LightSource packed into 32 bits (its kind in the top two bits, its index
///        below), for arrays where the variant's 8 bytes would cost (the solver's light links).
class LightId {
public:
    /// \brief Packs \p source; throws InternalError if its index does not fit in 30 bits.
    explicit LightId(const LightSource& source);
    /// \brief The source it names.
    LightSource source() const;
    bool operator==(const LightId&) const = default;

private:
    std::uint32_t bits_ = 0;
};

} // namespace penumbra
