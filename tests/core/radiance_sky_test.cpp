// Radiance's skies (issue #30): `!gensky` re-computed against what Radiance's gensky printed
// for the office's skies (the comments and arguments of data/office/sky_*.rad, copied here),
// the office scenes, and the thin-glass material keys of the scene file.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <variant>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/material.h"
#include "core/scene_io.h"
#include "core/solar_position.h"

#include "common/test_util.h"
#include "radiance/gensky.h"

namespace penumbra {
namespace {

radiance::GenskyResult gensky(const std::string& line) {
    radiance::Command command{.where = {"test.rad", 1}};
    std::istringstream in(line);
    for (std::string word; in >> word;)
        command.words.push_back(word);
    return radiance::run_gensky(command);
}

double altitude_deg(const Vec3& sun) {
    return std::asin(sun.z) * 180 / 3.14159265358979323846;
}

// sky_B_clear_sun.rad: "# gensky 3 21 +12 -a 52 -o 0 -m 0 +s -g 0.2", "Solar altitude and
// azimuth: 37.6 -0.0", "Ground ambient level: 14.0", the sun "6.534e+06" toward
// "0.000000 -0.792329 0.610094", and "7 1 7.794e+00 1.803e+01 4.715e-01 ...". Tolerances are
// half a unit of the printed last digit.
TEST(Gensky, ClearSkyWithSunMatchesRadiancesOutput) {
    const auto r = gensky("gensky 3 21 +12 -a 52 -o 0 -m 0 +s -g 0.2");
    EXPECT_EQ(r.sky_type, 1);
    EXPECT_NEAR(altitude_deg(r.sun_direction), 37.6, 0.05);
    EXPECT_NEAR(r.sun_direction.x, 0.000000, 5e-7);
    EXPECT_NEAR(r.sun_direction.y, -0.792329, 5e-7);
    EXPECT_NEAR(r.sun_direction.z, 0.610094, 5e-7);
    EXPECT_NEAR(r.zenith_radiance, 7.794, 5e-4);
    EXPECT_NEAR(r.ground_radiance, 18.03, 5e-3);
    EXPECT_NEAR(r.normalisation, 0.4715, 5e-5);
    EXPECT_NEAR(r.ambient_level, 14.0, 0.05);
    ASSERT_TRUE(r.sun);
    EXPECT_NEAR(r.sun_radiance, 6.534e6, 500);
}

// sky_A_overcast.rad: "# gensky 3 21 +12 -c -B 55.866 -g 0.2", "Solar altitude and azimuth:
// 51.8 -0.0" (gensky's default site, 0.66 rad north), "Ground ambient level: 17.8",
// "3 2 2.286e+01 3.557e+00".
TEST(Gensky, OvercastSkyMatchesRadiancesOutput) {
    const auto r = gensky("gensky 3 21 +12 -c -B 55.866 -g 0.2");
    EXPECT_EQ(r.sky_type, 2);
    EXPECT_NEAR(altitude_deg(r.sun_direction), 51.8, 0.05);
    EXPECT_NEAR(r.zenith_radiance, 22.86, 5e-3);
    EXPECT_NEAR(r.ground_radiance, 3.557, 5e-4);
    EXPECT_NEAR(r.ambient_level, 17.8, 0.05);
    EXPECT_FALSE(r.sun);
    // -B is the horizontal irradiance: 55.866 W/m² × 179 lm/W = 10 000 lx, and for the CIE
    // overcast sky E_h = (7π/9) L_z.
    EXPECT_NEAR(r.zenith_radiance * 7 * 3.14159265358979323846 / 9, 55.866, 1e-3);
}

TEST(Gensky, SolarPositionAtNoonOfTheEquinox) {
    // Solar noon of 21 March (day 80): declination 0.4093 sin(2π(80 − 81)/365) = −0.4037°, so
    // the altitude is 90° − 52° − 0.4037° and the sun due south (azimuth 180° from north).
    const SolarAngles a = solar_position_gensky({.latitude_deg = 52}, 3, 21, 12.0, true);
    const double declination_deg =
        0.4093 * std::sin(-2 * 3.14159265358979323846 / 365) * 180 / 3.14159265358979323846;
    EXPECT_NEAR(a.altitude_deg, 38 + declination_deg, 1e-9);
    EXPECT_NEAR(a.azimuth_deg, 180, 1e-9);
    // Standard time: at longitude 0 in time zone 0 the sun is due south when solar time is
    // 12, that is at 12 h − (equation of time); morning suns are east (azimuth < 180°).
    const SolarAngles morning =
        solar_position_gensky({.latitude_deg = 52, .longitude_deg = 0}, 3, 21, 9.0, false);
    EXPECT_GT(morning.azimuth_deg, 90);
    EXPECT_LT(morning.azimuth_deg, 180);
    // Longitude 15° east in time zone 0: solar time is one hour ahead of standard time.
    const SolarAngles east =
        solar_position_gensky({.latitude_deg = 52, .longitude_deg = 15}, 3, 21, 11.0, false);
    const SolarAngles noon =
        solar_position_gensky({.latitude_deg = 52, .longitude_deg = 0}, 3, 21, 12.0, false);
    EXPECT_NEAR(east.altitude_deg, noon.altitude_deg, 1e-9);
    EXPECT_NEAR(east.azimuth_deg, noon.azimuth_deg, 1e-9);
}

/// ∫ relative luminance × cos θ dω over the upper hemisphere by the midpoint rule, for the sun
/// at altitude \p altitude (radians) in the plane y-z.
double intermediate_sky_integral(double altitude) {
    const double pi = 3.14159265358979323846;
    const Vec3 sun(0, -std::cos(altitude), std::sin(altitude));
    constexpr int n_theta = 200, n_phi = 400;
    double sum = 0;
    for (int i = 0; i < n_theta; ++i) {
        const double theta = (i + 0.5) / n_theta * pi / 2;
        for (int j = 0; j < n_phi; ++j) {
            const double phi = (j + 0.5) / n_phi * 2 * pi;
            const Vec3 d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                         std::cos(theta));
            const double gamma = std::acos(std::clamp(dot(d, sun), -1.0, 1.0));
            sum += radiance_intermediate_sky(theta, gamma, pi / 2 - altitude) * std::cos(theta) *
                   std::sin(theta);
        }
    }
    return sum * (pi / 2 / n_theta) * (2 * pi / n_phi);
}

// gensky's normalisation of the intermediate sky (gensky.c, normsc() and F2): a polynomial fit
// of ∫ L cos θ dω / L_z × F2, with F2 its closed-form approximation of the zenith value. Our
// integral of the exact formula agrees with the fit to 2 % from 10° to 75° (the fit's own error).
TEST(Gensky, IntermediateSkyIntegralAgreesWithGenskysFit) {
    const double pi = 3.14159265358979323846;
    for (double altitude_deg : {10.0, 20.0, 30.0, 45.0, 60.0, 75.0}) {
        const double alt = altitude_deg * pi / 180;
        const double x = (alt - pi / 4) / (pi / 4);
        const double fit = 3.5556 + x * (-2.7152 + x * (-1.3081 + x * (1.0660 + x * 0.60227)));
        const double f2 = (2.739 + .9891 * std::sin(.3119 + 2.6 * alt)) *
                          std::exp(-(pi / 2 - alt) * (.4441 + 1.48 * alt));
        EXPECT_NEAR(intermediate_sky_integral(alt) * f2 / fit, 1.0, 0.02)
            << "altitude " << altitude_deg;
    }
    EXPECT_DOUBLE_EQ(radiance_intermediate_sky(0, 0.7, 0.7), 1.0);
}

TEST(Gensky, IntermediateSkyLineGivesTheIntermediateModel) {
    const std::string dir = test::temp_dir("radiance-intermediate");
    std::ofstream(dir + "/sky.rad") << "!gensky 6 21 +14 -a 45 +i\n"
                                       "skyfunc glow sky_glow\n0\n0\n4 1 1 1 0\n"
                                       "sky_glow source sky\n0\n0\n4 0 0 1 180\n";
    std::ofstream(dir + "/scene.json") << R"({"geometry": ["sky.rad"], "polygons": [{"material":
        "m", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0]]}], "materials": {"m": {}}})";
    const Scene scene = load_scene(dir + "/scene.json");
    ASSERT_TRUE(scene.sky && scene.sun);
    EXPECT_TRUE(std::holds_alternative<RadianceIntermediateSky>(scene.sky->model));
    const auto r = gensky("gensky 6 21 +14 -a 45 +i");
    EXPECT_EQ(r.sky_type, 4);
    // A2 is within gensky's approximation F2 of the zenith value (0.5 % here).
    EXPECT_NEAR(scene.sky->zenith_radiance / r.zenith_radiance, 1.0, 0.005);
}

