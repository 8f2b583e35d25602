#include "core/scene_io.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/rgb.h"

#include "common/test_util.h"

namespace penumbra {
namespace {

std::string write_file(const std::string& dir, const std::string& name, const std::string& text) {
    const std::string path = dir + "/" + name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

/// Runs \p load, expects an InputError, and checks that its message holds every part.
void expect_input_error(const std::function<void()>& load,
                        std::initializer_list<std::string> parts) {
    try {
        load();
        ADD_FAILURE() << "no InputError thrown";
    } catch (const InputError& e) {
        const std::string message = e.what();
        for (const std::string& part : parts)
            EXPECT_NE(message.find(part), std::string::npos)
                << "'" << part << "' missing from: " << message;
    }
}

/// A scene file with one emitting 1 m × 1 m inline square facing +z, plus \p extra keys.
std::string lamp_scene(const std::string& extra = "") {
    return R"json({
  "polygons": [{"name": "lamp", "material": "lamp",
                "vertices": [[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]]}],
  "materials": {"lamp": {"emission": 1}})json" +
           extra + "\n}\n";
}

Vec3 newell_normal(const Polygon& polygon) {
    Vec3 n;
    const auto& v = polygon.vertices;
    for (std::size_t i = 0; i < v.size(); ++i)
        n += cross(v[i], v[(i + 1) % v.size()]);
    return n;
}

double area_m2(const Polygon& polygon) {
    return 0.5 * length(newell_normal(polygon));
}

const Material& material_named(const Scene& scene, const std::string& name) {
    for (const Material& m : scene.materials)
        if (m.name == name)
            return m;
    throw std::runtime_error("no material " + name);
}

// Loading \p path throws one InputError line that names every one of \p parts and \p file.
void expect_one_line_error(const std::string& path, std::vector<std::string> parts,
                           const std::string& file) {
    parts.push_back(file);
    test::expect_one_line_input_error([&] { load_scene(path); }, parts, path);
}

TEST(SceneIo, LoadsCornellBox) {
    const Scene scene = load_scene(test::source_path("data/cornell/scene.json"));
    EXPECT_EQ(scene.name, "cornell-box");
    EXPECT_EQ(scene.up.y, 1.0);            // "up": [0, 1, 0]
    ASSERT_EQ(scene.polygons.size(), 16u); // 5 walls, 5 + 5 block faces, 1 light
    for (const Polygon& polygon : scene.polygons)
        EXPECT_EQ(polygon.vertices.size(), 4u) << polygon.source;
    EXPECT_EQ(scene.materials.size(), 4u); // assimp's unused default material is dropped

    const Polygon& floor = scene.polygons[0];
    EXPECT_EQ(floor.name, "floor");
    EXPECT_EQ(floor.source, "cornell.obj:face 1");
    EXPECT_NEAR(floor.vertices[0].x, 0.5528, 1e-7); // 552.8 mm
    EXPECT_NEAR(floor.vertices[3].z, 0.5592, 1e-7);
    EXPECT_GT(newell_normal(floor).y, 0); // faces up, into the box
    EXPECT_EQ(scene.polygons[15].name, "light");
    EXPECT_EQ(scene.polygons[15].source, "cornell.obj:face 16");

    const Material& light = material_named(scene, "light");
    EXPECT_EQ(light.emission, Rgb(17, 12, 4));
    EXPECT_FALSE(light.emission_two_sided);
    const Material& white = material_named(scene, "white");
    EXPECT_EQ(white.reflectance, Rgb(0.725f, 0.71f, 0.68f));
    EXPECT_TRUE(white.emission.is_black());
    EXPECT_EQ(material_named(scene, "red").reflectance, Rgb(0.63f, 0.065f, 0.05f));
    EXPECT_EQ(material_named(scene, "green").reflectance, Rgb(0.14f, 0.45f, 0.091f));

    ASSERT_TRUE(scene.camera.has_value());
    const Camera& camera = *scene.camera;
    EXPECT_NEAR(camera.eye.x, 0.278, 1e-12);
    EXPECT_NEAR(camera.eye.y, 0.273, 1e-12);
    EXPECT_NEAR(camera.eye.z, -0.8, 1e-12);
    EXPECT_NEAR(camera.look_at.z, 0.0, 1e-12);
    EXPECT_EQ(camera.up, Vec3(0, 1, 0));
    EXPECT_NEAR(camera.fov_deg, 39.3077, 1e-4);
    EXPECT_TRUE(camera.fov_axis_x);
    EXPECT_EQ(camera.width, 256);
    EXPECT_EQ(camera.height, 256);
    EXPECT_NEAR(scene.mesher.max_edge_length, 0.100, 1e-12); // 40 mm
    EXPECT_DOUBLE_EQ(scene.solver.residual, 1e-3);
}

TEST(SceneIo, CornellLightPowerInMetres) {
    const Scene scene = load_scene(test::source_path("data/cornell/scene.json"));
    const Polygon& light = scene.polygons.back();
    ASSERT_EQ(scene.materials[light.material].name, "light");
    const double area = area_m2(light);
    EXPECT_NEAR(area, 0.130 * 0.105, 1e-9);
    EXPECT_LT(newell_normal(light).y, 0); // emits downward
    const Rgb& radiance = scene.materials[light.material].emission;
    const double expected[3] = {0.7290, 0.5146, 0.1715}; // π · L · A, W
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(k_pi * radiance[c] * area, expected[c], 1e-3 * expected[c]) << c;
}

TEST(SceneIo, EmissionFluxLmBecomesRadiance) {
    const std::string dir = test::temp_dir("scene-flux");
    // 200 cm × 100 cm = 2 m², 1000 lm: L = 1000 / (π · 2) cd/m².
    write_file(dir, "scene.json", R"json({
  "units": "cm",
  "polygons": [
    {"name": "a", "material": "panel",
     "vertices": [[0, 0, 0], [200, 0, 0], [200, 100, 0], [0, 100, 0]]},
    {"name": "b", "material": "both",
     "vertices": [[0, 0, 0], [100, 0, 0], [100, 100, 0], [0, 100, 0]]}
  ],
  "materials": {
    "panel": {"emission_flux_lm": 1000, "emission_color": [1, 0.5, 0.25]},
    "both": {"emission_flux_lm": 1000, "emission_two_sided": true}
  }
})json");
    const Scene scene = load_scene(dir + "/scene.json");
    const Material& panel = material_named(scene, "panel");
    EXPECT_NEAR(to_photometric(panel.emission), 1000.0 / (k_pi * 2.0), 1e-4);
    EXPECT_NEAR(panel.emission.g / panel.emission.r, 0.5, 1e-6);
    EXPECT_NEAR(panel.emission.b / panel.emission.r, 0.25, 1e-6);
    // Two-sided: 1 m² per side, 2 m² in all.
    const Material& both = material_named(scene, "both");
    EXPECT_NEAR(to_photometric(both.emission), 1000.0 / (k_pi * 2.0), 1e-4);
    EXPECT_EQ(both.emission.r, both.emission.b);
    // Validating again changes nothing.
    Scene again = scene;
    validate_scene(again);
    EXPECT_EQ(again.materials[0].emission, scene.materials[0].emission);
}

// A flux whose radiance overflows the solve's float sums was accepted and became NaN (#32).
TEST(SceneIo, FluxBeyondTheFloatRangeIsAnError) {
    const std::string dir = test::temp_dir("scene-huge-flux");
    for (const char* flux : {"1e39", "1e308"}) {
        write_file(dir, "scene.json",
                   fmt::format(R"json({{
  "polygons": [{{"name": "a", "material": "panel",
                 "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]}}],
  "materials": {{"panel": {{"emission_flux_lm": {}}}}}
}})json",
                               flux));
        expect_input_error([&] { load_scene(dir + "/scene.json"); },
                           {"scene.json", "'materials.panel.emission_flux_lm'", "largest"});
    }
}

TEST(SceneIo, PointLightPhotometry) {
    const std::string dir = test::temp_dir("scene-point");
    write_file(dir, "scene.json", lamp_scene(R"json(,
  "units": "mm",
  "point_lights": [
    {"name": "bulb", "position": [1000, 2000, 3000], "flux_lm": 10000},
    {"position": [0, 0, 500], "intensity_cd": 500, "color": [1, 0.5, 0.5]}
  ])json"));
    const Scene scene = load_scene(dir + "/scene.json");
    ASSERT_EQ(scene.point_lights.size(), 2u);
    const PointLight& bulb = scene.point_lights[0];
    EXPECT_EQ(bulb.name, "bulb");
    EXPECT_NEAR(bulb.position.y, 2.0, 1e-12);
    EXPECT_NEAR(to_photometric(bulb.intensity), 10000.0 / (4.0 * k_pi), 1e-3);
    EXPECT_NEAR(bulb.intensity.r, 10000.0 / (4.0 * k_pi) / 179.0, 1e-5); // white: cd / 179
    const PointLight& red = scene.point_lights[1];
    EXPECT_EQ(red.name, "point_lights[1]");
    EXPECT_NEAR(to_photometric(red.intensity), 500.0, 1e-3);
    EXPECT_NEAR(red.intensity.g / red.intensity.r, 0.5, 1e-6);
}

TEST(SceneIo, SpotLights) {
    const std::string dir = test::temp_dir("scene-spot");
    write_file(dir, "scene.json", lamp_scene(R"json(,
  "units": "mm",
  "point_lights": [
    {"name": "down", "position": [0, 0, 2000], "intensity_cd": 900,
     "spot": {"direction": [0, 0, -2], "beam_deg": 20, "cutoff_deg": 30}},
    {"name": "cone", "position": [0, 0, 2000], "flux_lm": 1000,
     "spot": {"direction": [1, 1, 0], "beam_deg": 10, "cutoff_deg": 50}}
  ])json"));
    const Scene scene = load_scene(dir + "/scene.json");
    ASSERT_EQ(scene.point_lights.size(), 2u);
    const PointLight& down = scene.point_lights[0];
    ASSERT_TRUE(down.spot.has_value());
    EXPECT_NEAR(to_photometric(down.intensity), 900.0, 1e-3); // on the axis
    EXPECT_NEAR(down.spot->direction.z, -1.0, 1e-15);         // normalised, not scaled by mm
    EXPECT_EQ(down.spot->beam_deg, 20.0);
    EXPECT_EQ(down.spot->cutoff_deg, 30.0);
    // flux_lm is the flux in the cone: I = Φ / (2π [(1 − cos b) + (cos b − cos c) / 2]).
    const PointLight& cone = scene.point_lights[1];
    const double cb = std::cos(10 * k_pi / 180), cc = std::cos(50 * k_pi / 180);
    EXPECT_NEAR(to_photometric(cone.intensity), 1000.0 / (2 * k_pi * ((1 - cb) + (cb - cc) / 2)),
                1e-3);
    EXPECT_NEAR(to_photometric(cone.power()), 1000.0, 1e-2);
}

TEST(SceneIo, BadSpotsNameTheKey) {
    const std::string dir = test::temp_dir("scene-bad-spot");
    struct Case {
        const char* spot;
        std::initializer_list<std::string> parts;
    };
    const Case cases[] = {
        {R"({"direction": [0, 0, 0], "beam_deg": 10, "cutoff_deg": 20})",
         {"'point_lights[0].spot.direction'", "non-zero"}},
        {R"({"direction": ["nan", 0, -1], "beam_deg": 10, "cutoff_deg": 20})",
         {"'point_lights[0].spot.direction'", "expected 3 numbers"}},
        {R"({"direction": [0, 0, -1], "beam_deg": 30, "cutoff_deg": 20})",
         {"'point_lights[0].spot.beam_deg'", "[0, cutoff_deg = 20]", "got 30"}},
        {R"({"direction": [0, 0, -1], "beam_deg": -1, "cutoff_deg": 20})",
         {"'point_lights[0].spot.beam_deg'", "got -1"}},
        {R"({"direction": [0, 0, -1], "beam_deg": 10, "cutoff_deg": 181})",
         {"'point_lights[0].spot.cutoff_deg'", "(0, 180]", "got 181"}},
        {R"({"direction": [0, 0, -1], "beam_deg": 0, "cutoff_deg": 0})",
         {"'point_lights[0].spot.cutoff_deg'", "(0, 180]"}},
        {R"({"direction": [0, 0, -1], "beam_deg": 10, "cutoff_deg": 20, "falloff": 2})",
         {"'point_lights[0].spot.falloff'", "unknown key 'falloff'", "cutoff_deg"}},
        {R"({"beam_deg": 10, "cutoff_deg": 20})",
         {"'point_lights[0].spot.direction'", "missing required key"}},
    };
    int i = 0;
    for (const Case& c : cases) {
        const std::string name = "spot" + std::to_string(i++) + ".json";
        write_file(dir, name,
                   lamp_scene(std::string(R"json(, "point_lights": [{"position": [0, 0, 2],
                   "intensity_cd": 100, "spot": )json") +
                              c.spot + "}]"));
        expect_one_line_error(dir + "/" + name, c.parts, name);
    }
}

TEST(SceneIo, ValidateChecksSpotsBuiltInCode) {
    Scene scene;
    scene.file = "code";
    PointLight light;
    light.position = {0, 0, 2};
    light.intensity = Rgb(1.0f);
    light.spot = SpotCone{{0, 0, -3}, 10, 20};
    scene.point_lights.push_back(light);
    scene.polygons.push_back({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 0, "floor", "code:0"});
    scene.materials.push_back(Material{});
    Scene ok = scene;
    validate_scene(ok);
    EXPECT_NEAR(ok.point_lights[0].spot->direction.z, -1.0, 1e-15); // normalised in place
    Scene nan = scene;
    nan.point_lights[0].spot->direction.x = std::nan("");
    expect_input_error([&] { validate_scene(nan); },
                       {"'point_lights[0].spot.direction'", "finite, non-zero"});
    Scene wide = scene;
    wide.point_lights[0].spot->cutoff_deg = 190;
    expect_input_error([&] { validate_scene(wide); }, {"'point_lights[0].spot.cutoff_deg'"});
    Scene inverted = scene;
    inverted.point_lights[0].spot->beam_deg = 25;
    expect_input_error([&] { validate_scene(inverted); }, {"'point_lights[0].spot.beam_deg'"});
}

// ---- The sun: direction toward it, direct normal illuminance or irradiance, disc size ----

TEST(SceneIo, Sun) {
    const std::string dir = test::temp_dir("scene-sun");
    // A scene lit by the sun alone (no emissive material), in millimetres.
    write_file(dir, "lx.json", R"json({
  "units": "mm",
  "polygons": [{"material": "grey", "vertices": [[0, 0, 0], [1000, 0, 0], [0, 1000, 0]]}],
  "materials": {"grey": {"reflectance": 0.5}},
  "sun": {"direction": [0, -3, 4], "illuminance_lx": 80000, "color": [1, 0.9, 0.8]}
})json");
    const Scene lx = load_scene(dir + "/lx.json");
    ASSERT_TRUE(lx.sun.has_value());
    EXPECT_TRUE(lx.has_emitter());
    EXPECT_NEAR(lx.sun->direction.y, -0.6, 1e-15); // normalised, not scaled by mm
    EXPECT_NEAR(lx.sun->direction.z, 0.8, 1e-15);
    EXPECT_NEAR(to_photometric(lx.sun->irradiance), 80000.0, 80000.0 * 1e-6);
    EXPECT_NEAR(lx.sun->irradiance.b / lx.sun->irradiance.r, 0.8, 1e-6);
    EXPECT_EQ(lx.sun->angular_diameter_deg, 0.533);
    EXPECT_NEAR(lx.sun->angular_radius(), 0.2665 * k_pi / 180, 1e-15);
    // E_n · max(0, cos θ).
    EXPECT_NEAR(lx.sun->unoccluded({0, 0, 1}).g, 0.8 * lx.sun->irradiance.g, 1e-3);
    EXPECT_EQ(lx.sun->unoccluded({0, 0.6, -0.8}), Rgb{});

    write_file(dir, "w.json", lamp_scene(R"json(,
  "sun": {"direction": [1, 0, 0], "irradiance_w_m2": [500, 450, 400],
          "angular_diameter_deg": 0})json"));
    const Scene w = load_scene(dir + "/w.json");
    ASSERT_TRUE(w.sun.has_value());
    EXPECT_EQ(w.sun->irradiance, Rgb(500, 450, 400));
    EXPECT_EQ(w.sun->angular_diameter_deg, 0.0);
    write_file(dir, "grey.json", lamp_scene(R"json(,
  "sun": {"direction": [1, 0, 1], "irradiance_w_m2": 300, "angular_diameter_deg": 10})json"));
    EXPECT_EQ(load_scene(dir + "/grey.json").sun->irradiance, Rgb(300));
}

TEST(SceneIo, NamedCamerasAndCausticSettings) {
    const std::string dir = test::temp_dir("scene-cameras");
    write_file(dir, "c.json", lamp_scene(R"json(, "units": "mm",
  "camera": {"eye": [0, 0, 5000], "look_at": [0, 0, 0], "up": [0, 1, 0]},
  "cameras": [{"name": "low", "eye": [1000, 0, 500], "look_at": [0, 0, 0], "fov_deg": 60},
              {"name": "high", "eye": [0, 0, 9000], "look_at": [0, 0, 0], "up": [0, 1, 0]}],
  "image": {"width": 64, "height": 32, "spp": 9},
  "render": {"caustic_photons": 5000, "caustic_radius": 20})json"));
    Scene scene = load_scene(dir + "/c.json");
    ASSERT_EQ(scene.cameras.size(), 2u);
    EXPECT_EQ(scene.render.caustic_photons, 5000);
    ASSERT_TRUE(scene.render.caustic_radius_m.has_value());
    EXPECT_NEAR(*scene.render.caustic_radius_m, 0.02, 1e-15); // scene units: mm
    scene.select_camera("low");
    EXPECT_EQ(scene.camera->eye, Vec3(1, 0, 0.5)); // metres
    EXPECT_EQ(scene.camera->fov_deg, 60);
    EXPECT_EQ(scene.camera->width, 64); // `image` applies to every camera
    EXPECT_EQ(scene.camera->samples_per_pixel, 9);
    test::expect_one_line_input_error([&] { scene.select_camera("attic"); },
                                      {"'attic'", "low", "high"}, "select_camera");

    write_file(dir, "twice.json", lamp_scene(R"json(,
  "cameras": [{"name": "a", "eye": [1, 0, 0], "look_at": [0, 0, 0]},
              {"name": "a", "eye": [2, 0, 0], "look_at": [0, 0, 0]}])json"));
    expect_one_line_error(dir + "/twice.json", {"cameras", "named twice"}, "twice.json");
}

TEST(SceneIo, IrradianceCacheIsABooleanOrItsSettings) {
    const std::string dir = test::temp_dir("scene-irradiance-cache");
    const auto cache_of = [&](const std::string& value) {
        write_file(dir, "c.json",
                   lamp_scene(R"json(, "render": {"irradiance_cache": )json" + value + "}"));
        return load_scene(dir + "/c.json").render.irradiance_cache;
    };
    write_file(dir, "none.json", lamp_scene());
    EXPECT_FALSE(load_scene(dir + "/none.json").render.irradiance_cache.has_value());
    EXPECT_FALSE(cache_of("false").has_value());
    ASSERT_TRUE(cache_of("true").has_value());
    EXPECT_EQ(cache_of("true")->rays, IrradianceCacheSettings{}.rays);
    const auto set = cache_of(R"json({"rays": 64, "error": 0.3})json");
    ASSERT_TRUE(set.has_value());
    EXPECT_EQ(set->rays, 64);
    EXPECT_EQ(set->error, 0.3);
}

// render.light_samples, gather_rays and edge_tolerance (docs/rendering.md "Splitting"): read
// as given, and out-of-range values are one-line errors naming the key.
TEST(SceneIo, RenderSamplingSettings) {
    const std::string dir = test::temp_dir("scene-render-sampling");
    write_file(dir, "s.json", lamp_scene(R"json(,
  "render": {"light_samples": 2, "gather_rays": 9, "edge_tolerance": 0})json"));
    const Scene scene = load_scene(dir + "/s.json");
    EXPECT_EQ(scene.render.light_samples, 2);
    EXPECT_EQ(scene.render.gather_rays, 9);
    EXPECT_EQ(scene.render.edge_tolerance, 0.0);
    for (const char* bad :
         {R"("light_samples": 0)", R"("gather_rays": 2000)", R"("edge_tolerance": -1)"}) {
        write_file(dir, "bad.json", lamp_scene(std::string(",\n  \"render\": {") + bad + "}"));
        const std::string key = std::string(bad).substr(1, std::string(bad).find('"', 1) - 1);
        expect_one_line_error(dir + "/bad.json", {"render." + key}, "bad.json");
    }
}

TEST(SceneIo, BadSunsNameTheKey) {
    const std::string dir = test::temp_dir("scene-bad-sun");
    struct Case {
        const char* sun;
        std::initializer_list<std::string> parts;
    };
    const Case cases[] = {
        {R"({"direction": [0, 0, 0], "illuminance_lx": 1e5})", {"'sun.direction'", "non-zero"}},
        {R"({"direction": ["nan", 0, 1], "illuminance_lx": 1e5})",
         {"'sun.direction'", "expected 3 numbers"}},
        {R"({"direction": [0, 1], "illuminance_lx": 1e5})",
         {"'sun.direction'", "expected 3 numbers"}},
        {R"({"illuminance_lx": 1e5})", {"'sun.direction'", "missing required key"}},
        {R"({"direction": [0, 0, 1], "illuminance_lx": -5})",
         {"'sun.illuminance_lx'", ">= 0", "got -5"}},
        {R"({"direction": [0, 0, 1], "irradiance_w_m2": [1, -1, 1]})",
         {"'sun.irradiance_w_m2'", ">= 0"}},
        {R"({"direction": [0, 0, 1], "irradiance_w_m2": "bright"})",
         {"'sun.irradiance_w_m2'", "expected 3 numbers (or one number)"}},
        {R"({"direction": [0, 0, 1]})", {"'sun'", "exactly one of 'illuminance_lx'"}},
        {R"({"direction": [0, 0, 1], "illuminance_lx": 1, "irradiance_w_m2": 1})",
         {"'sun'", "exactly one of 'illuminance_lx'"}},
        {R"({"direction": [0, 0, 1], "irradiance_w_m2": 1, "color": [1, 1, 0]})",
         {"'sun.color'", "only used with 'illuminance_lx'"}},
        {R"({"direction": [0, 0, 1], "illuminance_lx": 1, "color": [0, 0, 0]})",
         {"'sun.color'", "non-zero luminance"}},
        {R"({"direction": [0, 0, 1], "illuminance_lx": 1, "angular_diameter_deg": -1})",
         {"'sun.angular_diameter_deg'", "[0, 10]", "got -1"}},
        {R"({"direction": [0, 0, 1], "illuminance_lx": 1, "angular_diameter_deg": 45})",
         {"'sun.angular_diameter_deg'", "got 45"}},
        {R"({"direction": [0, 0, 1], "illuminance_lx": 1, "elevation_deg": 30})",
         {"'sun.elevation_deg'", "unknown key 'elevation_deg'", "angular_diameter_deg"}},
        {R"([0, 0, 1])", {"'sun'", "expected an object"}},
    };
    int i = 0;
    for (const Case& c : cases) {
        const std::string name = "sun" + std::to_string(i++) + ".json";
        write_file(dir, name, lamp_scene(std::string(",\n  \"sun\": ") + c.sun));
        expect_one_line_error(dir + "/" + name, c.parts, name);
    }
}

TEST(SceneIo, ValidateChecksSunsBuiltInCode) {
    Scene scene;
    scene.file = "code";
    scene.sun = Sun{{0, -2, 2}, Rgb(500.0f), 0.533};
    scene.polygons.push_back({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 0, "floor", "code:0"});
    scene.materials.push_back(Material{});
    Scene ok = scene;
    validate_scene(ok);                                      // the sun is the emitter
    EXPECT_NEAR(ok.sun->direction.z, std::sqrt(0.5), 1e-15); // normalised in place
    Scene nan = scene;
    nan.sun->direction.x = std::nan("");
    expect_input_error([&] { validate_scene(nan); }, {"'sun.direction'", "finite, non-zero"});
    Scene zero = scene;
    zero.sun->direction = {};
    expect_input_error([&] { validate_scene(zero); }, {"'sun.direction'"});
    Scene negative = scene;
    negative.sun->irradiance.g = -1;
    expect_input_error([&] { validate_scene(negative); }, {"'sun'", "irradiance", ">= 0"});
    Scene wide = scene;
    wide.sun->angular_diameter_deg = 20;
    expect_input_error([&] { validate_scene(wide); }, {"'sun.angular_diameter_deg'", "got 20"});
    Scene dark = scene;
    dark.sun->irradiance = Rgb{};
    expect_input_error([&] { validate_scene(dark); }, {"scene has no emitter", "'sun'"});
}

TEST(SceneIo, SensorsInlineAndFromPtsFile) {
    const std::string dir = test::temp_dir("scene-sensors");
    write_file(dir, "scene.json", lamp_scene(R"json(,
  "sensors": [{"name": "desk", "position": [1, 2, 0.85], "normal": [0, 0, 2]},
              [3, 4, 0.85, 0, 3, 4]])json"));
    Scene scene = load_scene(dir + "/scene.json");
    ASSERT_EQ(scene.sensors.size(), 2u);
    EXPECT_EQ(scene.sensors[0].name, "desk");
    EXPECT_EQ(scene.sensors[0].normal, Vec3(0, 0, 1));
    EXPECT_EQ(scene.sensors[1].position, Vec3(3, 4, 0.85));
    EXPECT_NEAR(scene.sensors[1].normal.y, 0.6, 1e-12);
    EXPECT_NEAR(scene.sensors[1].normal.z, 0.8, 1e-12);

    write_file(dir, "grid.pts", "# workplane\n500 500 850 0 0 1\n\n1000 500 850 0 0 5  # east\n");
    write_file(dir, "pts.json",
               lamp_scene(R"json(, "units": "mm", "sensors": {"file": "grid.pts"})json"));
    scene = load_scene(dir + "/pts.json");
    ASSERT_EQ(scene.sensors.size(), 2u);
    EXPECT_NEAR(scene.sensors[1].position.x, 1.0, 1e-12);
    EXPECT_NEAR(scene.sensors[1].position.z, 0.85, 1e-12);
    EXPECT_EQ(scene.sensors[1].normal, Vec3(0, 0, 1));

    write_file(dir, "bad.pts", "0 0 0 0 0 1\n# fine\n1 2 3 0 0\n");
    write_file(dir, "bad.json", lamp_scene(R"json(, "sensors": {"file": "bad.pts"})json"));
    expect_input_error([&] { load_scene(dir + "/bad.json"); }, {"bad.pts:3", "expected 6 numbers"});
    write_file(dir, "zero.pts", "0 0 0 0 0 0\n");
    write_file(dir, "zero.json", lamp_scene(R"json(, "sensors": {"file": "zero.pts"})json"));
    expect_input_error([&] { load_scene(dir + "/zero.json"); }, {"zero.pts:1", "normal is zero"});
}

/// One triangle (0,0,0), (1,0,0), (0,1,0) facing +z, used by node "plain" and, under a parent
/// translated by +10 in x, by node "mirrored" scaled by (−2, 1, 1). \p buffer is the buffer
/// entry: an external .bin or the GLB chunk.
std::string triangle_gltf(const std::string& buffer) {
    return R"json({
  "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"name": "plain", "mesh": 0},
            {"name": "parent", "translation": [10, 0, 0], "children": [2]},
            {"name": "mirrored", "mesh": 0, "scale": [-2, 1, 1]}],
  "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
  "materials": [{"name": "glow", "emissiveFactor": [1, 0.5, 0.25],
                 "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.3, 0.4, 1],
                                          "metallicFactor": 0}}],
  "buffers": [)json" +
           buffer + R"json(],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}]
})json";
}

const float k_triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};

/// A binary glTF: 12-byte header, then a JSON chunk and a BIN chunk, each 4-byte aligned.
void write_glb(const std::string& path, std::string json) {
    json.resize((json.size() + 3) / 4 * 4, ' ');
    const auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<char*>(&v), 4); };
    const std::string bin(reinterpret_cast<const char*>(k_triangle), sizeof(k_triangle));
    const std::size_t total = 12 + 8 + json.size() + 8 + bin.size();
    std::ofstream(path, std::ios::binary)
        << u32(0x46546C67) << u32(2) << u32(std::uint32_t(total))     // "glTF", version 2
        << u32(std::uint32_t(json.size())) << u32(0x4E4F534A) << json // "JSON"
        << u32(std::uint32_t(bin.size())) << u32(0x004E4942) << bin;  // "BIN\0"
}

void expect_triangle_scene(const Scene& scene, const std::string& file) {
    ASSERT_EQ(scene.polygons.size(), 2u) << file;
    ASSERT_EQ(scene.materials.size(), 1u) << file; // assimp's extra default material is dropped
    EXPECT_EQ(scene.materials[0].name, "glow");
    EXPECT_NEAR(scene.materials[0].reflectance.g, 0.3f, 1e-6);
    EXPECT_EQ(scene.materials[0].emission, Rgb(1, 0.5f, 0.25f));
    const Polygon& plain = scene.polygons[0];
    const Polygon& mirrored = scene.polygons[1];
    EXPECT_EQ(plain.name, "plain");
    EXPECT_EQ(mirrored.name, "mirrored");
    EXPECT_EQ(mirrored.source, file + ":face 2");
    EXPECT_NEAR(area_m2(mirrored), 1.0, 1e-6); // scaled by 2 in x
    EXPECT_GT(newell_normal(plain).z, 0);
    EXPECT_GT(newell_normal(mirrored).z, 0); // the front side survives the mirror
    double min_x = 1e9;
    for (const Vec3& v : mirrored.vertices)
        min_x = std::min(min_x, v.x);
    EXPECT_NEAR(min_x, 8.0, 1e-9); // 10 − 2 · 1
}

TEST(SceneIo, GltfTransformsAndMirrors) {
    const std::string dir = test::temp_dir("scene-gltf");
    std::ofstream(dir + "/tri.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(k_triangle), sizeof(k_triangle));
    write_file(dir, "tri.gltf", triangle_gltf(R"json({"uri": "tri.bin", "byteLength": 36})json"));
    write_file(dir, "gltf.json", R"json({"geometry": ["tri.gltf"]})json");
    expect_triangle_scene(load_scene(dir + "/gltf.json"), "tri.gltf");

    write_glb(dir + "/tri.glb", triangle_gltf(R"json({"byteLength": 36})json"));
    write_file(dir, "glb.json", R"json({"geometry": "tri.glb"})json");
    expect_triangle_scene(load_scene(dir + "/glb.json"), "tri.glb");
}

TEST(SceneIo, MaterialOverridesAndIgnoredPrimitives) {
    const std::string dir = test::temp_dir("scene-override");
    write_file(dir, "a.mtl", "newmtl lamp\nKd 0.1 0.2 0.3\nKe 5 5 5\n");
    write_file(dir, "a.obj",
               "mtllib a.mtl\no quad\nusemtl lamp\nv 0 0 0\nv 1 0 0\nv 1 1 0\n"
               "v 0 1 0\nf 1 2 3 4\nl 1 2\np 3\n");
    write_file(dir, "b.obj", "o tri\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf 1 2 3\n");
    write_file(dir, "scene.json", R"json({"geometry": ["a.obj", "b.obj"],
  "materials": {"lamp": {"reflectance": 0.4},
                "DefaultMaterial": {"reflectance": [0.3, 0.3, 0.3]}}})json");
    const Scene scene = load_scene(dir + "/scene.json");
    ASSERT_EQ(scene.polygons.size(), 2u); // the line and the point are skipped
    EXPECT_EQ(scene.polygons[0].name, "quad");
    EXPECT_EQ(scene.polygons[1].name, "tri");
    EXPECT_EQ(scene.polygons[1].source, "b.obj:face 1");
    const Material& lamp = material_named(scene, "lamp");
    EXPECT_EQ(lamp.reflectance, Rgb(0.4f));
    EXPECT_EQ(lamp.emission, Rgb(5.0f)); // not given in the scene file: kept from the MTL
    EXPECT_EQ(material_named(scene, "DefaultMaterial").reflectance, Rgb(0.3f));
}

TEST(SceneIo, MissingFilesNameTheFile) {
    const std::string dir = test::temp_dir("scene-missing");
    expect_input_error([&] { load_scene(dir + "/nope.json"); }, {"nope.json", "not found"});
    write_file(dir, "scene.json", R"json({"geometry": "missing.obj"})json");
    expect_input_error([&] { load_scene(dir + "/scene.json"); },
                       {"missing.obj", "'geometry'", "not found"});
    write_file(dir, "broken.obj", "v 0 0 0\nf 1 2 3\n");
    write_file(dir, "broken.json", R"json({"geometry": "broken.obj"})json");
    expect_input_error([&] { load_scene(dir + "/broken.json"); },
                       {"broken.obj", "'geometry'", "vertex index out of range"});
}

// Issue #32: a sensor or a camera at 1e308 m gave NaN (or blamed camera.up), and a contact
// tolerance of 1e308 merged the emitter away: each is an error naming its key.
TEST(SceneIo, PositionsAndToleranceOutOfRangeAreErrors) {
    const std::string dir = test::temp_dir("scene-far");
    const std::string room = R"json("polygons": [{"material": "m",
      "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}],
  "materials": {"m": {"emission": 1}})json";
    const std::pair<const char*, const char*> cases[] = {
        {R"json("sensors": [[1e308, 0, 0, 0, 0, 1]])json", "'sensors[0].position'"},
        {R"json("camera": {"eye": [1e308, 0, 1], "look_at": [0, 0, 0]})json", "'camera.eye'"},
        {R"json("point_lights": [{"position": [0, -1e10, 1], "intensity_cd": 1}])json",
         "'point_lights[0].position'"},
        {R"json("mesher": {"contact_tolerance": 1e308})json", "'mesher.contact_tolerance'"},
    };
    for (const auto& [keys, key] : cases) {
        write_file(dir, "far.json", "{" + room + ",\n  " + keys + "}");
        expect_input_error([&] { load_scene(dir + "/far.json"); }, {"far.json", key});
    }
}

