#pragma once
// Real spherical harmonics up to band 2 for light probes and directional lightmaps (issue #29).
//
// Convention: the real orthonormal basis (∫ Y_lm Y_l'm' dω = δ), in the order
//   Y00, Y1−1, Y10, Y11, Y2−2, Y2−1, Y20, Y21, Y22
//   ∝ 1, y, z, x, xy, yz, 3z² − 1, xz, x² − y²
// of a unit direction (x, y, z) in the scene's (output) axes, with the Condon–Shortley phase
// left out (every constant positive, as Sloan's "Stupid SH tricks" and most engines write
// them). Radiance coefficients L_lm = ∫ L(ω) Y_lm(ω) dω over directions ω *toward* the light;
// the irradiance of a surface facing n is then (Ramamoorthi & Hanrahan 2001)
//   E(n) = Σ Â_l L_lm Y_lm(n),  Â_0 = π, Â_1 = 2π/3, Â_2 = π/4.
// docs/lightmaps.md describes where probes and directional lightmaps use it.

#include <array>

#include "core/rgb.h"
#include "core/vec.h"

namespace penumbra::lightmap {

/// Coefficients of bands 0 and 1 (L1) and of bands 0 to 2 (L2).
inline constexpr int k_sh_l1_count = 4;
inline constexpr int k_sh_l2_count = 9;

/// \brief The nine basis functions at the unit direction \p d, in the order of the file comment.
std::array<double, k_sh_l2_count> sh_basis_l2(const Vec3& d);

/// \brief Â_l of the clamped cosine: the factor that turns band l of radiance into band l of
///        irradiance (π, 2π/3, π/4 for l = 0, 1, 2).
double sh_cosine_lobe_band(int l);

/// \brief Band of coefficient \p k (0 for k = 0, 1 for k in 1..3, 2 for k in 4..8).
constexpr int sh_band(int k) {
    return k == 0 ? 0 : (k < 4 ? 1 : 2);
}

/// \brief RGB coefficients of a function on the sphere, bands 0 to 2.
struct ShL2 {
    std::array<RgbD, k_sh_l2_count> c{};

    /// \brief Adds \p weight × \p radiance × Y_lm(\p d) to every coefficient: one quadrature
    ///        sample of the projection (weight = its solid angle), or with weight 1 a delta of
    ///        irradiance \p radiance (a point light or the sun) arriving from \p d.
    void add(const Vec3& d, const RgbD& radiance, double weight);
    /// \brief The value Σ c_k Y_k(\p n) at the unit direction \p n.
    RgbD evaluate(const Vec3& n) const;
    /// \brief Bands 0 and 1 only evaluated at \p n.
    RgbD evaluate_l1(const Vec3& n) const;
};

/// \brief The irradiance coefficients of radiance coefficients \p radiance: each band l times
///        Â_l (sh_cosine_lobe_band), so that irradiance.evaluate(n) is E(n).
ShL2 irradiance_from_radiance(const ShL2& radiance);

} // namespace penumbra::lightmap
