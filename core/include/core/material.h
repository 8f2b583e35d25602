#pragma once
// Materials: the diffuse part that the radiosity solver transports, and an optional
// non-diffuse part (glossy, mirror, dielectric, thin glass) for the final gather (issue #28)
// and glazing (issue #30). Thin glass is defined here once, so that the renderer and the
// daylight solver agree on it. The solver and the mesher read a material only through
// radiosity_response(), so adding a lobe does not touch them.

#include <optional>
#include <string>
#include <variant>

#include "core/lightmap_mode.h"
#include "core/rgb.h"

namespace penumbra {

/// \brief No Fresnel factor: a glossy lobe reflects its specular colour at every angle.
struct FresnelNone {};
/// \brief Schlick's approximation F0 + (1 − F0)(1 − cos θ)⁵, with the specular colour as F0.
struct FresnelSchlick {};
/// \brief The exact Fresnel reflectance of unpolarised light on a dielectric, scaled by the
///        specular colour.
struct FresnelDielectric {
    double ior = 1.5; ///< refractive index of the dielectric relative to the outside, > 0
};
/// \brief How a glossy lobe's reflectance varies with the angle of incidence.
using Fresnel = std::variant<FresnelNone, FresnelSchlick, FresnelDielectric>;

/// \brief GGX (Trowbridge–Reitz) microfacet reflection.
struct GgxGlossy {
    /// GGX's own width parameter α, in (0, 1]: 0.05 is a sharp highlight, 1 nearly diffuse
    /// (glTF's roughness r and MTL's Pr give α = r²).
    double alpha = 0.1;
    Rgb specular{1.0f}; ///< specular colour, each channel in [0, 1]
    Fresnel fresnel = FresnelNone{};
    /// True: the lobe is a coat over the material's diffuse part ("plastic"), which receives
    /// what the coat does not reflect. False: the lobe alone (a metal; its diffuse part black).
    bool diffuse_base = false;
};

/// \brief A perfect mirror.
struct Mirror {
    Rgb colour{1.0f}; ///< reflectance at every angle, each channel in [0, 1]
};

/// \brief A smooth dielectric interface that reflects (Fresnel) and refracts.
struct Dielectric {
    double ior = 1.5; ///< refractive index inside relative to outside (the back side's medium)
    /// True: the surfaces close a solid body of the medium, fronts outward, and a ray inside
    /// is followed through total internal reflection until it leaves. False: one interface,
    /// the medium unbounded behind it (a water surface).
    bool solid = true;
    /// Factor on the light of each refraction, per channel in [0, 1] (MTL `Tf`): 1 = clear.
    Rgb transmittance{1.0f};
};

/// \brief Thin glass as Radiance's `glass`: one surface standing for a pane's two parallel
///        faces. Both polarisations are averaged, the reflections between the faces summed,
///        and absorption along the refracted path goes as tn^(1/cos θt). The pane is
///        symmetric: cos θ is taken on either side.
struct ThinGlass {
    /// Transmissivity tn at normal incidence per channel, in [0, 1]: the fraction that one
    /// crossing of the pane's thickness leaves, before any surface reflection (Radiance's
    /// input; clear glass of 88 % normal transmittance has tn = 0.96).
    Rgb transmissivity{0.96f};
    double ior = 1.52; ///< refractive index n of the glass, > 1

    /// Fraction of the light arriving at cos θ (to the normal, in [0, 1]) that passes.
    Rgb transmittance(double cos_theta) const;
    /// Fraction of the light arriving at cos θ that the pane reflects (specularly).
    Rgb reflectance(double cos_theta) const;
    /// Fraction of uniform diffuse light (cosine-weighted over the hemisphere) that passes:
    /// 2 ∫₀¹ T(μ) μ dμ.
    Rgb hemispherical_transmittance() const;
};

/// \brief One channel of ThinGlass at cos θ (clamped to [0, 1]; grazing light all reflects).
struct ThinGlassResponse {
    double transmittance = 0;
    double reflectance = 1;
};
/// \brief One channel of ThinGlass: transmissivity \p tn, refractive index \p ior.
ThinGlassResponse thin_glass_response(double tn, double ior, double cos_theta);
/// \brief 2 ∫₀¹ T(μ) μ dμ of one channel of ThinGlass (composite Simpson in μ).
double thin_glass_hemispherical_transmittance(double tn, double ior);

/// \brief The non-diffuse part of a material: one lobe beside (or over) its diffuse part.
using Lobe = std::variant<GgxGlossy, Mirror, Dielectric, ThinGlass>;

/// \brief A material: its diffuse part, which radiosity transports, and an optional lobe.
///        Emission is the emitted radiance of the front side (and of the back side too when
///        emission_two_sided).
struct Material {
    std::string name;
    Rgb reflectance{0.5f}; ///< diffuse reflectance ρ, each channel in [0, 1)
    Rgb emission{};        ///< emitted radiance, W/(sr·m²)
    bool two_sided = true; ///< front and back are separate receiving elements
    bool emission_two_sided = false;
    /// If set, the loader scales emission so that all polygons of this material together emit
    /// this luminous flux (lm); emission then holds the colour until scaling.
    std::optional<double> emission_flux_lm;
    /// The non-diffuse part (scene key `type`). A metal (GgxGlossy without diffuse_base), a
    /// mirror, a dielectric and thin glass have no diffuse part: `reflectance` is ignored.
    std::optional<Lobe> lobe;
    /// Diffuse transmittance τ per channel: the fraction of the light arriving on either side
    /// that leaves the other side diffusely (Radiance's `trans`: blinds, diffusing glass).
    /// ρ + τ < 1 per channel; a material with τ > 0 is two-sided.
    Rgb diffuse_transmittance{};
    /// What lightmaps bake of its emission (issue #29); only emitting materials use it.
    LightmapMode lightmap_mode = LightmapMode::all;
};

/// \brief What the radiosity solver transports of a material: its diffuse part, and for
///        glazing the light that passes. Every non-diffuse reflection is the final gather's.
struct RadiosityResponse {
    Rgb reflectance; ///< diffuse reflectance ρ
    Rgb emission;    ///< emitted radiance of the front side, W/(sr·m²)
    bool two_sided = true;
    bool emission_two_sided = false;
    /// Hemispherical transmittance of thin glass; 0 for every other material.
    Rgb transmittance;
    /// Diffuse transmittance τ: a side's radiosity gains τ times the other side's irradiance.
    Rgb diffuse_transmittance;
    /// A lobe and no diffuse part, nor glazing's transmittance (a mirror, a metal, a
    /// dielectric): what the surface shows is traced by the renderer, and nothing reads the
    /// solution's light on it but its reported irradiance, which the solver refines less.
    bool specular_only = false;

    /// Whether the surface blocks all light: visibility, occluders and hidden regions count
    /// only such surfaces.
    bool opaque() const { return transmittance.is_black(); }
};

/// \brief The diffuse reflectance of \p m: `reflectance` without a lobe or under a coat
///        ("plastic"), black for a metal, a mirror, a dielectric and thin glass.
Rgb diffuse_reflectance(const Material& m);

/// \brief The thin glass of \p m, if it is glazing.
std::optional<ThinGlass> glazing_of(const Material& m);

/// \brief The radiosity response of \p m: the one function through which the mesher and the
///        solver read a material.
RadiosityResponse radiosity_response(const Material& m);

} // namespace penumbra