// Issue #32: an OBJ face of one triangle's indices repeated 10 000 times took a minute and
// 3.6 GB; a face that visits a point twice is an error naming file and face.
TEST(SceneIo, FaceVisitingAPointTwiceIsAnError) {
    const std::string dir = test::temp_dir("scene-repeat");
    std::string face = "f";
    for (int k = 0; k < 10000; ++k)
        face += " 1 2 3";
    write_file(dir, "loop.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n" + face + "\n");
    write_file(dir, "scene.json", R"json({"geometry": "loop.obj"})json");
    expect_input_error([&] { load_scene(dir + "/scene.json"); },
                       {"loop.obj:face 1", "vertex 4 repeats vertex 1"});
    // Neighbours that repeat (a doubled corner) are the mesher's to merge.
    write_file(dir, "double.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2 3\n");
    write_file(dir, "double.json", R"json({"geometry": "double.obj",
  "materials": {"DefaultMaterial": {"emission": 1}}})json");
    EXPECT_NO_THROW(load_scene(dir + "/double.json"));
}

// Issue #32: a missing mtllib gave default materials without a word, a folder was "not found",
// and a bad sensor line was quoted whole (10 MB).
TEST(SceneIo, MissingMaterialLibraryFolderAndLongLinesAreClearErrors) {
    const std::string dir = test::temp_dir("scene-missing-mtl");
    write_file(dir, "room.obj", "# a room\nmtllib room.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    write_file(dir, "scene.json", R"json({"geometry": "room.obj"})json");
    expect_input_error([&] { load_scene(dir + "/scene.json"); },
                       {"room.obj:2", "material library 'room.mtl' not found"});
    std::filesystem::create_directories(dir + "/folder.obj");
    write_file(dir, "folder.json", R"json({"geometry": "folder.obj"})json");
    expect_input_error([&] { load_scene(dir + "/folder.json"); },
                       {"folder.obj", "'geometry'", "is a folder"});
    write_file(dir, "long.pts", "1 2 3 " + std::string(100000, 'x') + "\n");
    write_file(dir, "long.json",
               R"json({"polygons": [{"material": "m", "vertices": [[0,0,0],[1,0,0],[0,1,0]]}],
  "materials": {"m": {"emission": 1}},
  "sensors": {"file": "long.pts"}})json");
    try {
        load_scene(dir + "/long.json");
        ADD_FAILURE() << "no InputError thrown";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("long.pts:1"), std::string::npos) << e.what();
        EXPECT_LT(std::string(e.what()).size(), 300u);
    }
}