// ---- !gendaylit ----------------------------------------------------------------------------

/// The office B's geometry under the sky of \p line (sky and ground hemispheres driven by its
/// `skyfunc`).
Scene scene_under(const std::string& line) {
    const std::string dir = test::temp_dir("radiance-gendaylit");
    std::ofstream(dir + "/sky.rad") << line << "\n";
    const std::string office_dir = test::source_path("data/office");
    std::ofstream(dir + "/scene.json")
        << R"({"geometry": [")" << office_dir << R"(/materials.rad", ")" << office_dir
        << R"(/office.rad", "sky.rad", ")" << office_dir << R"(/skyglow.rad"]})";
    return load_scene(dir + "/scene.json");
}

// 21 June (day 172) at solar noon, 45° N, 700 W/m² direct normal, 150 W/m² diffuse. The sun is
// gensky's (solar_position_gensky). ε, Δ and the luminous efficacies are computed here from
// Perez et al. 1990 (eqs. 1, 2, 7, 8; Table 4's bin 4.5 ≤ ε < 6.2, 2 cm of precipitable water),
// Kasten's air mass and Spencer's eccentricity: the sun's normal irradiance is the direct
// illuminance / 179 lm/W, the sky integrates to the diffuse illuminance (to the quadrature's
// 1e-4), the ground is ρ (E_d + E_s sin h) / (π 179).
TEST(Gendaylit, LineGivesPerezsSunSkyAndGround) {
    const double pi = 3.14159265358979323846;
    const Scene scene = scene_under("!gendaylit 6 21 +12 -a 45 -o 0 -m 0 -W 700 150 -g 0.2");
    ASSERT_TRUE(scene.sun && scene.sky);
    const SolarAngles angles = solar_position_gensky({45, 0, 0}, 6, 21, 12, true);
    const Compass axes; // Radiance's: z up, y north
    const Vec3 sun = axes.direction(angles.altitude_deg, angles.azimuth_deg);
    for (std::size_t i = 0; i < 3; ++i)
        EXPECT_NEAR(scene.sun->direction[i], sun[i], 1e-9);

    const double z = std::acos(sun.z), kz3 = 1.041 * z * z * z;
    const double clearness = ((150.0 + 700.0) / 150.0 + kz3) / (1 + kz3);
    ASSERT_GT(clearness, 4.5);
    ASSERT_LT(clearness, 6.2);
    const double z_deg = z * 180 / pi;
    const double air_mass = 1 / (std::cos(z) + 0.15 * std::pow(93.885 - z_deg, -1.253));
    const double day_angle = 2 * pi * (172 - 1) / 365.0;
    const double eccentricity = 1.00011 + 0.034221 * std::cos(day_angle) +
                                0.00128 * std::sin(day_angle) + 0.000719 * std::cos(2 * day_angle) +
                                0.000077 * std::sin(2 * day_angle);
    const double brightness = 150.0 * air_mass / (1367.0 * eccentricity);
    const double direct_efficacy =
        105.75 + 0.77 * 2 - 1.26 * std::exp(5.73 * z - 5) - 34.44 * brightness;
    const double diffuse_efficacy =
        141.88 + 1.90 * 2 - 53.24 * std::cos(z) - 14.03 * std::log(brightness);
    const double direct_lx = 700 * direct_efficacy, diffuse_lx = 150 * diffuse_efficacy;

    EXPECT_NEAR(scene.sun->irradiance.g, direct_lx / 179, 1e-5 * direct_lx / 179);
    EXPECT_NEAR(scene.sun->angular_diameter_deg, 0.533, 1e-12);
    ASSERT_TRUE(std::holds_alternative<PerezCoefficientsSky>(scene.sky->model));
    EXPECT_EQ(scene.sky->horizon, Horizon::radiance_blend);
    EXPECT_NEAR(scene.sky->zenith_radiance *
                    scene.sky->horizontal_illuminance_per_zenith_luminance(),
                diffuse_lx / 179, 2e-4 * diffuse_lx / 179);
    EXPECT_NEAR(scene.sky->ground_radiance.value_or(-1),
                0.2 * (diffuse_lx + direct_lx * sun.z) / (pi * 179), 1e-5);

    // The sky's shape, through perezlum.cal's coefficients: that of perez_sky_and_sun() for the
    // same weather and sun.
    const Sky direct =
        perez_sky_and_sun(SolarIrradiance{700, 150}, axes, sun, 172, 0.2, Horizon::radiance_blend)
            .sky;
    for (const Vec3& dir : {Vec3(0, 0, 1), normalize(Vec3(0, -1, 1)), normalize(Vec3(1, 0, 0.2)),
                            normalize(Vec3(0, 1, 0.05)), normalize(Vec3(-1, 1, -0.3))}) {
        const double want = direct.radiance(dir).g;
        EXPECT_NEAR(scene.sky->radiance(dir).g, want, 1e-9 * want) << dir.x << " " << dir.y;
    }
}

