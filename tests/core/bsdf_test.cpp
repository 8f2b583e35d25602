// The BSDFs (core/bsdf.h): sampling against the density by a chi-square goodness-of-fit test
// (bins over (cos θ, φ), the density integrated per bin by the test, as pbrt-v3's and
// Mitsuba's chi2 tests do), sample weights against eval / pdf, and white furnaces: the albedo
// ∫ f cos dwi by quadrature is at most 1 and equals the analytic value where one exists.

#include "core/bsdf.h"

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/rng.h"

#include "common/test_util.h"

namespace penumbra {
namespace {

const Vec3 k_normal(0, 0, 1); // the world frame is the local frame

Vec3 direction(double cos_theta, double phi) {
    const double s = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    return {s * std::cos(phi), s * std::sin(phi), cos_theta};
}

Vec3 view(double theta_deg) {
    return direction(std::cos(theta_deg * k_pi / 180), 0.7);
}

double mean(const Rgb& c) {
    return (double(c.r) + double(c.g) + double(c.b)) / 3.0;
}

Material with_lobe(const Lobe& lobe, Rgb reflectance = Rgb(0.0f)) {
    Material m;
    m.reflectance = reflectance;
    m.lobe = lobe;
    return m;
}

Material plastic(double alpha, Fresnel fresnel, Rgb specular, Rgb reflectance) {
    return with_lobe(GgxGlossy{alpha, specular, fresnel, true}, reflectance);
}

Material metal(double alpha, Fresnel fresnel, Rgb specular) {
    return with_lobe(GgxGlossy{alpha, specular, fresnel, false});
}

struct NamedMaterial {
    std::string name;
    Material material;
};

std::vector<NamedMaterial> glossy_materials() {
    Material lambert;
    lambert.reflectance = Rgb(0.8f, 0.5f, 0.2f);
    return {
        {"lambert", lambert},
        {"ggx_0.05_none", metal(0.05, FresnelNone{}, Rgb(0.9f))}, // cornell-spheres' metal
        {"ggx_0.1_none", metal(0.1, FresnelNone{}, Rgb(0.9f))},
        {"ggx_0.35_schlick", metal(0.35, FresnelSchlick{}, Rgb(0.95f, 0.64f, 0.54f))},
        {"ggx_0.8_dielectric", metal(0.8, FresnelDielectric{1.5}, Rgb(1.0f))},
        {"plastic_0.2_dielectric",
         plastic(0.2, FresnelDielectric{1.5}, Rgb(1.0f), Rgb(0.7f, 0.3f, 0.1f))},
        {"plastic_0.6_none", plastic(0.6, FresnelNone{}, Rgb(0.3f), Rgb(0.6f))},
        {"plastic_0.1_schlick", plastic(0.1, FresnelSchlick{}, Rgb(0.05f), Rgb(0.9f))},
    };
}

// ---- Chi-square goodness of fit ---------------------------------------------------------------

constexpr int k_cos_bins = 24, k_phi_bins = 48;
constexpr int k_sub = 24; ///< midpoints per bin and axis for the bin's integrated density
constexpr int k_samples = 400000;

/// P(χ² ≥ x) for k degrees of freedom by the Wilson–Hilferty normal approximation
/// (accurate to a few per cent of the p-value for k ≥ 30).
double chi_square_p_value(double x, int k) {
    const double h = 2.0 / (9.0 * k);
    const double z = (std::cbrt(x / k) - (1.0 - h)) / std::sqrt(h);
    return 0.5 * std::erfc(z / std::sqrt(2.0));
}

int bin_of(const Vec3& w) {
    const int i = std::clamp(int((w.z + 1.0) * 0.5 * k_cos_bins), 0, k_cos_bins - 1);
    double phi = std::atan2(w.y, w.x);
    if (phi < 0)
        phi += 2 * k_pi;
    const int j = std::clamp(int(phi / (2 * k_pi) * k_phi_bins), 0, k_phi_bins - 1);
    return i * k_phi_bins + j;
}

/// Four-point Gauss–Legendre rule on [−1, 1]: exact for polynomials of degree 7, and it never
/// evaluates a bin's edge (where the horizon would count toward the bin below it).
constexpr double k_gauss_nodes[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                     0.8611363115940526};
constexpr double k_gauss_weights[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                       0.3478548451374538};

/// Expected probabilities per bin: the density integrated over each (cos θ, φ) cell, dω =
/// sin θ dθ dφ, by Gauss–Legendre in θ on k_sub / 4 pieces per bin (uniform in angle, so
/// that a narrow lobe near the pole is resolved) and the midpoint rule in φ; the last entry
/// is what the sampler loses (directions below the horizon), 1 − the total.
std::vector<double> expected_probabilities(const Bsdf& bsdf, const Vec3& wo) {
    std::vector<double> p(k_cos_bins * k_phi_bins + 1, 0.0);
    const double dphi = 2 * k_pi / (k_phi_bins * k_sub);
    constexpr int pieces = k_sub / 4;
    double total = 0;
    for (int i = 0; i < k_cos_bins; ++i) {
        const double theta_hi = std::acos(-1.0 + 2.0 * i / k_cos_bins);
        const double theta_lo = std::acos(-1.0 + 2.0 * (i + 1) / k_cos_bins);
        const double half = 0.5 * (theta_hi - theta_lo) / pieces;
        for (int a = 0; a < pieces; ++a)
            for (int g = 0; g < 4; ++g) {
                const double theta = theta_lo + (2 * a + 1) * half + k_gauss_nodes[g] * half;
                const double w = k_gauss_weights[g] * half * std::sin(theta) * dphi;
                for (int j = 0; j < k_phi_bins * k_sub; ++j) {
                    const double mass =
                        bsdf.pdf(wo, direction(std::cos(theta), (j + 0.5) * dphi)) * w;
                    p[i * k_phi_bins + j / k_sub] += mass;
                    total += mass;
                }
            }
    }
    p.back() = std::max(0.0, 1.0 - total);
    return p;
}

struct ChiSquare {
    double statistic = 0;
    int dof = 0;
};

/// Pearson's statistic over the bins, those expecting fewer than 5 samples pooled into one.
ChiSquare chi_square(const std::vector<double>& observed, const std::vector<double>& expected) {
    ChiSquare result;
    double pooled_o = 0, pooled_e = 0;
    for (std::size_t b = 0; b < observed.size(); ++b) {
        if (expected[b] < 5) {
            pooled_o += observed[b];
            pooled_e += expected[b];
            continue;
        }
        result.statistic += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b];
        ++result.dof;
    }
    if (pooled_e >= 5) {
        result.statistic += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e;
        ++result.dof;
    } else
        EXPECT_LE(pooled_o, 25) << "samples where the density expects (almost) none";
    --result.dof;
    return result;
}

class GlossySampling : public testing::TestWithParam<NamedMaterial> {};

TEST_P(GlossySampling, MatchesItsDensity) {
    const Bsdf bsdf(GetParam().material, k_normal);
    int stream = 0;
    for (const double theta : {5.0, 40.0, 75.0, 140.0}) { // 140°: the back of a two-sided one
        const Vec3 wo = view(theta);
        Pcg32 rng = Pcg32::for_stream(RngPurpose::pixel_sample, 28, ++stream, 0, 1);
        std::vector<double> observed(k_cos_bins * k_phi_bins + 1, 0.0);
        for (int s = 0; s < k_samples; ++s) {
            const double ul = rng.next_double();
            const Vec2 u{rng.next_double(), rng.next_double()};
            const std::optional<BsdfSample> sample = bsdf.sample(wo, ul, u);
            observed[sample ? bin_of(sample->wi) : observed.size() - 1] += 1;
        }
        std::vector<double> expected = expected_probabilities(bsdf, wo);
        for (double& e : expected)
            e *= k_samples;
        const ChiSquare c = chi_square(observed, expected);
        ASSERT_GE(c.dof, 10) << "θo " << theta;
        EXPECT_GT(chi_square_p_value(c.statistic, c.dof), 1e-4)
            << "θo " << theta << ": χ² " << c.statistic << " with " << c.dof << " dof";
    }
}

// Every sample's weight is eval / pdf and its pdf is pdf(): the estimator the renderer uses
// with MIS is the same as the one it uses with the sample's weight alone.
TEST_P(GlossySampling, WeightIsEvalOverPdf) {
    const Bsdf bsdf(GetParam().material, k_normal);
    Pcg32 rng = Pcg32::for_stream(RngPurpose::pixel_sample, 28, 100, 0, 1);
    for (const double theta : {3.0, 50.0, 85.0, 120.0})
        for (int s = 0; s < 2000; ++s) {
            const Vec3 wo = view(theta);
            const double ul = rng.next_double();
            const std::optional<BsdfSample> sample =
                bsdf.sample(wo, ul, Vec2{rng.next_double(), rng.next_double()});
            if (!sample)
                continue;
            EXPECT_FALSE(sample->delta());
            EXPECT_GT(sample->wi.z * wo.z, 0) << "reflection stays on wo's side";
            const double pdf = bsdf.pdf(wo, sample->wi);
            ASSERT_GT(pdf, 0);
            EXPECT_NEAR(sample->pdf / pdf, 1.0, 1e-9);
            const Rgb f = bsdf.eval(wo, sample->wi);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(sample->weight[c], f[c] / pdf, 1e-5 * (1.0 + f[c] / pdf));
        }
}

// ---- White furnace ------------------------------------------------------------------------------

/// ∫ eval(wo, wi) dwi over the sphere by the midpoint rule in (cos θ, φ).
Rgb albedo_by_quadrature(const Bsdf& bsdf, const Vec3& wo, int n_cos = 1200, int n_phi = 1200) {
    RgbD sum;
    for (int i = 0; i < n_cos; ++i)
        for (int j = 0; j < n_phi; ++j)
            sum += RgbD(bsdf.eval(
                wo, direction(-1.0 + 2.0 * (i + 0.5) / n_cos, 2 * k_pi * (j + 0.5) / n_phi)));
    const double d = 2.0 / n_cos * 2 * k_pi / n_phi;
    return Rgb(float(sum.r * d), float(sum.g * d), float(sum.b * d));
}

TEST_P(GlossySampling, ReflectsAtMostWhatArrives) {
    const Bsdf bsdf(GetParam().material, k_normal);
    for (const double theta : {0.0, 30.0, 60.0, 80.0, 89.0}) {
        const Rgb albedo = albedo_by_quadrature(bsdf, view(theta));
        EXPECT_LE(albedo.max_component(), 1.0 + 1e-3) << "θo " << theta;
        EXPECT_GE(albedo.max_component(), 0.0);
    }
}

// Helmholtz reciprocity f(wo, wi) = f(wi, wo), in a frame tilted away from the world axes,
// on both sides of a two-sided material; no light passes to the other side.
TEST_P(GlossySampling, ReciprocalInATiltedFrame) {
    const Vec3 n = normalize(Vec3(0.3, -0.5, 0.8));
    const Bsdf bsdf(GetParam().material, n);
    const Frame frame = Frame::from_normal(n);
    Pcg32 rng = Pcg32::for_stream(RngPurpose::pixel_sample, 28, 300, 0, 1);
    for (int k = 0; k < 500; ++k) {
        const double side = k % 2 ? 1.0 : -1.0;
        const Vec3 a =
            frame.to_world(direction(side * rng.next_double(), 2 * k_pi * rng.next_double()));
        const Vec3 b =
            frame.to_world(direction(side * rng.next_double(), 2 * k_pi * rng.next_double()));
        const Rgb fab = bsdf.f(a, b), fba = bsdf.f(b, a);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(fab[c], fba[c], 1e-4 * (1.0 + fab[c]));
        EXPECT_TRUE(bsdf.eval(a, b - n * (2 * dot(b, n))).is_black()) << "through the surface";
    }
}

INSTANTIATE_TEST_SUITE_P(Bsdf, GlossySampling, testing::ValuesIn(glossy_materials()),
                         [](const auto& info) { return test::case_name(info.param.name); });

TEST(Bsdf, LambertAlbedoIsItsReflectance) {
    Material m;
    m.reflectance = Rgb(0.8f, 0.5f, 0.2f);
    const Bsdf bsdf(m, k_normal);
    const Rgb f = bsdf.f(view(30), view(70));
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(f[c], m.reflectance[c] / k_pi, 1e-7);
    for (const double theta : {0.0, 45.0, 85.0, 130.0}) {
        const Rgb a = albedo_by_quadrature(bsdf, view(theta), 800, 64);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(a[c], m.reflectance[c], 1e-3) << "θo " << theta;
    }
}

/// The albedo of GGX reflection by quadrature over the microfacet normal m instead of wi:
/// E = ∫ F D(m) G2 |wo·m| / cos θo dm over the normals that reflect above the horizon (the
/// Jacobian dwi/dm = 4 |wo·m| applied by hand).
double ggx_albedo_over_normals(double alpha, const Vec3& wo) {
    const GgxDistribution ggx{alpha};
    constexpr int n_theta = 2000, n_phi = 800;
    double sum = 0;
    for (int i = 0; i < n_theta; ++i)
        for (int j = 0; j < n_phi; ++j) {
            const double theta = 0.5 * k_pi * (i + 0.5) / n_theta;
            const Vec3 m = direction(std::cos(theta), 2 * k_pi * (j + 0.5) / n_phi);
            const Vec3 wi = reflect(wo, m);
            if (wi.z <= 0 || dot(wo, m) <= 0)
                continue;
            sum += ggx.d(m) * ggx.g2(wo, wi) * dot(wo, m) / wo.z * std::sin(theta);
        }
    return sum * (0.5 * k_pi / n_theta) * (2 * k_pi / n_phi);
}

// The white-furnace limit of the metal: specular 1, no Fresnel, so only masking (and the
// light sent below the horizon) is lost; the albedo over wi equals the albedo over m.
TEST(Bsdf, WhiteGgxAlbedoOverDirectionsAndNormalsAgree) {
    for (const double alpha : {0.1, 0.5, 1.0})
        for (const double theta : {0.0, 60.0}) {
            const Bsdf bsdf(metal(alpha, FresnelNone{}, Rgb(1.0f)), k_normal);
            const double a = mean(albedo_by_quadrature(bsdf, view(theta)));
            EXPECT_LE(a, 1.0 + 1e-3) << alpha;
            EXPECT_NEAR(a, ggx_albedo_over_normals(alpha, view(theta)), 1e-3)
                << "α " << alpha << " θo " << theta;
        }
}

// The plastic's base reflects exactly what the coat does not: its total albedo is
// E + ρ (1 − E), with E the coat's own albedo by quadrature (not the code's table).
TEST(Bsdf, PlasticBaseTakesWhatTheCoatLeaves) {
    for (const double alpha : {0.2, 0.45, 0.9})
        for (const double theta : {0.0, 50.0, 80.0}) {
            const Rgb rho(0.9f, 0.5f, 0.1f);
            const Material m = plastic(alpha, FresnelSchlick{}, Rgb(0.04f), rho);
            const Rgb total = albedo_by_quadrature(Bsdf(m, k_normal), view(theta));
            const Rgb coat = albedo_by_quadrature(
                Bsdf(metal(alpha, FresnelSchlick{}, Rgb(0.04f)), k_normal), view(theta));
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(total[c], coat[c] + rho[c] * (1 - coat[c]), 2e-3)
                    << "α " << alpha << " θo " << theta << " channel " << c;
        }
}

TEST(Bsdf, OneSidedBackReflectsNothing) {
    Material m;
    m.two_sided = false;
    const Bsdf bsdf(m, k_normal);
    const Vec3 wo = view(120), wi = view(150);
    EXPECT_TRUE(bsdf.eval(wo, wi).is_black());
    EXPECT_EQ(bsdf.pdf(wo, wi), 0.0);
    EXPECT_FALSE(bsdf.sample(wo, 0.5, Vec2{0.3, 0.3}));
    EXPECT_FALSE(bsdf.eval(view(30), view(60)).is_black());
}

// ---- Delta lobes
// ---------------------------------------------------------------------------------

/// The expected weight of the outcomes of a delta BSDF from wo, split by lobe: E[weight ·
/// 1{lobe}] = Σ probability × weight, enumerated over u_lobe (each outcome is decided by
/// u_lobe alone).
struct DeltaOutcomes {
    Rgb reflected, transmitted;
    std::vector<BsdfSample> samples;
};

DeltaOutcomes delta_outcomes(const Bsdf& bsdf, const Vec3& wo) {
    DeltaOutcomes out;
    for (const double ul : {0.0, 0.999999999}) { // the first and the last event
        const std::optional<BsdfSample> s = bsdf.sample(wo, ul, Vec2{0.5, 0.5});
        if (!s || (!out.samples.empty() && out.samples.back().lobe == s->lobe))
            continue;
        EXPECT_TRUE(s->delta());
        (s->transmission() ? out.transmitted : out.reflected) += s->weight * float(s->pdf);
        out.samples.push_back(*s);
    }
    return out;
}

TEST(Bsdf, MirrorReflectsItsColour) {
    const Rgb colour(0.9f, 0.8f, 0.7f);
    const Bsdf bsdf(with_lobe(Mirror{colour}), k_normal);
    EXPECT_TRUE(bsdf.is_delta());
    for (const double theta : {0.0, 45.0, 89.0, 160.0}) {
        const Vec3 wo = view(theta);
        const std::optional<BsdfSample> s = bsdf.sample(wo, 0.3, Vec2{0.1, 0.2});
        ASSERT_TRUE(s);
        EXPECT_EQ(s->weight, colour);
        EXPECT_NEAR(length(s->wi - Vec3(-wo.x, -wo.y, wo.z)), 0.0, 1e-12);
        EXPECT_TRUE(bsdf.eval(wo, s->wi).is_black());
        EXPECT_EQ(bsdf.pdf(wo, s->wi), 0.0);
    }
}

// R + T = 1 for clear glass (importance: the flux a photon carries is kept), radiance scaled
// by 1/η² through the interface, Snell's law, and total internal reflection from inside.
TEST(Bsdf, DielectricConservesEnergyAndRefractsBySnell) {
    const double n = 1.5;
    const Bsdf photons(with_lobe(Dielectric{n, true, Rgb(1.0f)}), k_normal,
                       TransportMode::importance);
    const Bsdf camera(with_lobe(Dielectric{n, true, Rgb(1.0f)}), k_normal);
    for (const double theta : {0.0, 30.0, 60.0, 85.0, 150.0, 170.0}) {
        const Vec3 wo = view(theta);
        const DeltaOutcomes out = delta_outcomes(photons, wo);
        const double f = fresnel_dielectric(wo.z, n);
        EXPECT_NEAR(mean(out.reflected), f, 1e-6) << theta;
        EXPECT_NEAR(mean(out.reflected + out.transmitted), 1.0, 1e-6) << theta;
        for (const BsdfSample& s : out.samples) {
            if (!s.transmission())
                continue;
            const double eta = wo.z > 0 ? n : 1.0 / n;
            EXPECT_NEAR(s.eta, eta, 1e-12);
            const double sin_o = std::sqrt(1 - wo.z * wo.z), sin_i = std::sqrt(1 - s.wi.z * s.wi.z);
            EXPECT_NEAR(sin_o, eta * sin_i, 1e-9) << "Snell at " << theta;
            EXPECT_LT(s.wi.z * wo.z, 0);
            const std::optional<BsdfSample> c = camera.sample(wo, 0.999999999, Vec2{});
            ASSERT_TRUE(c);
            EXPECT_NEAR(c->weight.g, s.weight.g / (eta * eta), 1e-6);
        }
    }
    const Vec3 beyond_critical = view(180 - 45); // inside, 45° > 41.8°
    const DeltaOutcomes tir = delta_outcomes(photons, beyond_critical);
    EXPECT_NEAR(mean(tir.reflected), 1.0, 1e-12);
    EXPECT_TRUE(tir.transmitted.is_black());
}

// Thin glass reflects R(θ) and passes T(θ) of ThinGlass (material.h), straight through.
TEST(Bsdf, ThinGlassReflectsAndPassesAsMaterialH) {
    const ThinGlass glass{Rgb(0.5f, 0.762842f, 1.0f), 1.52};
    const Bsdf bsdf(with_lobe(glass), k_normal);
    for (const double theta : {0.0, 45.0, 80.0, 135.0}) {
        const Vec3 wo = view(theta);
        const DeltaOutcomes out = delta_outcomes(bsdf, wo);
        const Rgb r = glass.reflectance(std::abs(wo.z)), t = glass.transmittance(std::abs(wo.z));
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(out.reflected[c], r[c], 1e-6) << theta;
            EXPECT_NEAR(out.transmitted[c], t[c], 1e-6) << theta;
        }
        for (const BsdfSample& s : out.samples)
            EXPECT_NEAR(length(s.wi - (s.transmission() ? -wo : Vec3(-wo.x, -wo.y, wo.z))), 0.0,
                        1e-12);
    }
}