// Issue #32: a garbage .gltf was reported as "OBJ: Invalid face index" (assimp tried every
// reader by content when the glTF readers refused it); it is a glTF error now, with the glTF
// reader's reason.
TEST(SceneIo, BrokenGltfIsAGltfError) {
    const std::string dir = test::temp_dir("scene-broken-gltf");
    const std::pair<const char*, const char*> files[] = {{"bad.gltf", ".gltf"},
                                                         {"bad.GLB", ".glb"}};
    for (const auto& [name, extension] : files) {
        write_file(dir, name, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n"); // OBJ's text
        write_file(dir, "scene.json", fmt::format(R"json({{"geometry": "{}"}})json", name));
        try {
            load_scene(dir + "/scene.json");
            ADD_FAILURE() << "no InputError thrown";
        } catch (const InputError& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find(name), std::string::npos) << message;
            EXPECT_NE(message.find("'geometry'"), std::string::npos) << message;
            EXPECT_NE(message.find(std::string("not a readable ") + extension + " file"),
                      std::string::npos)
                << message;
            EXPECT_NE(message.find("GLTF"), std::string::npos) << message;
            EXPECT_EQ(message.find("OBJ"), std::string::npos) << message;
        }
    }
    write_file(dir, "broken.gltf", R"json({"asset": {"version": "2.0"}, "meshes": [{]})json");
    write_file(dir, "broken.json", R"json({"geometry": "broken.gltf"})json");
    expect_input_error([&] { load_scene(dir + "/broken.json"); },
                       {"broken.gltf", "not a readable .gltf file", "JSON parse error, offset 42"});
}

