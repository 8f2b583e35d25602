#pragma once
// The sky and the ground: one source at infinity over the whole sphere of directions, the
// sky's luminance above the horizon and a uniform ground below it (issue #30). The luminance
// models are the CIE's (ISO 15469:2004 / CIE S 011 general skies, the CIE standard overcast
// sky) and Perez's all-weather sky; the sun itself stays Scene::sun (core/light.h). Directions
// are the scene's: Compass says which way is up and which way is north.

#include <optional>
#include <variant>

#include "core/rgb.h"
#include "core/vec.h"

namespace penumbra {

/// \brief The scene's up and north directions (unit, perpendicular). Azimuths are measured
///        clockwise from north seen from above (east = 90°), as EPW files and NOAA use.
struct Compass {
    Vec3 up{0, 0, 1};
    Vec3 north{0, 1, 0};

    /// \brief East (north × up): seen from above, 90° clockwise from north.
    Vec3 east() const;
    /// \brief The unit direction of altitude \p altitude_deg above the horizon and azimuth
    ///        \p azimuth_deg clockwise from north.
    Vec3 direction(double altitude_deg, double azimuth_deg) const;
};

/// \brief A sky of the same luminance in every direction above the horizon.
struct UniformSky {};

/// \brief The CIE standard overcast sky (Moon & Spencer 1942; CIE S 003):
///        L(θ) = L_z (1 + 2 cos θ) / 3, θ the zenith angle. E_h = (7π/9) L_z.
struct CieOvercastSky {};

/// \brief One of the 15 CIE general skies of ISO 15469:2004 / CIE S 011/E:2003, by its number
///        in the standard's Table 1 (1 = overcast, steep gradation … 15 = cloudless turbid,
///        broad corona); its relative luminance depends on the sun's position.
struct CieGeneralSky {
    int type = 12; ///< in [1, 15]; 12 is the CIE standard clear sky (low turbidity)
};

/// \brief Perez's all-weather sky (Perez, Seals & Michalsky 1993) for one hour's weather:
///        its five coefficients follow from the sky's clearness ε and brightness Δ, which
///        follow from the direct-normal and diffuse-horizontal irradiance and the sun's zenith
///        angle (and the day of the year, for the extraterrestrial irradiance).
struct PerezSky {
    double clearness = 1;  ///< ε, ≥ 1
    double brightness = 0; ///< Δ, ≥ 0
};

/// \brief Radiance's intermediate sky (skybright.cal type 4, written by gensky -i/+i), which
///        Radiance calls the CIE intermediate sky; it is none of ISO 15469's 15 general skies.
///        Its luminance relative to the zenith's is radiance_intermediate_sky(); it depends on
///        the sun's position.
struct RadianceIntermediateSky {};

/// \brief The relative luminance distribution of a sky.
using SkyModel =
    std::variant<UniformSky, CieOvercastSky, CieGeneralSky, PerezSky, RadianceIntermediateSky>;

/// \brief RadianceIntermediateSky's luminance relative to its zenith's, at zenith angle
///        \p zenith_angle and angle \p sun_angle from the sun, for the sun at zenith angle
///        \p sun_zenith_angle (radians; the direction above the horizon).
double radiance_intermediate_sky(double zenith_angle, double sun_angle, double sun_zenith_angle);

/// \brief How the sky meets the ground.
enum class Horizon {
    sharp,          ///< sky above the horizon, ground below (CIE 171:2006 test cases)
    radiance_blend, ///< Radiance's skybright.cal: a weighted mean of the two near the horizon
};

/// \brief A sky and its ground, resolved to absolute radiance (W/(sr·m²); luminance / 179 lm/W,
///        rgb.h). Built by the scene loader from what the scene gives (a horizontal
///        illuminance, a zenith luminance, or weather data): see make_sky().
struct Sky {
    SkyModel model = CieOvercastSky{};
    Compass compass;
    /// Unit, toward the sun: the general and Perez skies depend on it (also when Scene::sun is
    /// absent, as under an overcast sky).
    Vec3 sun_direction{0, 0, 1};
    double zenith_radiance = 0; ///< W/(sr·m²) at the zenith
    Rgb colour{1.0f};           ///< relative colour of the sky's radiance (luminance 1)
    Horizon horizon = Horizon::sharp;
    /// Radiance of the uniform ground hemisphere below the horizon, W/(sr·m²); unset: nothing
    /// below the horizon (the scene's own ground geometry receives the sky).
    std::optional<double> ground_radiance;

    /// \brief Radiance arriving from the unit direction \p dir (pointing away from the scene,
    ///        toward the sky or the ground), W/(sr·m²) per channel.
    Rgb radiance(const Vec3& dir) const;
    /// \brief Luminance relative to the zenith's, above the horizon (no ground, no blend).
    double relative_luminance(const Vec3& dir) const;
    /// \brief The sky's unobstructed horizontal illuminance, lx: ∫ L cos θ dω over the upper
    ///        hemisphere (sky only, no sun; with Horizon::radiance_blend, the blended values).
    double horizontal_illuminance_lx() const;
};

} // namespace penumbra
