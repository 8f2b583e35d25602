#pragma once
// The BSDF of a material at a surface point, for the renderer's final gather and photon map
// (issue #28). Built per hit from a Material and the shading normal; evaluates, gives the
// density of and samples incident directions. Conventions (as pbrt's): wo and wi are world
// unit vectors pointing away from the surface (wo toward the viewer or the previous vertex,
// wi toward the light); eval() returns f(wo, wi) |cos θi|, the cosine to the shading normal
// included, so that an estimate is L(wi) eval / pdf.
//
// Lobes: the material's diffuse part (Lambertian), GGX reflection (a metal, or a coat over the
// diffuse part: "plastic"), a perfect mirror, a smooth dielectric, thin glass. Opaque
// materials reflect alike on both sides when two_sided, and not at all on the back otherwise;
// the dielectric's front is its outside (normal outward); thin glass is symmetric. The
// geometric normal is not seen here: the renderer discards directions on the wrong side of
// it when shading normals are interpolated.

#include <cstdint>
#include <optional>
#include <variant>

#include "core/material.h"
#include "core/microfacet.h"
#include "core/rgb.h"
#include "core/vec.h"

namespace penumbra {

/// \brief What a path carries: radiance (camera paths: refraction scales radiance by
///        1/η², η = n_t/n_i) or importance/flux (photons: no scaling).
enum class TransportMode { radiance, importance };

/// \brief The lobe a sample came from.
enum class BsdfLobe : std::uint8_t {
    diffuse,               ///< the Lambertian part (the radiosity solution's share)
    glossy_reflection,     ///< GGX reflection
    specular_reflection,   ///< a delta reflection (mirror, glass)
    specular_transmission, ///< a delta transmission (refraction, or straight through thin glass)
};

/// \brief One sampled incident direction.
struct BsdfSample {
    Vec3 wi; ///< world, unit, away from the surface
    /// f |cos θi| / pdf; for a delta lobe, that lobe's reflectance or transmittance (radiance:
    /// scaled by 1/η²) over the probability of choosing it.
    Rgb weight;
    /// Solid-angle density of wi (sr⁻¹) for a non-delta lobe, the BSDF's whole density as
    /// pdf() gives it; for a delta lobe, the discrete probability of choosing the lobe.
    double pdf = 0;
    BsdfLobe lobe = BsdfLobe::diffuse;
    /// For a refraction, n_t / n_i of the interface crossed (> 1 entering the denser medium);
    /// 1 otherwise.
    double eta = 1;

    bool delta() const {
        return lobe == BsdfLobe::specular_reflection || lobe == BsdfLobe::specular_transmission;
    }
    bool transmission() const { return lobe == BsdfLobe::specular_transmission; }
};

/// \brief Lambertian reflection f = ρ/π.
struct LambertLobe {
    Rgb reflectance;
};

/// \brief A Fresnel factor of the form a + b (1 − cos)⁵ per channel: no Fresnel (b = 0) and
///        Schlick's; the coat of a plastic also approximates a dielectric's this way, which
///        keeps its albedo linear in (a, b) (core/src/coat_albedo.h).
struct LinearFresnel {
    Rgb a, b;
    Rgb at(double cos_i) const;
};

/// \brief The exact dielectric Fresnel factor scaled by a colour (a metal's FresnelDielectric).
struct ScaledDielectricFresnel {
    Rgb scale;
    double eta = 1.5;
};

/// \brief GGX reflection f = F(wo·m) D(m) G2(wo, wi) / (4 cos θo cos θi), m the half vector.
struct GgxLobe {
    GgxDistribution distribution;
    std::variant<LinearFresnel, ScaledDielectricFresnel> fresnel;

    Rgb fresnel_at(double cos_i) const;
};

/// \brief A GGX coat over a Lambertian base, after Kelemen & Szirmay-Kalos 2001 and Kulla &
///        Conty 2017: f = f_coat + ρ/π (1 − E(μo)) (1 − E(μi)) / (1 − E_avg), with E(μ) the
///        coat's directional albedo and E_avg = 2 ∫ E(μ) μ dμ. Reciprocal, and the base
///        reflects exactly ρ (1 − E(μo)) of what arrives from wo: what the coat does not
///        reflect. (Light the coat's masking loses is not given to the base.)
struct PlasticLobe {
    GgxLobe coat; ///< its fresnel is a LinearFresnel
    Rgb reflectance;
};

/// \brief A perfect mirror of constant colour.
struct MirrorLobe {
    Rgb colour;
};

/// \brief A smooth dielectric interface: Fresnel reflection and refraction, total internal
///        reflection; \p transmittance multiplies each refraction. Dielectric::solid does not
///        change the interface: it tells the renderer how to follow a ray inside.
struct DielectricLobe {
    double ior = 1.5; ///< n_inside / n_outside
    Rgb transmittance{1.0f};
};

/// \brief Thin glass (ThinGlass): delta reflection and straight transmission.
struct ThinGlassLobe {
    ThinGlass glass;
};

/// \brief A material's scattering at one point, in the frame of its shading normal.
class Bsdf {
public:
    using Lobes =
        std::variant<LambertLobe, GgxLobe, PlasticLobe, MirrorLobe, DielectricLobe, ThinGlassLobe>;

    /// \p shading_normal is unit; the material's front side faces it.
    Bsdf(const Material& material, const Vec3& shading_normal,
         TransportMode mode = TransportMode::radiance);

    /// f(wo, wi) |cos θi| of the non-delta lobes; 0 for a delta-only BSDF.
    Rgb eval(const Vec3& wo, const Vec3& wi) const;
    /// f(wo, wi) alone, for density estimation (photons arrive with their own cosine); 0 at
    /// grazing wi and for a delta-only BSDF.
    Rgb f(const Vec3& wo, const Vec3& wi) const;
    /// Solid-angle density with which sample() draws wi from wo; 0 for a delta-only BSDF.
    double pdf(const Vec3& wo, const Vec3& wi) const;
    /// Draws wi: \p u_lobe ∈ [0, 1) chooses a lobe, \p u ∈ [0, 1)² the direction within it.
    /// The choice: a plastic's coat with probability E / (E + ρ (1 − E)) (E the coat's albedo
    /// from wo, channels averaged), else its base; a dielectric reflects with probability F
    /// (Fresnel at wo), else refracts; thin glass reflects with probability R / (R + T)
    /// (channel means at wo). None when nothing scatters (a direction below the horizon, the
    /// back of a one-sided material, a zero weight).
    std::optional<BsdfSample> sample(const Vec3& wo, double u_lobe, const Vec2& u) const;

    /// Whether every lobe is a delta (mirror, dielectric, thin glass): eval and pdf are 0.
    bool is_delta() const;
    const Lobes& lobes() const { return lobes_; }
    const Frame& frame() const { return frame_; }

private:
    Frame frame_;
    Lobes lobes_;
    bool two_sided_ = true;
    TransportMode mode_ = TransportMode::radiance;
};

/// \brief The lobes of \p material as Bsdf builds them (the local model, without a frame).
Bsdf::Lobes bsdf_lobes(const Material& material);

} // namespace penumbra
