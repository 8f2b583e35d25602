#include "core/light.h"

#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"

namespace penumbra {
namespace {

double cos_deg(double deg) {
    return std::cos(deg * k_pi / 180.0);
}

PointLight spot(double beam_deg, double cutoff_deg, const Vec3& axis = {0, 0, 1}) {
    PointLight light;
    light.intensity = Rgb(2.0f, 1.0f, 0.5f);
    light.spot = SpotCone{axis, beam_deg, cutoff_deg};
    return light;
}

// ∫ profile dω over the sphere by the midpoint rule in μ = cos θ to the z axis (dω = dμ dφ),
// with the profile evaluated on directions at azimuth phi: for a spot along z it does not
// depend on φ. 10⁶ intervals: the profile is C¹ and piecewise polynomial in μ, so the error
// is about 1e-12.
double numeric_solid_angle(const PointLight& light, double phi) {
    const int n = 1000000;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
        const double mu = -1.0 + (i + 0.5) * 2.0 / n;
        const double s = std::sqrt(1.0 - mu * mu);
        sum += light.profile(Vec3(s * std::cos(phi), s * std::sin(phi), mu));
    }
    return 2.0 * k_pi * sum * 2.0 / n;
}

TEST(PointLight, IsotropicProfileAndPower) {
    PointLight light;
    light.intensity = Rgb(1.0f, 2.0f, 3.0f);
    EXPECT_EQ(light.profile(normalize(Vec3(1, -2, 3))), 1.0);
    EXPECT_EQ(light.profile_cos(-1.0), 1.0);
    EXPECT_DOUBLE_EQ(light.profile_solid_angle(), 4.0 * k_pi);
    EXPECT_NEAR(light.power().g, 8.0 * k_pi, 1e-12);
}

TEST(PointLight, SpotProfileIsASmoothstepBetweenBeamAndCutoff) {
    const PointLight light = spot(20, 50);
    const double cb = cos_deg(20), cc = cos_deg(50);
    EXPECT_EQ(light.profile_cos(1.0), 1.0);
    EXPECT_EQ(light.profile_cos(cb), 1.0);
    EXPECT_EQ(light.profile_cos(cc), 0.0);
    EXPECT_EQ(light.profile_cos(-1.0), 0.0);
    EXPECT_NEAR(light.profile_cos(0.5 * (cb + cc)), 0.5, 1e-12);
    // Continuous slope: zero at both ends of the falloff.
    const double h = 1e-7 * (cb - cc);
    EXPECT_NEAR((light.profile_cos(cb - h) - 1.0) / h, 0.0, 1e-5);
    EXPECT_NEAR(light.profile_cos(cc + h) / h, 0.0, 1e-5);
    // By direction: the same function of the cosine to the axis.
    const Vec3 axis = normalize(Vec3(1, 2, -2));
    const PointLight tilted = spot(20, 50, axis);
    const Vec3 dir = normalize(Vec3(0.3, 1, -1));
    EXPECT_EQ(tilted.profile(dir), tilted.profile_cos(dot(dir, axis)));
}

TEST(PointLight, SpotSolidAngleMatchesClosedFormAndNumericIntegral) {
    for (const auto& [beam, cutoff] :
         std::vector<std::pair<double, double>>{{30, 45}, {0, 10}, {10, 90}, {60, 180}, {5, 6}}) {
        const PointLight light = spot(beam, cutoff);
        const double cb = cos_deg(beam), cc = cos_deg(cutoff);
        const double closed = 2.0 * k_pi * ((1.0 - cb) + (cb - cc) / 2.0);
        EXPECT_NEAR(light.profile_solid_angle(), closed, 1e-12) << beam << "/" << cutoff;
        EXPECT_NEAR(numeric_solid_angle(light, 0.7), closed, 1e-6) << beam << "/" << cutoff;
        EXPECT_NEAR(light.power().r, 2.0 * closed, 1e-6);
    }
}

TEST(PointLight, HardEdgedSpotSolidAngleIsItsCap) {
    const PointLight light = spot(25, 25);
    EXPECT_EQ(light.profile_cos(cos_deg(25) + 1e-9), 1.0);
    EXPECT_EQ(light.profile_cos(cos_deg(25) - 1e-9), 0.0);
    EXPECT_NEAR(light.profile_solid_angle(), 2.0 * k_pi * (1.0 - cos_deg(25)), 1e-12);
}

TEST(Sun, AngularRadiusAndUnoccludedIrradiance) {
    Sun sun;
    sun.direction = normalize(Vec3(0, 1, 1));
    sun.irradiance = Rgb(800.0f);
    EXPECT_NEAR(sun.angular_radius(), 0.533 / 2 * k_pi / 180, 1e-15);
    EXPECT_NEAR(sun.unoccluded({0, 0, 1}).r, 800.0 / std::sqrt(2.0), 1e-3);
    EXPECT_TRUE(sun.unoccluded({0, 0, -1}).is_black()); // below the horizon
}

TEST(LightSource, KindsAtInfinityAndDescriptions) {
    EXPECT_FALSE(at_infinity(AreaSource{3}));
    EXPECT_FALSE(at_infinity(PointSource{0}));
    EXPECT_TRUE(at_infinity(SunSource{}));
    EXPECT_TRUE(at_infinity(SkySource{}));
    EXPECT_EQ(describe(AreaSource{3}), "polygon 3");
    EXPECT_EQ(describe(PointSource{0}), "point light 0");
    EXPECT_EQ(describe(SunSource{}), "the sun");
    EXPECT_EQ(describe(SkySource{}), "the sky");
    EXPECT_NE(LightSource(AreaSource{1}), LightSource(PointSource{1}));
    EXPECT_EQ(LightSource(PointSource{2}), LightSource(PointSource{2}));
}

TEST(LightId, RoundTripsEveryKindInFourBytes) {
    static_assert(sizeof(LightId) == 4);
    const std::uint32_t largest = (std::uint32_t(1) << 30) - 1;
    for (const LightSource& s :
         std::vector<LightSource>{AreaSource{0}, AreaSource{largest}, PointSource{0},
                                  PointSource{7}, PointSource{largest}, SunSource{}, SkySource{}})
        EXPECT_EQ(LightId(s).source(), s) << describe(s);
    EXPECT_EQ(LightId(PointSource{4}), LightId(PointSource{4}));
    EXPECT_FALSE(LightId(PointSource{4}) == LightId(AreaSource{4}));
    EXPECT_THROW(LightId(AreaSource{largest + 1}), InternalError);
}

} // namespace
} // namespace penumbra
