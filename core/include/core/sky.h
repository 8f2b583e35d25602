#pragma once
// The sky and the ground: one source at infinity over the whole sphere of directions, the
// sky's luminance above the horizon and a uniform ground below it (issue #30). The luminance
// models are the CIE's (ISO 15469:2004 / CIE S 011 general skies, the CIE standard overcast
// sky) and Perez's all-weather sky; the sun itself stays Scene::sun (core/light.h). Directions
// are the scene's: Compass says which way is up and which way is north.

#include <optional>
#include <span>
#include <variant>

#include "core/light.h"
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
///        angle (and the day of the year, for the extraterrestrial irradiance); see
///        perez_sky_and_sun().
struct PerezSky {
    double clearness = 1;     ///< ε, in [1, 12.01)
    double brightness = 0.01; ///< Δ, in [0.01, 0.6]
};

/// \brief Radiance's intermediate sky (skybright.cal type 4, written by gensky -i/+i), which
///        Radiance calls the CIE intermediate sky; it is none of ISO 15469's 15 general skies.
///        Its luminance relative to the zenith's is radiance_intermediate_sky(); it depends on
///        the sun's position.
struct RadianceIntermediateSky {};

/// \brief Perez's all-weather sky given by its five coefficients a … e directly, as gendaylit
///        prints them for perezlum.cal (Radiance scenes): l_v = (1 + a exp(b / cos Z))
///        (1 + c exp(d γ) + e cos² γ), relative to its value at the zenith.
struct PerezCoefficientsSky {
    double a = 0, b = 0, c = 0, d = 0, e = 0; ///< all 0: a uniform sky
};

/// \brief The relative luminance distribution of a sky.
using SkyModel = std::variant<UniformSky, CieOvercastSky, CieGeneralSky, PerezSky,
                              RadianceIntermediateSky, PerezCoefficientsSky>;

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
///        rgb.h). Built by make_sky() from a horizontal illuminance or a zenith luminance, or by
///        perez_sky_and_sun() from weather data. A plain value: thread-safe to read.
struct Sky {
    SkyModel model = CieOvercastSky{};
    Compass compass;
    /// Unit, toward the sun: the general and Perez skies depend on it (also when Scene::sun is
    /// absent, as under an overcast sky).
    Vec3 sun_direction{0, 0, 1};
    double zenith_radiance = 0; ///< W/(sr·m²) at the zenith
    Rgb colour{1.0f};           ///< relative colour of the sky's radiance (luminance 1)
    Horizon horizon = Horizon::sharp;
    /// Radiance of the uniform grey ground hemisphere below the horizon, W/(sr·m²) in every
    /// channel; unset: nothing below the horizon (the scene's own ground geometry receives the
    /// sky), and Horizon::radiance_blend has nothing to blend with (the horizon stays sharp).
    std::optional<double> ground_radiance;
    LightmapMode lightmap_mode = LightmapMode::all; ///< what lightmaps bake of it (issue #29)

    /// \brief Radiance arriving from the unit direction \p dir (pointing away from the scene,
    ///        toward the sky or the ground), W/(sr·m²) per channel. Sharp horizon: the sky
    ///        above (dir·up > 0), the ground at and below. radiance_blend (with a ground):
    ///        skybright.cal's mean (w_s sky + w_g ground) / (w_s + w_g) in every direction,
    ///        w_s = (Dz + 1.01)^10, w_g = (Dz + 1.01)^−10, Dz = dir·up, with the sky's
    ///        formula continued below the horizon as relative_luminance() does.
    Rgb radiance(const Vec3& dir) const;
    /// \brief radiance() of each of \p dirs into \p out (the same size), with the sky's
    ///        constants (normalisation, Perez's coefficients) computed once: for many
    ///        directions (a single radiance() call costs about 0.2 µs).
    void radiance(std::span<const Vec3> dirs, std::span<Rgb> out) const;
    /// \brief Luminance relative to the zenith's, without ground or blend. Above the horizon
    ///        the model's formula; at and below it the continuation the blend uses (as
    ///        skybright.cal and perezlum.cal do): the CIE gradation takes its horizon value,
    ///        Perez's is evaluated at Dz = max(Dz, 0.01), the overcast sky keeps (1 + 2 Dz)/3.
    ///        Never negative (Perez's formula can be, and is clamped at 0 as gendaymtx does).
    double relative_luminance(const Vec3& dir) const;
    /// \brief The sky's unobstructed horizontal illuminance, lx: ∫ L cos θ dω over the upper
    ///        hemisphere (sky only, no sun; with Horizon::radiance_blend, the blended values),
    ///        by quadrature: about 1e-5 relative for the CIE skies, 1e-4 for Perez's; about
    ///        1 ms.
    double horizontal_illuminance_lx() const;
    /// \brief ∫ relative_luminance cos θ dω over the upper hemisphere, sr: E_h / L_z of the
    ///        model alone (sharp horizon, no ground, no colour): π for a uniform sky.
    double horizontal_illuminance_per_zenith_luminance() const;
};