// -L gives illuminances, -G the direct light on the horizontal, -s drops the sun.
TEST(Gendaylit, IlluminanceDirectHorizontalAndNoSun) {
    const Scene w = scene_under("!gendaylit 6 21 +12 -a 45 -o 0 -m 0 -W 700 150");
    ASSERT_TRUE(w.sun && w.sky);
    const double sin_h = w.sun->direction.z;
    const Scene g = scene_under("!gendaylit 6 21 +12 -a 45 -o 0 -m 0 -G " +
                                std::to_string(700 * sin_h) + " 150");
    ASSERT_TRUE(g.sun && g.sky);
    EXPECT_NEAR(g.sun->irradiance.g, w.sun->irradiance.g, 1e-5 * w.sun->irradiance.g);
    EXPECT_NEAR(g.sky->zenith_radiance, w.sky->zenith_radiance, 1e-5 * w.sky->zenith_radiance);
    // The illuminances the -W line stands for give the same sky and sun back.
    const double direct_lx = w.sun->irradiance.g * 179;
    const double diffuse_lx =
        w.sky->zenith_radiance * w.sky->horizontal_illuminance_per_zenith_luminance() * 179;
    const Scene l = scene_under("!gendaylit 6 21 +12 -a 45 -o 0 -m 0 -L " +
                                std::to_string(direct_lx) + " " + std::to_string(diffuse_lx));
    ASSERT_TRUE(l.sun && l.sky);
    EXPECT_NEAR(l.sun->irradiance.g, w.sun->irradiance.g, 1e-3 * w.sun->irradiance.g);
    EXPECT_NEAR(l.sky->zenith_radiance, w.sky->zenith_radiance, 1e-3 * w.sky->zenith_radiance);
    const Scene s = scene_under("!gendaylit 6 21 +12 -a 45 -o 0 -m 0 -W 700 150 -s");
    EXPECT_FALSE(s.sun.has_value());
    ASSERT_TRUE(s.sky.has_value());
    EXPECT_DOUBLE_EQ(s.sky->zenith_radiance, w.sky->zenith_radiance);
}

