// Spherical harmonics of probes and directional lightmaps (issue #29) against closed forms:
// orthonormality, a furnace (uniform radiance), a single delta light and its L2 ringing.

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "lightmap/sh.h"

namespace penumbra {
namespace {

using lightmap::ShL2;

// Midpoint quadrature over n × 2n equal-area cells of the sphere (uniform in z and φ).
template <typename Fn> void for_each_cell(int n, Fn&& fn) {
    const double weight = 4.0 * k_pi / (2.0 * n * n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < 2 * n; ++j) {
            const double z = -1.0 + (i + 0.5) * 2.0 / n, phi = (j + 0.5) * k_pi / n;
            const double r = std::sqrt(1.0 - z * z);
            fn(Vec3(r * std::cos(phi), r * std::sin(phi), z), weight);
        }
}

std::vector<Vec3> test_normals() {
    std::vector<Vec3> out{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int k = 0; k < 20; ++k) {
        const double z = -0.95 + 0.1 * k, phi = 2.39996 * k; // a golden-angle spiral
        const double r = std::sqrt(1 - z * z);
        out.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
    }
    return out;
}

TEST(Sh, BasisIsOrthonormalAndOrderedAsOneYZX) {
    double gram[9][9] = {};
    for_each_cell(400, [&](const Vec3& d, double w) {
        const auto y = lightmap::sh_basis_l2(d);
        for (int a = 0; a < 9; ++a)
            for (int b = 0; b < 9; ++b)
                gram[a][b] += w * y[std::size_t(a)] * y[std::size_t(b)];
    });
    for (int a = 0; a < 9; ++a)
        for (int b = 0; b < 9; ++b)
            EXPECT_NEAR(gram[a][b], a == b ? 1.0 : 0.0, 1e-4) << a << ", " << b;
    // Band 1 is ∝ (y, z, x): the basis at +y, +z, +x picks coefficient 1, 2, 3.
    EXPECT_GT(lightmap::sh_basis_l2(Vec3(0, 1, 0))[1], 0.0);
    EXPECT_GT(lightmap::sh_basis_l2(Vec3(0, 0, 1))[2], 0.0);
    EXPECT_GT(lightmap::sh_basis_l2(Vec3(1, 0, 0))[3], 0.0);
    EXPECT_NEAR(lightmap::sh_basis_l2(Vec3(1, 0, 0))[1], 0.0, 1e-15);
}

// A furnace: uniform radiance L from every direction gives L00 = 2√π L, no other band, and
// the irradiance π L on a surface facing any way.
TEST(Sh, UniformRadianceGivesOnlyBandZeroAndPiL) {
    const RgbD l(0.5, 1.0, 2.0);
    ShL2 radiance;
    for_each_cell(64, [&](const Vec3& d, double w) { radiance.add(d, l, w); });
    EXPECT_NEAR(radiance.c[0].g, 2.0 * std::sqrt(k_pi) * l.g, 1e-12);
    for (int k = 1; k < 9; ++k)
        EXPECT_NEAR(radiance.c[std::size_t(k)].g, 0.0, 1e-3 * l.g) << "coefficient " << k;
    const ShL2 e = lightmap::irradiance_from_radiance(radiance);
    for (const Vec3& n : test_normals()) {
        EXPECT_NEAR(e.evaluate(n).r, k_pi * l.r, 1e-3 * k_pi * l.r);
        EXPECT_NEAR(e.evaluate(n).b, k_pi * l.b, 1e-3 * k_pi * l.b);
    }
}

// A delta of irradiance I from d0 (a point light): L_lm = I Y_lm(d0), so
// E_L2(n) = I Σ_l Â_l (2l + 1)/(4π) P_l(cos γ) = I [1/4 + cos γ / 2 + (5/32)(3 cos² γ − 1)]
// (addition theorem), γ the angle between n and d0. The band-0 term, I/4 (the mean of E over
// all n), is exact; facing the light E_L2 = 1.0625 I against the true I; over the facing
// hemisphere L2's ringing keeps |E_L2 − I cos γ| ≤ 3I/32 (at grazing, cos γ = 0).
TEST(Sh, DeltaLightMatchesTheAdditionTheoremAndRingsWithinThreeThirtySeconds) {
    const Vec3 d0 = normalize(Vec3(0.3, -0.5, 0.8));
    const double i = 2.0;
    ShL2 radiance;
    radiance.add(d0, RgbD(i, i, i), 1.0);
    const ShL2 e = lightmap::irradiance_from_radiance(radiance);
    EXPECT_NEAR(e.c[0].g * lightmap::sh_basis_l2(d0)[0], i / 4, 1e-14);
    EXPECT_NEAR(e.evaluate(d0).g, 1.0625 * i, 1e-12);
    for (const Vec3& n : test_normals()) {
        const double c = dot(n, d0);
        const double expected = i * (0.25 + 0.5 * c + 5.0 / 32.0 * (3 * c * c - 1));
        EXPECT_NEAR(e.evaluate(n).g, expected, 1e-12);
        if (c >= 0) {
            EXPECT_LE(std::abs(e.evaluate(n).g - i * c), 3.0 / 32.0 * i + 1e-12);
        }
    }
}

// Bands 0 and 1 alone give E(n) = π L00 Y00 + (2π/3) Σ L1m Y1m(n) (directional lightmaps).
TEST(Sh, BandsZeroAndOneEvaluateAsTheDirectionalLightmapFormula) {
    const Vec3 d0 = normalize(Vec3(-0.2, 0.4, 0.9));
    ShL2 radiance;
    radiance.add(d0, RgbD(1, 1, 1), 1.0);
    const ShL2 e = lightmap::irradiance_from_radiance(radiance);
    for (const Vec3& n : test_normals()) {
        const auto y = lightmap::sh_basis_l2(n);
        const double formula =
            k_pi * radiance.c[0].g * y[0] +
            2 * k_pi / 3 *
                (radiance.c[1].g * y[1] + radiance.c[2].g * y[2] + radiance.c[3].g * y[3]);
        EXPECT_NEAR(e.evaluate_l1(n).g, formula, 1e-12);
        EXPECT_NEAR(formula, 0.25 + 0.5 * dot(n, d0), 1e-12);
    }
}

} // namespace
} // namespace penumbra