// The fraction of samples that choose reflection is the probability the sample reports
// (within 4 binomial standard deviations), for the dielectric and thin glass.
TEST(Bsdf, DeltaLobeChoiceFollowsItsProbability) {
    const Material materials[] = {with_lobe(Dielectric{1.5, true, Rgb(1.0f)}),
                                  with_lobe(ThinGlass{Rgb(0.3f, 0.6f, 0.9f), 1.52})};
    int stream = 200;
    for (const Material& m : materials)
        for (const double theta : {20.0, 70.0, 110.0}) {
            const Bsdf bsdf(m, k_normal);
            const Vec3 wo = view(theta);
            Pcg32 rng = Pcg32::for_stream(RngPurpose::pixel_sample, 28, ++stream, 0, 1);
            constexpr int n = 200000;
            int reflected = 0;
            double p = 0;
            for (int i = 0; i < n; ++i) {
                const std::optional<BsdfSample> s = bsdf.sample(wo, rng.next_double(), Vec2{});
                ASSERT_TRUE(s);
                if (!s->transmission()) {
                    ++reflected;
                    p = s->pdf;
                }
            }
            EXPECT_NEAR(double(reflected) / n, p, 4 * std::sqrt(p * (1 - p) / n)) << theta;
        }
}

} // namespace
} // namespace penumbra
