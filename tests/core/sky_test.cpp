// The sky models against closed forms, the standard's own formula integrated independently,
// values of the formulas worked by hand, and Perez et al.'s relations worked by hand.

#include "core/sky.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/rgb.h"

namespace penumbra {
namespace {

constexpr double k_deg = k_pi / 180;

Sky sky_of(const SkyModel& model, double sun_altitude_deg = 90, double sun_azimuth_deg = 180) {
    Sky sky;
    sky.model = model;
    sky.sun_direction = sky.compass.direction(sun_altitude_deg, sun_azimuth_deg);
    sky.zenith_radiance = 1;
    return sky;
}

TEST(Compass, EastIsClockwiseFromNorthSeenFromAbove) {
    const Compass compass; // z up, y north: x is east
    EXPECT_NEAR(length(compass.east() - Vec3(1, 0, 0)), 0, 1e-12);
    EXPECT_NEAR(length(compass.direction(0, 90) - Vec3(1, 0, 0)), 0, 1e-12);
    EXPECT_NEAR(length(compass.direction(0, 180) - Vec3(0, -1, 0)), 0, 1e-12);
    EXPECT_NEAR(length(compass.direction(90, 37) - Vec3(0, 0, 1)), 0, 1e-12);
    const Vec3 d = compass.direction(30, 45);
    EXPECT_NEAR(d.z, 0.5, 1e-12);
    EXPECT_NEAR(d.x, d.y, 1e-12);
}

// E_h / L_z in closed form: π for a uniform sky, 7π/9 for the CIE overcast sky
// (∫ (1 + 2 cos θ)/3 cos θ dω = 2π (1/2 + 2/3)/3).
TEST(SkyIntegral, UniformAndOvercastMatchClosedForms) {
    EXPECT_NEAR(sky_of(UniformSky{}).horizontal_illuminance_per_zenith_luminance() / k_pi, 1, 1e-9);
    EXPECT_NEAR(sky_of(CieOvercastSky{}).horizontal_illuminance_per_zenith_luminance() /
                    (7 * k_pi / 9),
                1, 1e-9);
    Sky lit = sky_of(CieOvercastSky{});
    lit.zenith_radiance = 3;
    EXPECT_NEAR(lit.horizontal_illuminance_lx() / (179 * 3 * 7 * k_pi / 9), 1, 1e-9);
}

// ISO 15469:2004 / CIE S 011/E:2003 Table 1, typed again here from the standard: a, b, c, d, e
// per sky type 1–15.
constexpr double k_standard[15][5] = {
    {4.0, -0.70, 0, -1.0, 0},      {4.0, -0.70, 2, -1.5, 0.15},   {1.1, -0.8, 0, -1.0, 0},
    {1.1, -0.8, 2, -1.5, 0.15},    {0, -1.0, 0, -1.0, 0},         {0, -1.0, 2, -1.5, 0.15},
    {0, -1.0, 5, -2.5, 0.30},      {0, -1.0, 10, -3.0, 0.45},     {-1.0, -0.55, 2, -1.5, 0.15},
    {-1.0, -0.55, 5, -2.5, 0.30},  {-1.0, -0.55, 10, -3.0, 0.45}, {-1.0, -0.32, 10, -3.0, 0.45},
    {-1.0, -0.32, 16, -3.0, 0.30}, {-1.0, -0.15, 16, -3.0, 0.30}, {-1.0, -0.15, 24, -2.8, 0.15},
};

/// L / L_z of the standard's formula at zenith angle z, sun zenith angle zs, azimuth difference
/// da (radians).
double standard_ratio(const double* p, double z, double zs, double da) {
    const auto gradation = [&](double t) { return 1 + p[0] * std::exp(p[1] / std::cos(t)); };
    const auto indicatrix = [&](double chi) {
        return 1 + p[2] * (std::exp(p[3] * chi) - std::exp(p[3] * k_pi / 2)) +
               p[4] * std::cos(chi) * std::cos(chi);
    };
    const double cos_chi = std::cos(z) * std::cos(zs) + std::sin(z) * std::sin(zs) * std::cos(da);
    const double chi = std::acos(std::clamp(cos_chi, -1.0, 1.0));
    return gradation(z) * indicatrix(chi) / (gradation(0) * indicatrix(zs));
}

/// ∫ L/L_z cos θ dω by the midpoint rule in zenith angle and azimuth (a different scheme
/// from the code's polar coordinates about the sun), with the sun on a cell corner.
double standard_integral(const double* p, double sun_zenith) {
    constexpr int nz = 400, na = 800;
    double total = 0;
    for (int i = 0; i < nz; ++i) {
        const double z = (i + 0.5) * (k_pi / 2) / nz;
        double ring = 0;
        for (int j = 0; j < na; ++j)
            ring += standard_ratio(p, z, sun_zenith, (j + 0.5) * 2 * k_pi / na);
        total += ring * std::cos(z) * std::sin(z);
    }
    return total * (k_pi / 2 / nz) * (2 * k_pi / na);
}

class GeneralSkyIntegral : public testing::TestWithParam<int> {};

TEST_P(GeneralSkyIntegral, MatchesTheStandardsFormulaIntegratedIndependently) {
    const int type = GetParam();
    for (const double altitude : {35.0, 65.0}) {
        const double expected = standard_integral(k_standard[type - 1], (90 - altitude) * k_deg);
        const Sky sky = sky_of(CieGeneralSky{type}, altitude, 200);
        EXPECT_NEAR(sky.horizontal_illuminance_per_zenith_luminance() / expected, 1, 1e-4)
            << "type " << type << ", sun altitude " << altitude;
    }
}

INSTANTIATE_TEST_SUITE_P(AllFifteen, GeneralSkyIntegral, testing::Range(1, 16));

// The formula φ(Z) f(χ) / (φ(0) f(Z_s)) evaluated by hand (a calculator, the standard's
// parameters) at a few directions.
TEST(GeneralSky, LuminanceRatiosMatchValuesWorkedByHand) {
    const Compass compass;
    // Type 12, sun at altitude 30° due south; a point at altitude 30° due east (χ = 75.52°).
    const Sky clear = sky_of(CieGeneralSky{12}, 30, 180);
    EXPECT_NEAR(clear.relative_luminance(compass.direction(30, 90)), 1.3407659955746933, 1e-9);
    EXPECT_NEAR(clear.relative_luminance(compass.direction(30, 180)), 13.479005318233309, 1e-9);
    // Type 1 at zenith angle 80°: (1 + 4 e^(−0.7/cos 80°)) / (1 + 4 e^−0.7), no sun term.
    const Sky overcast = sky_of(CieGeneralSky{1}, 60, 0);
    EXPECT_NEAR(overcast.relative_luminance(compass.direction(10, 123)), 0.3586383085131506, 1e-9);
    EXPECT_NEAR(overcast.relative_luminance(compass.up), 1, 1e-12);
    // Type 7, sun at altitude 50°, the point at zenith angle 45° opposite the sun.
    const Sky partly = sky_of(CieGeneralSky{7}, 50, 100);
    EXPECT_NEAR(partly.relative_luminance(compass.direction(45, 280)), 0.5261787362308129, 1e-9);
    // Type 15, sun at altitude 40°, the point at zenith angle 70°, 30° of azimuth away.
    const Sky turbid = sky_of(CieGeneralSky{15}, 40, 100);
    EXPECT_NEAR(turbid.relative_luminance(compass.direction(20, 130)), 5.104817736071635, 1e-9);
    // The CIE overcast sky: (1 + 2 cos 60°) / 3.
    EXPECT_NEAR(sky_of(CieOvercastSky{}).relative_luminance(compass.direction(30, 0)), 2.0 / 3,
                1e-12);
}

// Radiance's skybright.cal: skybr = wmean((Dz + 1.01)^10, sky, (Dz + 1.01)^−10, ground).
TEST(SkyHorizon, RadianceBlendIsTheWeightedMeanOfSkyAndGround) {
    Sky sky = sky_of(CieOvercastSky{});
    sky.zenith_radiance = 30;
    sky.ground_radiance = 5;
    sky.horizon = Horizon::radiance_blend;
    const Vec3 horizon = sky.compass.direction(0, 30);
    const double ws = std::pow(1.01, 10), wg = std::pow(1.01, -10);
    EXPECT_NEAR(sky.radiance(horizon).g, (ws * 30 / 3 + wg * 5) / (ws + wg), 1e-5);
    // 10° up: Dz = sin 10°; the overcast sky there is 30 (1 + 2 Dz)/3.
    const double dz = std::sin(10 * k_deg);
    const double ws10 = std::pow(dz + 1.01, 10), wg10 = std::pow(dz + 1.01, -10);
    EXPECT_NEAR(sky.radiance(sky.compass.direction(10, 0)).r,
                (ws10 * 30 * (1 + 2 * dz) / 3 + wg10 * 5) / (ws10 + wg10), 1e-5);
    // Sharp: the sky above, the ground at and below.
    sky.horizon = Horizon::sharp;
    EXPECT_FLOAT_EQ(sky.radiance(sky.compass.direction(1e-3, 0)).b,
                    float(30 * (1 + 2 * std::sin(1e-3 * k_deg)) / 3));
    EXPECT_FLOAT_EQ(sky.radiance(horizon).b, 5.0f);
    EXPECT_FLOAT_EQ(sky.radiance(-sky.compass.up).b, 5.0f);
    sky.ground_radiance.reset();
    EXPECT_TRUE(sky.radiance(-sky.compass.up).is_black());
}

TEST(SkyRadiance, ManyDirectionsAtOnceEqualOneAtATime) {
    Sky sky = sky_of(PerezSky{2.5, 0.3}, 25, 140);
    sky.ground_radiance = 4;
    sky.horizon = Horizon::radiance_blend;
    std::vector<Vec3> dirs;
    for (int i = 0; i < 40; ++i)
        dirs.push_back(sky.compass.direction(-80 + 4.3 * i, 17.0 * i));
    std::vector<Rgb> batch(dirs.size());
    sky.radiance(dirs, batch);
    for (std::size_t i = 0; i < dirs.size(); ++i)
        EXPECT_EQ(batch[i], sky.radiance(dirs[i])) << i;
}

// gensky 3 21 +12 -c -B 55.866 -g 0.2 (the office's sky A: 10 000 lx) wrote zenith 22.86 and
// ground 3.557 W/(sr·m²); make_sky's closed-form scale gives them.
TEST(MakeSky, OvercastScaleAndGroundMatchGensky) {
    SkyDescription description;
    description.model = CieOvercastSky{};
    description.level = HorizontalIlluminance{10000};
    const Sky sky = make_sky(description);
    EXPECT_NEAR(sky.zenith_radiance, 10000 / (179 * 7 * k_pi / 9), 1e-6);
    EXPECT_NEAR(sky.zenith_radiance, 22.86, 0.005);
    ASSERT_TRUE(sky.ground_radiance);
    EXPECT_NEAR(*sky.ground_radiance, 0.2 * 10000 / (k_pi * 179), 1e-9);
    EXPECT_NEAR(*sky.ground_radiance, 3.557, 0.0005);
    EXPECT_NEAR(sky.horizontal_illuminance_lx(), 10000, 1e-5);
}

TEST(MakeSky, GroundCountsTheSunAndZenithLuminanceSetsTheLevel) {
    SkyDescription description;
    description.model = CieGeneralSky{12};
    description.sun_direction = description.compass.direction(40, 150);
    description.level = ZenithLuminance{5000};
    description.ground_reflectance = 0.3;
    description.colour = Rgb(0.8f, 1.0f, 1.3f);
    const Sun sun{description.sun_direction, Rgb(400.0f), 0.533};
    const double sun_lx = horizontal_illuminance_lx(sun, description.compass);
    EXPECT_NEAR(sun_lx, 179 * 400 * std::sin(40 * k_deg), 1e-6);
    const Sky sky = make_sky(description, sun_lx);
    EXPECT_NEAR(to_photometric(sky.radiance(description.compass.up)), 5000, 5000 * 1e-6);
    const double sky_lx = sky.horizontal_illuminance_lx();
    EXPECT_NEAR(*sky.ground_radiance, 0.3 * (sky_lx + sun_lx) / (k_pi * 179), 1e-6);
}

// Perez et al. 1990/1993 worked by hand for DNI 600 W/m², DHI 150 W/m², sun at altitude 40°,
// 21 June (day 172): air mass 1.55255, eccentricity 0.967443, Δ = 0.176094, ε = 3.36432 (bin
// 6 of 8), diffuse efficacy 140.9134 lm/W, direct 98.47246 lm/W.
constexpr double k_diffuse_lx = 21137.013007895977;
constexpr double k_direct_lx = 59083.476044456045;

TEST(PerezSky, FromIrradianceGivesTheDiffuseIlluminanceAndTheSun) {
    const Compass compass;
    const Vec3 sun_dir = compass.direction(40, 180);
    const PerezSkyAndSun result =
        perez_sky_and_sun(SolarIrradiance{600, 150}, compass, sun_dir, 172, 0.2);
    const auto& perez = std::get<PerezSky>(result.sky.model);
    EXPECT_NEAR(perez.clearness, 3.364318312959384, 1e-9);
    EXPECT_NEAR(perez.brightness, 0.17609366554294734, 1e-9);
    EXPECT_NEAR(result.sky.relative_luminance(compass.up), 1, 1e-12);
    EXPECT_NEAR(result.sky.horizontal_illuminance_lx() / k_diffuse_lx, 1, 1e-4);
    ASSERT_TRUE(result.sun);
    EXPECT_NEAR(to_photometric(result.sun->irradiance) / k_direct_lx, 1, 1e-6);
    EXPECT_NEAR(result.sun->angular_diameter_deg, 0.533, 1e-12);
    const double global = k_diffuse_lx + k_direct_lx * std::sin(40 * k_deg);
    EXPECT_NEAR(*result.sky.ground_radiance / (0.2 * global / (k_pi * 179)), 1, 1e-4);
    // The bin's coefficients by hand: a … e = −0.94248, −0.33678, 13.02975, −3.44208, 0.26195;
    // the point at altitude 20°, 60° of azimuth from the sun.
    EXPECT_NEAR(result.sky.relative_luminance(compass.direction(20, 120)), 1.7835149637469623,
                1e-6);
}

TEST(PerezSky, FromIlluminanceFindsTheSameSky) {
    const Compass compass;
    const Vec3 sun_dir = compass.direction(40, 180);
    const PerezSkyAndSun result = perez_sky_and_sun(SolarIlluminance{k_direct_lx, k_diffuse_lx},
                                                    compass, sun_dir, 172, std::nullopt);
    const auto& perez = std::get<PerezSky>(result.sky.model);
    EXPECT_NEAR(perez.clearness, 3.364318312959384, 1e-5);
    EXPECT_NEAR(perez.brightness, 0.17609366554294734, 1e-6);
    EXPECT_NEAR(result.sky.horizontal_illuminance_lx() / k_diffuse_lx, 1, 1e-4);
    EXPECT_NEAR(to_photometric(result.sun->irradiance) / k_direct_lx, 1, 1e-6);
    EXPECT_FALSE(result.sky.ground_radiance);
}

TEST(PerezSky, ZenithIsOneAndNightIsDark) {
    const Compass compass;
    for (const double clearness : {1.0, 1.1, 1.4, 1.7, 2.3, 3.5, 5.0, 9.0})
        for (const double brightness : {0.05, 0.2, 0.4}) {
            const Sky sky = sky_of(PerezSky{clearness, brightness}, 35, 90);
            EXPECT_NEAR(sky.relative_luminance(compass.up), 1, 1e-12);
        }
    const PerezSkyAndSun night =
        perez_sky_and_sun(SolarIrradiance{0, 0}, compass, compass.direction(-20, 0), 10, 0.2);
    EXPECT_EQ(night.sky.zenith_radiance, 0);
    EXPECT_FALSE(night.sun);
    const PerezSkyAndSun dusk =
        perez_sky_and_sun(SolarIrradiance{0, 20}, compass, compass.direction(-2, 270), 10, 0.2);
    EXPECT_FALSE(dusk.sun);
    EXPECT_NEAR(dot(dusk.sky.sun_direction, compass.up), 0, 1e-12); // lifted onto the horizon
    EXPECT_GT(dusk.sky.horizontal_illuminance_lx(), 0);
}

} // namespace
} // namespace penumbra