// A perezlum.cal brightfunc as gendaylit prints it: A1 (1 + a e^(b/Dz)) (1 + c e^(dγ) + e cos²γ)
// above the horizon, blended with A2 by skybright.cal's weights (Dz + 1.01)^±10.
TEST(Gendaylit, PerezlumFunctionGivesItsRadiance) {
    const Scene scene = scene_under("void brightfunc skyfunc\n2 skybright perezlum.cal\n0\n"
                                    "10 12.5 3.5 -1.0 -0.32 10 -3 0.45 0 -0.6 0.8");
    ASSERT_TRUE(scene.sky);
    ASSERT_TRUE(std::holds_alternative<PerezCoefficientsSky>(scene.sky->model));
    const Vec3 sun(0, -0.6, 0.8);
    for (const Vec3& dir : {Vec3(0, 0, 1), normalize(Vec3(0.3, -0.5, 0.8)),
                            normalize(Vec3(1, 1, 0.1)), normalize(Vec3(0, -1, 0.02))}) {
        const double gamma = std::acos(std::clamp(dot(dir, sun), -1.0, 1.0));
        const double c = std::cos(gamma);
        const double sky =
            12.5 * (1 - std::exp(-0.32 / dir.z)) * (1 + 10 * std::exp(-3 * gamma) + 0.45 * c * c);
        const double ws = std::pow(dir.z + 1.01, 10), wg = std::pow(dir.z + 1.01, -10);
        const double want = (ws * sky + wg * 3.5) / (ws + wg);
        EXPECT_NEAR(scene.sky->radiance(dir).g, want, 1e-6 * want) << dir.x << " " << dir.z;
    }
    EXPECT_DOUBLE_EQ(scene.sky->ground_radiance.value_or(-1), 3.5);
}

