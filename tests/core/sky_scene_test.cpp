// The scene keys of daylight: `site`, `sky`, and `sun.time`, good and bad.

#include <cmath>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/scene_io.h"
#include "core/solar_position.h"

#include "common/test_util.h"

namespace penumbra {
namespace {

constexpr double k_deg = k_pi / 180;

/// A floor under the sky, plus \p extra top-level keys (each line starting with a comma).
Scene load(const std::string& extra) {
    const std::string dir = test::temp_dir("sky_scene");
    const std::string path = dir + "/scene.json";
    std::ofstream(path) << R"({
  "polygons": [{"name": "floor", "material": "floor",
                "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]}],
  "materials": {"floor": {"reflectance": 0.5}})"
                        << extra << "\n}\n";
    return load_scene(path);
}

void expect_error(const std::string& extra, std::initializer_list<std::string> parts) {
    try {
        load(extra);
        ADD_FAILURE() << "no InputError for " << extra;
    } catch (const InputError& e) {
        const std::string message = e.what();
        for (const std::string& part : parts)
            EXPECT_NE(message.find(part), std::string::npos)
                << "'" << part << "' missing from: " << message;
    }
}

TEST(SkyScene, OvercastByHorizontalIlluminance) {
    const Scene scene = load(R"(,
  "sky": {"model": "cie_overcast", "horizontal_illuminance_lx": 10000})");
    ASSERT_TRUE(scene.sky);
    EXPECT_TRUE(std::holds_alternative<CieOvercastSky>(scene.sky->model));
    EXPECT_NEAR(scene.sky->zenith_radiance, 10000 / (179 * 7 * k_pi / 9), 1e-6);
    EXPECT_NEAR(*scene.sky->ground_radiance, 0.2 * 10000 / (k_pi * 179), 1e-9);
    EXPECT_EQ(scene.sky->horizon, Horizon::sharp);
    EXPECT_FALSE(scene.sun);
}

TEST(SkyScene, UniformByZenithLuminanceWithGroundGeometryAndBlend) {
    const Scene uniform = load(R"(,
  "sky": {"model": "uniform", "zenith_luminance_cd_m2": 2000, "ground": "geometry"})");
    EXPECT_NEAR(uniform.sky->zenith_radiance, 2000.0 / 179, 1e-9);
    EXPECT_FALSE(uniform.sky->ground_radiance);
    const Scene blended = load(R"(,
  "sky": {"model": "uniform", "zenith_luminance_cd_m2": 2000, "ground_reflectance": 0.1,
          "horizon": "radiance_blend"})");
    EXPECT_EQ(blended.sky->horizon, Horizon::radiance_blend);
    EXPECT_NEAR(*blended.sky->ground_radiance, 0.1 * 2000 * k_pi / (k_pi * 179), 1e-9);
}

TEST(SkyScene, ClearSkyAtASolarTimeUsesTheSite) {
    const Scene scene = load(R"(,
  "site": {"latitude_deg": 52, "longitude_deg": 0, "time_zone_h": 0},
  "sky": {"model": "cie_general", "type": 12, "horizontal_illuminance_lx": 20000,
          "time": {"month": 3, "day": 21, "hour": 12, "solar_time": true}})");
    const SolarAngles sun = solar_position_at_solar_time({52, 0, 0}, {2025, 3, 21, 12});
    const Vec3 expected = scene.sky->compass.direction(sun.altitude_deg, sun.azimuth_deg);
    EXPECT_NEAR(length(scene.sky->sun_direction - expected), 0, 1e-12);
    EXPECT_NEAR(scene.sky->sun_direction.y, -std::cos(sun.altitude_deg * k_deg), 1e-9); // south
    EXPECT_NEAR(scene.sky->horizontal_illuminance_lx(), 20000, 20000 * 1e-5);
}

TEST(SkyScene, SunByTimeLightsTheGroundAndPlacesTheSky) {
    const Scene scene = load(R"(,
  "site": {"latitude_deg": 40, "longitude_deg": -105, "time_zone_h": -7, "north": [1, 0, 0]},
  "sun": {"time": {"year": 2010, "month": 6, "day": 21, "hour": 13}, "illuminance_lx": 80000},
  "sky": {"model": "cie_general", "type": 13, "horizontal_illuminance_lx": 15000})");
    ASSERT_TRUE(scene.sun && scene.sky);
    const SolarAngles sun = solar_position({40, -105, -7}, {2010, 6, 21, 13});
    // North is +x, up +z: east is −y.
    const Compass compass{{0, 0, 1}, {1, 0, 0}};
    EXPECT_NEAR(length(scene.sun->direction - compass.direction(sun.altitude_deg, sun.azimuth_deg)),
                0, 1e-12);
    EXPECT_NEAR(length(scene.sky->sun_direction - scene.sun->direction), 0, 1e-12);
    const double global = 15000 + 80000 * std::sin(sun.altitude_deg * k_deg);
    EXPECT_NEAR(*scene.sky->ground_radiance, 0.2 * global / (k_pi * 179), 1e-3);
}

TEST(SkyScene, PerezBringsItsSun) {
    const Scene scene = load(R"(,
  "site": {"latitude_deg": 41.98, "longitude_deg": -87.92, "time_zone_h": -6},
  "sky": {"model": "perez", "direct_normal_w_m2": 600, "diffuse_horizontal_w_m2": 150,
          "time": {"month": 6, "day": 21, "hour": 11}})");
    ASSERT_TRUE(scene.sky && scene.sun);
    EXPECT_TRUE(std::holds_alternative<PerezSky>(scene.sky->model));
    EXPECT_NEAR(length(scene.sky->sun_direction - scene.sun->direction), 0, 1e-12);
    const Scene by_direction = load(R"(,
  "sky": {"model": "perez", "direct_normal_lx": 50000, "diffuse_horizontal_lx": 20000,
          "sun_direction": [0, -1, 1], "day_of_year": 100})");
    EXPECT_NEAR(to_photometric(by_direction.sun->irradiance), 50000, 0.1);
    EXPECT_NEAR(by_direction.sky->horizontal_illuminance_lx(), 20000, 20000 * 1e-4);
}

TEST(SkyScene, BadKeysNameTheirKey) {
    const std::string site =
        R"(, "site": {"latitude_deg": 52, "longitude_deg": 0, "time_zone_h": 0})";
    expect_error(R"(, "sky": {"model": "cloudy", "horizontal_illuminance_lx": 1})",
                 {"'sky.model'", "unknown sky model 'cloudy'"});
    expect_error(R"(, "sky": {"model": "cie_general", "horizontal_illuminance_lx": 1,
                  "sun_direction": [0, 0, 1]})",
                 {"'sky.type'", "missing required key"});
    expect_error(R"(, "sky": {"model": "cie_general", "type": 16, "sun_direction": [0, 0, 1],
                  "horizontal_illuminance_lx": 1})",
                 {"'sky.type'", "[1, 15]"});
    expect_error(R"(, "sky": {"model": "cie_general", "type": 12, "horizontal_illuminance_lx": 1})",
                 {"'sky'", "needs the sun's position"});
    expect_error(R"(, "sky": {"model": "uniform", "horizontal_illuminance_lx": 1,
                  "zenith_luminance_cd_m2": 1})",
                 {"'sky'", "exactly one of"});
    expect_error(R"(, "sky": {"model": "uniform", "horizontal_illuminance_lx": -1})",
                 {"'sky.horizontal_illuminance_lx'"});
    expect_error(R"(, "sky": {"model": "cie_general", "type": 3, "horizontal_illuminance_lx": 1,
                  "time": {"month": 3, "day": 21, "hour": 12}})",
                 {"'sky.time'", "needs the top-level 'site'"});
    expect_error(site + R"(, "sky": {"model": "cie_general", "type": 3,
                  "horizontal_illuminance_lx": 1, "time": {"month": 3, "day": 21, "hour": 25}})",
                 {"'sky.time.hour'", "[0, 24)"});
    expect_error(site + R"(, "sky": {"model": "cie_general", "type": 3,
                  "horizontal_illuminance_lx": 1, "time": {"month": 2, "day": 30, "hour": 2}})",
                 {"'sky.time.day'"});
    expect_error(site + R"(, "sky": {"model": "cie_general", "type": 3,
                  "horizontal_illuminance_lx": 1, "time": {"month": 12, "day": 21, "hour": 2}})",
                 {"'sky'", "below the horizon"});
    expect_error(R"(, "sky": {"model": "uniform", "horizontal_illuminance_lx": 1,
                  "sun_direction": [0, 0, 1]})",
                 {"'sky.sun_direction'", "only used by"});
    expect_error(R"(, "sky": {"model": "uniform", "horizontal_illuminance_lx": 1,
                  "ground": "geometry", "horizon": "radiance_blend"})",
                 {"'sky.horizon'", "radiance_blend"});
    expect_error(R"(, "sky": {"model": "uniform", "horizontal_illuminance_lx": 1,
                  "ground": "geometry", "ground_reflectance": 0.3})",
                 {"'sky.ground_reflectance'", "not both"});
    expect_error(R"(, "sky": {"model": "uniform", "horizontal_illuminance_lx": 1,
                  "ground_reflectance": 1.5})",
                 {"'sky.ground_reflectance'"});
    expect_error(R"(, "sky": {"model": "uniform", "horizontal_illuminance_lx": 1, "hozion": 1})",
                 {"'sky.hozion'", "unknown key"});
    expect_error(R"(, "sun": {"direction": [0, 1, 1], "illuminance_lx": 1e5},
                  "sky": {"model": "perez", "direct_normal_w_m2": 500,
                  "diffuse_horizontal_w_m2": 100, "sun_direction": [0, 1, 1], "day_of_year": 3})",
                 {"'sky'", "brings its own sun"});
    expect_error(R"(, "sky": {"model": "perez", "direct_normal_w_m2": 500,
                  "sun_direction": [0, 1, 1], "day_of_year": 3})",
                 {"'sky.diffuse_horizontal_w_m2'", "missing required key"});
    expect_error(R"(, "sky": {"model": "perez", "direct_normal_w_m2": 500,
                  "diffuse_horizontal_w_m2": 100, "sun_direction": [0, 1, 1]})",
                 {"'sky'", "'day_of_year'"});
    expect_error(R"(, "sun": {"direction": [0, 1, 1], "illuminance_lx": 1e5},
                  "sky": {"model": "cie_general", "type": 12, "horizontal_illuminance_lx": 1,
                  "sun_direction": [0, -1, 1]})",
                 {"'sky.sun_direction'", "give the sun's position once"});
    expect_error(R"(, "site": {"latitude_deg": 100, "longitude_deg": 0, "time_zone_h": 0},
                  "sun": {"direction": [0, 1, 1], "illuminance_lx": 1})",
                 {"'site.latitude_deg'", "[-90, 90]"});
    expect_error(R"(, "site": {"latitude_deg": 10, "longitude_deg": 0, "time_zone_h": 0,
                  "north": [0, 0, 2]}, "sun": {"direction": [0, 1, 1], "illuminance_lx": 1})",
                 {"'site.north'", "not parallel to 'up'"});
    expect_error(site + R"(, "sun": {"time": {"month": 1, "day": 5, "hour": 23},
                  "illuminance_lx": 1e5})",
                 {"'sun.time'", "below the horizon"});
    expect_error(site + R"(, "sun": {"time": {"month": 1, "day": 5, "hour": 12},
                  "direction": [0, 0, 1], "illuminance_lx": 1e5})",
                 {"'sun'", "not both"});
}

} // namespace
} // namespace penumbra
