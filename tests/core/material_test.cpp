// Materials (core/material.h): thin glass against the transmittances of Radiance's `glass`
// quoted in issue #26, conservation of energy, and the radiosity response.

#include <cmath>

#include <gtest/gtest.h>

#include "core/material.h"
#include "core/vec.h"

namespace penumbra {
namespace {

// Glass of 70 % normal transmittance: Radiance's transmissivity for Tn = 0.70 at n = 1.52.
constexpr double k_tn = 0.762842;
constexpr double k_ior = 1.52;

double cos_deg(double deg) {
    return std::cos(deg * k_pi / 180.0);
}

double transmittance_at(double deg) {
    return thin_glass_response(k_tn, k_ior, cos_deg(deg)).transmittance;
}

TEST(ThinGlass, TransmitsAsRadianceGlass) {
    EXPECT_NEAR(transmittance_at(0), 0.700, 1e-3);
    EXPECT_NEAR(transmittance_at(45), 0.663, 1e-3);
    EXPECT_NEAR(transmittance_at(60), 0.603, 1e-3);
    EXPECT_NEAR(transmittance_at(80), 0.295, 1e-3);
    EXPECT_NEAR(thin_glass_response(k_tn, k_ior, 1.0).reflectance, 0.065, 1e-3);
}

TEST(ThinGlass, GrazingLightAllReflects) {
    const ThinGlassResponse grazing = thin_glass_response(k_tn, k_ior, 0.0);
    EXPECT_EQ(grazing.transmittance, 0.0);
    EXPECT_EQ(grazing.reflectance, 1.0);
    // Without absorption too, where the sums of the bounces are 0/0 at exactly 90°.
    EXPECT_EQ(thin_glass_response(1.0, k_ior, 0.0).transmittance, 0.0);
    EXPECT_NEAR(thin_glass_response(k_tn, k_ior, 1e-9).transmittance, 0.0, 1e-6);
}

// What is neither transmitted nor reflected is absorbed: never negative, and nothing when the
// glass does not absorb (tn = 1), at every angle.
TEST(ThinGlass, ConservesEnergy) {
    for (int tenth = 0; tenth <= 900; ++tenth) {
        const double c = cos_deg(tenth / 10.0);
        for (const double tn : {0.0, 0.3, k_tn, 0.96}) {
            const ThinGlassResponse g = thin_glass_response(tn, k_ior, c);
            EXPECT_GE(g.transmittance, 0.0);
            EXPECT_GE(g.reflectance, 0.0);
            EXPECT_LE(g.transmittance + g.reflectance, 1.0 + 1e-12) << tn << " at " << c;
        }
        const ThinGlassResponse clear = thin_glass_response(1.0, k_ior, c);
        EXPECT_NEAR(clear.transmittance + clear.reflectance, 1.0, 1e-12) << "at " << c;
    }
}

// 2 ∫ T(θ) cos θ sin θ dθ over [0, π/2] by the midpoint rule in θ: another variable and
// another rule than the code's Simpson in cos θ.
TEST(ThinGlass, HemisphericalTransmittance) {
    constexpr int n = 200000;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
        const double theta = (i + 0.5) * (0.5 * k_pi / n);
        sum += 2.0 * thin_glass_response(k_tn, k_ior, std::cos(theta)).transmittance *
               std::cos(theta) * std::sin(theta);
    }
    const double quadrature = sum * (0.5 * k_pi / n);
    const double h = thin_glass_hemispherical_transmittance(k_tn, k_ior);
    EXPECT_NEAR(h, 0.620, 1e-3);
    EXPECT_NEAR(h, quadrature, 1e-7);
}

TEST(ThinGlass, ChannelsAreIndependent) {
    const ThinGlass glass{Rgb(0.5f, float(k_tn), 1.0f), k_ior};
    const double c = cos_deg(30);
    const Rgb t = glass.transmittance(c), r = glass.reflectance(c);
    const Rgb h = glass.hemispherical_transmittance();
    const double tn[3] = {0.5, double(float(k_tn)), 1.0};
    for (int k = 0; k < 3; ++k) {
        const ThinGlassResponse g = thin_glass_response(tn[k], k_ior, c);
        EXPECT_FLOAT_EQ(t[k], float(g.transmittance));
        EXPECT_FLOAT_EQ(r[k], float(g.reflectance));
        EXPECT_FLOAT_EQ(h[k], float(thin_glass_hemispherical_transmittance(tn[k], k_ior)));
    }
}

TEST(RadiosityResponse, DiffuseMaterialAsIs) {
    Material m;
    m.reflectance = Rgb(0.1f, 0.2f, 0.3f);
    m.emission = Rgb(4, 5, 6);
    m.two_sided = false;
    m.emission_two_sided = true;
    GgxGlossy plastic;
    plastic.diffuse_base = true;
    for (const auto& lobe : {std::optional<Lobe>{}, std::optional<Lobe>{plastic}}) {
        m.lobe = lobe;
        const RadiosityResponse r = radiosity_response(m);
        EXPECT_EQ(r.reflectance, m.reflectance); // a plastic's base is its diffuse part
        EXPECT_EQ(r.emission, m.emission);
        EXPECT_FALSE(r.two_sided);
        EXPECT_TRUE(r.emission_two_sided);
        EXPECT_TRUE(r.transmittance.is_black());
        EXPECT_TRUE(r.opaque());
        EXPECT_FALSE(r.specular_only);
    }
}

// A metal, a mirror and a dielectric have no diffuse part: radiosity transports nothing off
// them (what they reflect onto diffuse surfaces is the final gather's caustic term).
TEST(RadiosityResponse, SpecularMaterialsHaveNoDiffusePart) {
    Material m;
    m.reflectance = Rgb(0.1f, 0.2f, 0.3f);
    m.emission = Rgb(4, 5, 6);
    for (const Lobe& lobe :
         {Lobe{GgxGlossy{}}, Lobe{Mirror{}}, Lobe{Dielectric{}}, Lobe{ThinGlass{}}}) {
        m.lobe = lobe;
        const RadiosityResponse r = radiosity_response(m);
        EXPECT_TRUE(r.reflectance.is_black());
        EXPECT_TRUE(diffuse_reflectance(m).is_black());
        EXPECT_EQ(r.emission, m.emission);
        EXPECT_EQ(r.opaque(), !std::holds_alternative<ThinGlass>(lobe));
        // Glazing passes light into the solution: not what the renderer alone shows.
        EXPECT_EQ(r.specular_only, !std::holds_alternative<ThinGlass>(lobe));
    }
}

TEST(RadiosityResponse, ThinGlassTransmits) {
    Material m;
    const ThinGlass glass{Rgb(float(k_tn)), k_ior};
    m.lobe = glass;
    const RadiosityResponse r = radiosity_response(m);
    EXPECT_EQ(r.transmittance, glass.hemispherical_transmittance());
    EXPECT_FALSE(r.opaque());
    m.lobe = ThinGlass{Rgb(0.0f), k_ior}; // glass that absorbs everything blocks
    EXPECT_TRUE(radiosity_response(m).opaque());
}

} // namespace
} // namespace penumbra