/// The office scene \p name (data/office/).
Scene office(const std::string& name) {
    return load_scene(test::source_path("data/office/" + name + ".json"));
}

const Material& material_named(const Scene& scene, const std::string& name) {
    for (const Material& m : scene.materials)
        if (m.name == name)
            return m;
    throw std::runtime_error("no material " + name);
}

TEST(OfficeScenes, OvercastGlazedOfficeLoads) {
    const Scene a = office("A");
    EXPECT_EQ(a.polygons.size(), 10u); // floor, ceiling, 3 walls, 4 pieces of the front, pane
    EXPECT_EQ(a.materials.size(), 4u);
    // The .pts file's 77 sensors, then the 'workplane' grid's 77 over the same points.
    ASSERT_EQ(a.sensors.size(), 154u);
    ASSERT_EQ(a.grids.size(), 1u);
    for (std::size_t i = 0; i < 77; ++i)
        EXPECT_LT(length(a.sensors[77 + i].position - a.sensors[i].position), 1e-9) << i;
    EXPECT_NEAR(a.sensors.front().position.z, 0.85, 1e-12);
    EXPECT_EQ(a.sensors.front().normal, Vec3(0, 0, 1));
    EXPECT_FLOAT_EQ(material_named(a, "wall_mat").reflectance.g, 0.5f);
    EXPECT_FLOAT_EQ(material_named(a, "floor_mat").reflectance.g, 0.2f);
    EXPECT_FLOAT_EQ(material_named(a, "ceiling_mat").reflectance.g, 0.8f);
    const Material& glass = material_named(a, "glass_70");
    ASSERT_TRUE(glass.lobe && std::holds_alternative<ThinGlass>(*glass.lobe));
    EXPECT_NEAR(std::get<ThinGlass>(*glass.lobe).transmittance(1.0).g, 0.700, 5e-4);
    EXPECT_FALSE(a.sun.has_value());
    ASSERT_TRUE(a.sky.has_value());
    EXPECT_TRUE(std::holds_alternative<CieOvercastSky>(a.sky->model));
    EXPECT_DOUBLE_EQ(a.sky->zenith_radiance, 22.86);
    EXPECT_DOUBLE_EQ(a.sky->ground_radiance.value_or(-1), 3.557);
    EXPECT_EQ(a.sky->horizon, Horizon::radiance_blend);
}

TEST(OfficeScenes, OpenOfficeHasNoPane) {
    const Scene open = office("A-open");
    EXPECT_EQ(open.polygons.size(), 9u);
    EXPECT_EQ(open.materials.size(), 3u);
    EXPECT_EQ(open.sensors.size(), 154u); // the .pts file's and the grid's
    EXPECT_TRUE(open.sky.has_value());
}

TEST(OfficeScenes, ClearSkyOfficeHasGenskysSun) {
    const Scene b = office("B");
    EXPECT_EQ(b.polygons.size(), 10u);
    ASSERT_TRUE(b.sun && b.sky);
    EXPECT_NEAR(b.sun->direction.y, -0.792329, 1e-6);
    EXPECT_NEAR(b.sun->direction.z, 0.610094, 1e-6);
    const double disc_sr =
        2 * 3.14159265358979323846 * (1 - std::cos(0.25 * 3.14159265358979323846 / 180));
    EXPECT_NEAR(b.sun->irradiance.g, 6.534e6 * disc_sr, 1e-3);
    ASSERT_TRUE(std::holds_alternative<CieGeneralSky>(b.sky->model));
    EXPECT_EQ(std::get<CieGeneralSky>(b.sky->model).type, 12);
    EXPECT_NEAR(b.sky->ground_radiance.value_or(-1), 18.03, 1e-9);
}