TEST(SceneIo, MalformedJsonNamesTheLine) {
    const std::string dir = test::temp_dir("scene-malformed");
    write_file(dir, "scene.json", "{\n  \"name\": \"x\",\n  \"units\": mm\n}\n");
    try {
        load_scene(dir + "/scene.json");
        ADD_FAILURE() << "no InputError thrown";
    } catch (const InputError& e) {
        EXPECT_EQ(e.line(), 3);
        EXPECT_NE(std::string(e.what()).find("scene.json:3"), std::string::npos) << e.what();
    }
    write_file(dir, "twice.json", lamp_scene(R"json(, "units": "m", "units": "mm")json"));
    expect_input_error([&] { load_scene(dir + "/twice.json"); }, {"twice.json", "'units'"});
}

TEST(SceneIo, UnknownKeysAreErrors) {
    const std::string dir = test::temp_dir("scene-unknown");
    write_file(dir, "top.json", lamp_scene(R"json(, "exposure": 1)json"));
    expect_input_error([&] { load_scene(dir + "/top.json"); },
                       {"top.json", "'exposure'", "unknown key", "known: name, units"});
    write_file(dir, "nested.json", R"json({
  "polygons": [{"material": "light", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]}],
  "materials": {"light": {"emision": [1, 1, 1]}}
})json");
    expect_input_error(
        [&] { load_scene(dir + "/nested.json"); },
        {"nested.json", "'materials.light.emision'", "unknown key 'emision'", "emission_flux_lm"});
}