/// \brief A sky's level: its unobstructed horizontal illuminance (the sky alone, no sun).
struct HorizontalIlluminance {
    double lx = 10000;
};
/// \brief A sky's level: its zenith luminance.
struct ZenithLuminance {
    double cd_m2 = 0;
};
using SkyLevel = std::variant<HorizontalIlluminance, ZenithLuminance>;

/// \brief What make_sky() needs to build a sky from a model.
struct SkyDescription {
    SkyModel model = CieOvercastSky{};
    Compass compass;
    Vec3 sun_direction{0, 0, 1}; ///< unit, toward the sun (for CieGeneralSky and PerezSky)
    SkyLevel level;
    /// Reflectance ρ_g of the uniform ground hemisphere, in [0, 1]; unset: no ground (the
    /// scene's own geometry is the ground).
    std::optional<double> ground_reflectance = 0.2;
    Horizon horizon = Horizon::sharp;
    Rgb colour{1.0f}; ///< relative colour of the sky; rescaled to luminance 1
};

/// \brief The sky of \p description. A HorizontalIlluminance level scales the model so that
///        its horizontal_illuminance_per_zenith_luminance() (the sharp sky, as gensky -B and
///        CIE 171 normalise) gives that illuminance; with Horizon::radiance_blend the blended
///        sky's own horizontal_illuminance_lx() then differs slightly, as in Radiance. The
///        ground's radiance is ρ_g E_h / π with E_h the global horizontal illuminance, the sky's
///        plus \p sun_horizontal_illuminance_lx (the sun's direct light on the unobstructed
///        horizontal: see horizontal_illuminance_lx(const Sun&, const Compass&)), converted at
///        179 lm/W (Radiance's convention).
/// \throws InternalError for a CIE type outside [1, 15], a negative level or reflectance.
Sky make_sky(const SkyDescription& description, double sun_horizontal_illuminance_lx = 0);

/// \brief The sun's direct illuminance on an unobstructed horizontal surface, lx:
///        its normal illuminance × max(0, sin altitude).
double horizontal_illuminance_lx(const Sun& sun, const Compass& compass);

/// \brief One hour's solar components as weather files give them, radiometric (W/m²).
struct SolarIrradiance {
    double direct_normal_w_m2 = 0;
    double diffuse_horizontal_w_m2 = 0;
};
/// \brief One hour's solar components, photometric (lx).
struct SolarIlluminance {
    double direct_normal_lx = 0;
    double diffuse_horizontal_lx = 0;
};
using SolarComponents = std::variant<SolarIrradiance, SolarIlluminance>;

/// \brief A Perez sky and the sun that goes with it.
struct PerezSkyAndSun {
    Sky sky;
    /// Unset when the sun is at or below the horizon or its direct illuminance is 0.
    std::optional<Sun> sun;
};

/// \brief The Perez all-weather sky and the sun of one hour, as Radiance's gendaylit builds
///        them (gendaymtx the same): ε and Δ from the direct-normal and diffuse-horizontal
///        irradiance (Perez et al. 1990: Kasten's air mass, 1367 W/m² times the eccentricity
///        correction of \p day_of_year), clamped to ε ∈ [1, 12.01), Δ ∈ [0.01, 0.6];
///        illuminances from Perez et al. 1990's diffuse and direct luminous efficacies with
///        2 cm of precipitable water (gendaylit's default); irradiance from illuminance input
///        by iterating those efficacies. The sky's luminance integrates to the diffuse
///        horizontal illuminance (sharp sky, as make_sky()); the sun's normal irradiance is
///        the direct normal illuminance / 179 lm/W in every channel (Radiance's convention:
///        radiometric values carry the luminous ones at 179 lm/W), with a 0.533° disc. The
///        ground: ρ_g × (diffuse + direct × sin altitude) / (π 179) as gendaymtx computes it.
///        A sun below the horizon is taken at the horizon for the sky's shape (gendaymtx
///        does the same); no diffuse light gives a black sky.
/// \param sun_direction unit, toward the sun, in the compass's axes
/// \param day_of_year 1–366
/// \throws InternalError for negative components or a day outside [1, 366].
PerezSkyAndSun perez_sky_and_sun(const SolarComponents& weather, const Compass& compass,
                                 const Vec3& sun_direction, int day_of_year,
                                 std::optional<double> ground_reflectance = 0.2,
                                 Horizon horizon = Horizon::sharp);

} // namespace penumbra
