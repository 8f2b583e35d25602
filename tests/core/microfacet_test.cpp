// GGX (core/microfacet.h) against its defining integrals, by quadrature in the test: the
// distribution's normalisation, Smith's projected-area identity, and the Fresnel factor at
// angles with closed forms.

#include "core/microfacet.h"

#include <cmath>

#include <gtest/gtest.h>

namespace penumbra {
namespace {

Vec3 direction(double cos_theta, double phi) {
    const double s = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    return {s * std::cos(phi), s * std::sin(phi), cos_theta};
}

/// ∫ D(m) (m·n) dm = 2π ∫₀¹ D(μ) μ dμ (isotropic), by the midpoint rule in t = μ²: the
/// peak of width ~α² at μ = 1 spans thousands of the 2·10⁶ intervals even at α = 0.01.
double projected_d_integral(const GgxDistribution& ggx) {
    constexpr int n = 2000000;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
        const double t = (i + 0.5) / n; // μ² ; μ dμ = dt / 2
        sum += ggx.d(Vec3(0, 0, std::sqrt(t)));
    }
    return 2.0 * k_pi * 0.5 * sum / n;
}

TEST(Ggx, DistributionIsNormalised) {
    for (const double alpha : {0.01, 0.05, 0.1, 0.3, 0.7, 1.0})
        EXPECT_NEAR(projected_d_integral(GgxDistribution{alpha}), 1.0, 1e-4) << "α " << alpha;
}

// Heitz 2014, eq. 2: ∫ G1(wo) max(0, wo·m) D(m) dm = cos θo, so the visible normals' density
// integrates to 1. Quadrature over (cos θm, φm) on a grid fine enough for α ≥ 0.1.
TEST(Ggx, VisibleNormalsIntegrateToOne) {
    constexpr int n_mu = 4000, n_phi = 400;
    for (const double alpha : {0.1, 0.4, 1.0})
        for (const double cos_o : {0.98, 0.6, 0.15}) {
            const GgxDistribution ggx{alpha};
            const Vec3 wo = direction(cos_o, 0.3);
            double sum = 0;
            for (int i = 0; i < n_mu; ++i)
                for (int j = 0; j < n_phi; ++j) {
                    const double mu = (i + 0.5) / n_mu, phi = 2 * k_pi * (j + 0.5) / n_phi;
                    sum += ggx.visible_normal_pdf(wo, direction(mu, phi));
                }
            EXPECT_NEAR(sum * 2 * k_pi / (double(n_mu) * n_phi), 1.0, 2e-3)
                << "α " << alpha << " cos θo " << cos_o;
        }
}

TEST(Ggx, SampledNormalsFaceTheViewer) {
    const GgxDistribution ggx{0.3};
    const Vec3 wo = direction(0.2, 1.0);
    for (int i = 0; i < 64; ++i)
        for (int j = 0; j < 64; ++j) {
            const Vec3 m = ggx.sample_visible_normal(wo, Vec2{(i + 0.5) / 64, (j + 0.5) / 64});
            EXPECT_NEAR(length(m), 1.0, 1e-12);
            EXPECT_GE(dot(wo, m), -1e-9);
            EXPECT_GT(m.z, 0);
        }
}

// Normal incidence ((n − 1)/(n + 1))², total internal reflection past the critical angle,
// Brewster's angle (r_p = 0, so F = r_s² / 2), and the same from inside.
TEST(Fresnel, DielectricClosedForms) {
    const double n = 1.5;
    EXPECT_NEAR(fresnel_dielectric(1.0, n), 0.04, 1e-12);
    EXPECT_NEAR(fresnel_dielectric(-1.0, n), 0.04, 1e-12);
    const double critical = std::asin(1.0 / n);
    EXPECT_EQ(fresnel_dielectric(-std::cos(critical + 0.01), n), 1.0);
    EXPECT_LT(fresnel_dielectric(-std::cos(critical - 0.01), n), 1.0);
    const double brewster = std::atan(n);
    const double ct = std::cos(std::atan(1.0 / n)); // θt = 90° − θB
    const double ci = std::cos(brewster);
    const double rs = (ci - n * ct) / (ci + n * ct);
    EXPECT_NEAR(fresnel_dielectric(ci, n), 0.5 * rs * rs, 1e-12);
    EXPECT_NEAR(fresnel_dielectric(0.0, n), 1.0, 1e-12);
    EXPECT_NEAR(fresnel_schlick(0.04, 1.0), 0.04, 1e-15);
    EXPECT_NEAR(fresnel_schlick(0.04, 0.0), 1.0, 1e-15);
}

} // namespace
} // namespace penumbra