TEST(SceneIo, WrongTypesNameTheKey) {
    const std::string dir = test::temp_dir("scene-types");
    write_file(dir, "a.json", R"json({
  "polygons": [{"material": "lamp", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]}],
  "materials": {"lamp": {"emission": 1}, "white": {"reflectance": "white"}}
})json");
    expect_input_error(
        [&] { load_scene(dir + "/a.json"); },
        {"a.json", "'materials.white.reflectance'", "expected 3 numbers", "got string"});
    write_file(dir, "b.json", lamp_scene(R"json(, "image": {"width": 256})json"));
    expect_input_error([&] { load_scene(dir + "/b.json"); }, {"'image'", "needs a 'camera'"});
    write_file(dir, "c.json", lamp_scene(R"json(, "solver": {"visibility_rays": 2.5})json"));
    expect_input_error([&] { load_scene(dir + "/c.json"); },
                       {"'solver.visibility_rays'", "expected an integer"});
    write_file(dir, "d.json", lamp_scene(R"json(, "units": "yards")json"));
    expect_input_error([&] { load_scene(dir + "/d.json"); }, {"'units'", "unknown unit 'yards'"});
    write_file(dir, "e.json", lamp_scene(R"json(, "solver": {"residual": 2})json"));
    expect_input_error([&] { load_scene(dir + "/e.json"); }, {"'solver.residual'", "[1e-12, 0.5]"});
}