TEST(OfficeScenes, GenskyLineGivesTheSkyGenskyPrinted) {
    // The office B with its sky file replaced by the gensky line it came from.
    const std::string dir = test::temp_dir("radiance-gensky");
    std::ofstream(dir + "/sky.rad") << "!gensky 3 21 +12 -a 52 -o 0 -m 0 +s -g 0.2\n";
    const std::string office_dir = test::source_path("data/office");
    std::ofstream(dir + "/scene.json")
        << R"({"geometry": [")" << office_dir << R"(/materials.rad", ")" << office_dir
        << R"(/office.rad", "sky.rad", ")" << office_dir << R"(/skyglow.rad"]})";
    const Scene ours = load_scene(dir + "/scene.json");
    const Scene printed = office("B");
    ASSERT_TRUE(ours.sun && ours.sky);
    for (std::size_t i = 0; i < 3; ++i)
        EXPECT_NEAR(ours.sun->direction[i], printed.sun->direction[i], 5e-7);
    EXPECT_NEAR(ours.sun->irradiance.g, printed.sun->irradiance.g,
                1e-4 * printed.sun->irradiance.g);
    EXPECT_NEAR(ours.sky->zenith_radiance, printed.sky->zenith_radiance, 1e-4 * 7.794);
    EXPECT_NEAR(*ours.sky->ground_radiance, *printed.sky->ground_radiance, 5e-3);
}

// ---- Thin glass in the scene file ---------------------------------------------------------

std::string glass_scene(const std::string& glass) {
    return R"({"polygons": [{"name": "lamp", "material": "lamp",
      "vertices": [[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]]},
     {"name": "pane", "material": "glass",
      "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]}],
  "materials": {"lamp": {"emission": 1}, "glass": )" +
           glass + "}}";
}

const ThinGlass& pane_of(const Scene& scene) {
    const Material& m = material_named(scene, "glass");
    EXPECT_TRUE(m.reflectance.is_black());
    return std::get<ThinGlass>(m.lobe.value());
}

TEST(ThinGlassMaterial, TransmittanceAtNormalIncidenceUsesRadiancesFormula) {
    // The office's glass (shared/scenes/office/materials.rad): Tn = 0.70 gives tn = 0.762842
    // by (sqrt(.8402528435 + .0072522239 Tn²) − .9166530661) / .0036261119 / Tn.
    const Scene s = parse_scene(
        glass_scene(R"({"type": "thin_glass", "transmittance_normal": 0.70})"), "s.json", ".");
    const ThinGlass& pane = pane_of(s);
    EXPECT_NEAR(pane.transmissivity.g, 0.762842, 1e-6);
    EXPECT_DOUBLE_EQ(pane.ior, 1.52);
    // At another index the inversion still gives back the normal transmittance.
    const Scene dense = parse_scene(
        glass_scene(
            R"({"type": "thin_glass", "transmittance_normal": [0.6, 0.7, 0.8], "ior": 1.7})"),
        "s.json", ".");
    const ThinGlass& d = pane_of(dense);
    EXPECT_DOUBLE_EQ(d.ior, 1.7);
    EXPECT_NEAR(d.transmittance(1.0).r, 0.6, 1e-6);
    EXPECT_NEAR(d.transmittance(1.0).b, 0.8, 1e-6);
}

TEST(ThinGlassMaterial, TransmissivityIsTakenAsGiven) {
    const Scene s = parse_scene(
        glass_scene(R"({"type": "thin_glass", "transmissivity": 0.9, "two_sided": false})"),
        "s.json", ".");
    EXPECT_FLOAT_EQ(pane_of(s).transmissivity.r, 0.9f);
    EXPECT_FALSE(material_named(s, "glass").two_sided);
}

TEST(ThinGlassMaterial, BadKeysAreErrors) {
    const auto expect_error = [](const std::string& glass, const std::string& part) {
        try {
            parse_scene(glass_scene(glass), "s.json", ".");
            ADD_FAILURE() << "no InputError for " << glass;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
        }
    };
    expect_error(R"({"type": "thin_glass"})", "exactly one of");
    expect_error(R"({"type": "thin_glass", "transmissivity": 0.9, "transmittance_normal": 0.8})",
                 "exactly one of");
    expect_error(R"({"type": "thin_glass", "transmissivity": 0.9, "reflectance": 0.1})",
                 "materials.glass.reflectance");
    expect_error(R"({"type": "thin_glass", "transmittance_normal": 0.95})",
                 "materials.glass.transmittance_normal");
    expect_error(R"({"type": "thin_glass", "transmissivity": 0.9, "ior": 1})", "(1, 10]");
    expect_error(R"({"transmissivity": 0.9})", "not a key of a 'diffuse' material");
    expect_error(R"({"type": "chrome"})", "unknown material type 'chrome'");
}

} // namespace
} // namespace penumbra
