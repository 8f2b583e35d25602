#pragma once
// The GGX (Trowbridge–Reitz) microfacet distribution and the Fresnel factors of the BSDFs
// (core/bsdf.h). Directions are in a local frame whose z axis is the surface normal; the
// distribution is isotropic, so only θ enters D and Λ.

#include "core/vec.h"

#include <algorithm>

namespace penumbra {

/// \brief Isotropic GGX: normal distribution D, Smith's Λ and shadowing, and the sampling of
///        visible normals (Heitz 2018, "Sampling the GGX Distribution of Visible Normals").
///        Shadowing–masking is Smith's height-correlated G2 = 1 / (1 + Λ(wo) + Λ(wi)).
struct GgxDistribution {
    double alpha = 0.1; ///< width α > 0: the slope's RMS over √2

    /// D(m), normalised so that ∫ D(m) (m · n) dm = 1 over the hemisphere.
    double d(const Vec3& m) const;
    /// Smith's Λ(w) = (√(1 + α² tan² θ) − 1) / 2.
    double lambda(const Vec3& w) const;
    /// Masking of one direction, 1 / (1 + Λ(w)); 0 below the horizon.
    double g1(const Vec3& w) const;
    /// Height-correlated shadowing–masking of a reflection pair (both above the horizon).
    double g2(const Vec3& wo, const Vec3& wi) const;
    /// Density of visible normals seen from \p wo (wo.z > 0): G1(wo) max(0, wo·m) D(m) / wo.z.
    double visible_normal_pdf(const Vec3& wo, const Vec3& m) const;
    /// A normal drawn from visible_normal_pdf by \p u ∈ [0, 1)² (Heitz 2018's method: the
    /// view is stretched to α = 1, where visible normals are a disc projected onto a
    /// hemisphere). Requires wo.z > 0.
    Vec3 sample_visible_normal(const Vec3& wo, const Vec2& u) const;
};

/// \brief Fresnel reflectance of unpolarised light at a smooth dielectric interface, for
///        light arriving at \p cos_i (to the normal on the side it comes from, > 0 is the
///        side of the outer medium) with relative index \p eta = n_inside / n_outside. 1 under
///        total internal reflection.
double fresnel_dielectric(double cos_i, double eta);

/// \brief Schlick's approximation F0 + (1 − F0)(1 − cos)⁵ for one channel.
inline double fresnel_schlick(double f0, double cos_i) {
    const double m = std::clamp(1.0 - cos_i, 0.0, 1.0);
    const double m2 = m * m;
    return f0 + (1.0 - f0) * m2 * m2 * m;
}

/// \brief Mirror reflection of \p w about \p n (both unit; the result is on w's side of n).
inline Vec3 reflect(const Vec3& w, const Vec3& n) {
    return n * (2.0 * dot(w, n)) - w;
}

} // namespace penumbra