TEST(SceneIo, BadGeometryIsReported) {
    const std::string dir = test::temp_dir("scene-bad-geometry");
    write_file(dir, "nan.obj", "o wall\nv 0 0 0\nv 1 0 0\nv nan 0 0\nf 1 2 3\n");
    write_file(dir, "nan.json", lamp_scene(R"json(, "geometry": "nan.obj")json"));
    expect_input_error(
        [&] { load_scene(dir + "/nan.json"); },
        {"nan.json", "polygon 'wall'", "nan.obj:face 1", "vertex 3 must be finite", "(nan, 0, 0)"});
    write_file(dir, "flat.json", R"json({
  "polygons": [{"name": "sliver", "material": "lamp",
                "vertices": [[0, 0, 0], [1, 1, 1], [2, 2, 2]]}],
  "materials": {"lamp": {"emission": 1}}
})json");
    expect_input_error([&] { load_scene(dir + "/flat.json"); },
                       {"flat.json", "'polygons[0]'", "polygon 'sliver'", "zero-area face"});
    write_file(dir, "nomat.json", R"json({
  "polygons": [{"material": "glass", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]}]
})json");
    expect_input_error([&] { load_scene(dir + "/nomat.json"); },
                       {"'polygons[0].material'", "unknown material 'glass'"});
}

TEST(SceneIo, SceneWithoutEmitterIsAnError) {
    const std::string dir = test::temp_dir("scene-dark");
    write_file(dir, "dark.json", R"json({
  "polygons": [{"material": "grey", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]}],
  "materials": {"grey": {"reflectance": 0.5}}
})json");
    expect_input_error([&] { load_scene(dir + "/dark.json"); },
                       {"dark.json", "scene has no emitter", "point_lights"});
}

// ---- PointLight::profile and PointLight::power (core/scene.h): the closed-form power of a
// spot against its profile integrated numerically over the sphere ----

PointLight spot(const Vec3& direction, double beam_deg, double cutoff_deg) {
    PointLight light;
    light.intensity = Rgb(2.0f, 1.0f, 0.5f);
    light.spot = SpotCone{normalize(direction), beam_deg, cutoff_deg};
    return light;
}

// ∫ profile dω over the sphere, sr, in a frame around the spot's axis: 8-point Gauss–Legendre
// panels in u = cos θ (split at the beam and cut-off, where the profile has kinks) times 16
// azimuths. The profile is called with full 3D directions, so a wrong axis or an asymmetric
// profile shows.
double integrate_profile(const PointLight& light) {
    constexpr std::array<double, 8> x = {
        -0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
        0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
    constexpr std::array<double, 8> w = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                         0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                         0.2223810344533745, 0.1012285362903763};
    const Vec3 axis = light.spot ? light.spot->direction : Vec3(0, 0, 1);
    std::vector<double> breaks = {-1.0, 1.0};
    if (light.spot) {
        breaks.push_back(std::cos(light.spot->cutoff_deg * k_pi / 180.0));
        breaks.push_back(std::cos(light.spot->beam_deg * k_pi / 180.0));
    }
    std::sort(breaks.begin(), breaks.end());
    const Frame frame = Frame::from_normal(axis);
    const int panels = 200, azimuths = 16;
    double sum = 0;
    for (std::size_t b = 0; b + 1 < breaks.size(); ++b) {
        const double h = (breaks[b + 1] - breaks[b]) / panels;
        for (int p = 0; p < panels; ++p) {
            const double mid = breaks[b] + (p + 0.5) * h;
            for (std::size_t k = 0; k < x.size(); ++k) {
                const double u = std::clamp(mid + 0.5 * h * x[k], -1.0, 1.0);
                const double r = std::sqrt(std::max(0.0, 1.0 - u * u));
                double ring = 0;
                for (int a = 0; a < azimuths; ++a) {
                    const double phi = 2.0 * k_pi * (a + 0.25) / azimuths;
                    ring += light.profile(
                        frame.to_world(Vec3(r * std::cos(phi), r * std::sin(phi), u)));
                }
                sum += 0.5 * h * w[k] * ring * (2.0 * k_pi / azimuths);
            }
        }
    }
    return sum;
}

TEST(SpotLight, IsotropicProfileIsOneAndPowerIsFourPiI) {
    PointLight light;
    light.intensity = Rgb(1.0f, 2.0f, 3.0f);
    EXPECT_EQ(light.profile(normalize(Vec3(0.3, -0.2, 0.9))), 1.0);
    EXPECT_DOUBLE_EQ(light.power().g, 2.0 * 4.0 * k_pi);
    EXPECT_NEAR(integrate_profile(light), 4.0 * k_pi, 1e-9);
}

TEST(SpotLight, ProfileIsOneInTheBeamZeroBeyondTheCutoffAndSmoothBetween) {
    const PointLight light = spot({0.3, -0.5, 0.8}, 20, 35);
    const Vec3 axis = light.spot->direction;
    const Frame f = Frame::from_normal(axis);
    auto at_deg = [&](double theta_deg) {
        const double t = theta_deg * k_pi / 180.0;
        return light.profile(f.to_world(Vec3(std::sin(t), 0, std::cos(t))));
    };
    EXPECT_EQ(at_deg(0), 1.0);
    EXPECT_EQ(at_deg(19.9), 1.0);
    EXPECT_EQ(at_deg(35.1), 0.0);
    EXPECT_EQ(at_deg(120), 0.0);
    // Smoothstep in cos θ, written out here independently of scene.cpp.
    const double cb = std::cos(20 * k_pi / 180), cc = std::cos(35 * k_pi / 180);
    for (double theta : {21.0, 27.5, 34.0}) {
        const double s = (std::cos(theta * k_pi / 180) - cc) / (cb - cc);
        EXPECT_NEAR(at_deg(theta), s * s * (3 - 2 * s), 1e-12) << theta;
    }
    // Decreasing from the beam to the cut-off.
    double previous = 1;
    for (double theta = 20; theta <= 35; theta += 0.5) {
        EXPECT_LE(at_deg(theta), previous) << theta;
        previous = at_deg(theta);
    }
}

class SpotPower : public ::testing::TestWithParam<std::array<double, 2>> {};

TEST_P(SpotPower, NumericallyIntegratedProfileEqualsPower) {
    const auto [beam, cutoff] = GetParam();
    const PointLight light = spot({-0.4, 0.1, -0.9}, beam, cutoff);
    const double numeric = integrate_profile(light);
    const RgbD power = light.power();
    const double relative = std::abs(numeric * light.intensity.r - power.r) / power.r;
    std::printf("spot beam %g cutoff %g: integral %.12f sr, power()/I %.12f sr, rel. %.2e\n", beam,
                cutoff, numeric, power.r / light.intensity.r, relative);
    EXPECT_LT(relative, 1e-6);
    EXPECT_NEAR(power.b / power.r, 0.25, 1e-7); // the colour is the intensity's
}

INSTANTIATE_TEST_SUITE_P(
    Cones, SpotPower,
    ::testing::Values(std::array<double, 2>{20, 35}, std::array<double, 2>{0, 90},
                      std::array<double, 2>{45, 45}, std::array<double, 2>{60, 150},
                      std::array<double, 2>{0, 180}, std::array<double, 2>{1, 2}));

TEST(SceneIo, ThinLensCameraKeys) {
    const std::string dir = test::temp_dir("scene-lens");
    const auto camera = [](const std::string& lens) {
        return lamp_scene(R"json(,
  "units": "mm",
  "camera": {"eye": [0, 0, 0], "look_at": [0, 0, 1000], "up": [0, 1, 0])json" +
                          lens + "}");
    };
    write_file(dir, "lens.json",
               camera(R"json(, "aperture_radius": 20, "focus_distance": 1500)json"));
    const Scene scene = load_scene(dir + "/lens.json");
    EXPECT_NEAR(scene.camera->aperture_radius_m, 0.02, 1e-12);
    EXPECT_NEAR(scene.camera->focus_distance_m.value_or(0), 1.5, 1e-12);
    write_file(dir, "pinhole.json", camera(""));
    EXPECT_EQ(load_scene(dir + "/pinhole.json").camera->aperture_radius_m, 0.0);
    EXPECT_FALSE(load_scene(dir + "/pinhole.json").camera->focus_distance_m);
    write_file(dir, "negative.json", camera(R"json(, "aperture_radius": -1)json"));
    expect_input_error([&] { load_scene(dir + "/negative.json"); },
                       {"negative.json", "camera.aperture_radius", ">= 0"});
    write_file(dir, "zero.json", camera(R"json(, "focus_distance": 0)json"));
    expect_input_error([&] { load_scene(dir + "/zero.json"); },
                       {"zero.json", "camera.focus_distance", "> 0"});
}

} // namespace
} // namespace penumbra
