// The Radiance importer (issue #30): each supported primitive into the Scene's data, !xform,
// and errors that name file and line. Expected values follow from Radiance's reference manual
// (plastic's diffuse part colour × (1 − spec), glass's default index 1.52, a source's
// solid angle 2π(1 − cos(angle/2))) and from closed-form geometry.

#include <cmath>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <string>
#include <variant>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/scene_io.h"

#include "common/test_util.h"

namespace penumbra {
namespace {

constexpr double k_pi = 3.14159265358979323846;

/// A folder holding \p rad_files (name, text) and a scene.json whose `geometry` lists them in
/// order, plus \p extra top-level keys; returns the scene file's path.
std::string write_scene(const std::vector<std::pair<std::string, std::string>>& rad_files,
                        const std::string& extra = "") {
    const std::string dir = test::temp_dir("radiance");
    std::string list;
    for (const auto& [name, text] : rad_files) {
        std::ofstream(dir + "/" + name, std::ios::binary) << text;
        list += (list.empty() ? "\"" : ", \"") + name + "\"";
    }
    const std::string path = dir + "/scene.json";
    std::ofstream(path) << "{\"geometry\": [" << list << "]" << extra << "}\n";
    return path;
}

/// A light square (so the scene has an emitter) and its material.
const std::string k_lamp = R"(void light lamp_mat
0
0
3 10 10 10

lamp_mat polygon lamp
0
0
12 0 0 3  1 0 3  1 1 3  0 1 3
)";

Scene load_rad(const std::string& text, const std::string& extra = "") {
    return load_scene(write_scene({{"test.rad", k_lamp + text}}, extra));
}

const Material& material_named(const Scene& scene, const std::string& name) {
    for (const Material& m : scene.materials)
        if (m.name == name)
            return m;
    throw std::runtime_error("no material " + name);
}

const Polygon& polygon_named(const Scene& scene, const std::string& name) {
    for (const Polygon& p : scene.polygons)
        if (p.name == name)
            return p;
    throw std::runtime_error("no polygon " + name);
}

void expect_rgb(const Rgb& got, const Rgb& want, double tolerance) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], want[c], tolerance) << "channel " << c;
}

void expect_vec(const Vec3& got, const Vec3& want, double tolerance) {
    for (std::size_t c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], want[c], tolerance) << "axis " << c;
}

/// Loading \p scene_path throws one InputError line holding every one of \p parts.
void expect_error(const std::string& scene_path, std::initializer_list<std::string> parts) {
    test::expect_one_line_input_error([&] { load_scene(scene_path); }, parts, scene_path);
}

/// Lines of k_lamp.
constexpr int k_lamp_lines = 9;

/// The .rad file \p text (after the lamp) fails at its line \p line.
void expect_rad_error(const std::string& text, int line, std::initializer_list<std::string> parts) {
    const std::string path = write_scene({{"test.rad", k_lamp + text}});
    SCOPED_TRACE(text);
    std::vector<std::string> all(parts);
    all.push_back(fmt::format("test.rad:{}:", line + k_lamp_lines));
    EXPECT_EQ(test::expect_one_line_input_error([&] { load_scene(path); }, all, path),
              line + k_lamp_lines);
}

const std::string k_square = "0\n0\n12 0 0 0  1 0 0  1 1 0  0 1 0\n";

TEST(Radiance, PlasticIsLambertianWithColourTimesOneMinusSpec) {
    const Scene scene = load_rad("# a comment\nvoid plastic grey\n0\n0\n5 0.5 0.4 0.3 0.1 0.05\n"
                                 "grey polygon floor\n" +
                                 k_square);
    const Material& grey = material_named(scene, "grey");
    expect_rgb(grey.reflectance, Rgb(0.45f, 0.36f, 0.27f), 1e-6);
    EXPECT_TRUE(grey.emission.is_black());
    EXPECT_FALSE(grey.lobe.has_value());
    const Polygon& floor = polygon_named(scene, "floor");
    ASSERT_EQ(floor.vertices.size(), 4u);
    expect_vec(floor.vertices[2], Vec3(1, 1, 0), 0);
    EXPECT_NE(floor.source.find("test.rad:15"), std::string::npos) << floor.source;
}

TEST(Radiance, MetalKeepsItsDiffusePart) {
    const Scene scene =
        load_rad("void metal alu\n0\n0\n5 0.8 0.8 0.6 0.25 0\nalu polygon sheet\n" + k_square);
    expect_rgb(material_named(scene, "alu").reflectance, Rgb(0.6f, 0.6f, 0.45f), 1e-6);
}

TEST(Radiance, GlassIsThinGlassWithDefaultIndex152) {
    const Scene scene = load_rad("void glass clear\n0\n0\n3 0.762842 0.762842 0.762842\n"
                                 "void glass dense\n0\n0\n4 0.9 0.8 0.7 1.6\n"
                                 "clear polygon pane\n" +
                                 k_square + "dense polygon pane2\n" + k_square);
    const Material& clear = material_named(scene, "clear");
    EXPECT_TRUE(clear.reflectance.is_black());
    ASSERT_TRUE(clear.lobe && std::holds_alternative<ThinGlass>(*clear.lobe));
    const ThinGlass& pane = std::get<ThinGlass>(*clear.lobe);
    EXPECT_DOUBLE_EQ(pane.ior, 1.52);
    expect_rgb(pane.transmissivity, Rgb(0.762842f), 1e-7);
    // Radiance's own figure for this glass (shared/scenes/README.md): 0.700 at normal incidence.
    EXPECT_NEAR(pane.transmittance(1.0).g, 0.700, 5e-4);
    const ThinGlass& dense = std::get<ThinGlass>(*material_named(scene, "dense").lobe);
    EXPECT_DOUBLE_EQ(dense.ior, 1.6);
    expect_rgb(dense.transmissivity, Rgb(0.9f, 0.8f, 0.7f), 1e-7);
}

TEST(Radiance, LightGlowAndIllumEmitTheirRadiance) {
    const Scene scene = load_rad("void glow g\n0\n0\n4 1 2 3 0\n"
                                 "void illum i\n1 alternate\n0\n3 4 5 6\n"
                                 "g polygon a\n" +
                                 k_square + "i polygon b\n" + k_square);
    const Material& lamp = material_named(scene, "lamp_mat");
    EXPECT_EQ(lamp.emission, Rgb(10, 10, 10));
    EXPECT_TRUE(lamp.reflectance.is_black());
    EXPECT_EQ(material_named(scene, "g").emission, Rgb(1, 2, 3));
    EXPECT_EQ(material_named(scene, "i").emission, Rgb(4, 5, 6));
}

// trans "r g b spec rough trans tspec": of the light not reflected specularly, trans passes
// (Radiance's reference manual); its diffuse parts are ρ = c (1 − spec)(1 − trans) and
// τ = c (1 − spec) trans (1 − tspec).
TEST(Radiance, TransGivesDiffuseReflectanceAndTransmittance) {
    const Scene scene = load_rad("void trans blind\n0\n0\n7 0.5 0.6 0.7 0.1 0 0.4 0.25\n"
                                 "blind polygon slat\n" +
                                 k_square);
    const Material& m = material_named(scene, "blind");
    const Rgb c(0.5f, 0.6f, 0.7f);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(m.reflectance[i], c[i] * 0.9 * 0.6, 1e-6) << i;
        EXPECT_NEAR(m.diffuse_transmittance[i], c[i] * 0.9 * 0.4 * 0.75, 1e-6) << i;
    }
    EXPECT_TRUE(m.two_sided);
}

TEST(Radiance, UnitsScaleVerticesAndUnusedMaterialsAreLeftOut) {
    const Scene scene =
        load_rad("void plastic unused\n0\n0\n5 .5 .5 .5 0 0\n", ", \"units\": \"cm\"");
    expect_vec(polygon_named(scene, "lamp").vertices[2], Vec3(0.01, 0.01, 0.03), 1e-15);
    EXPECT_EQ(scene.materials.size(), 1u);
}

TEST(Radiance, SourceOfLightIsTheSun) {
    const Scene scene = load_rad("void light solar\n0\n0\n3 6.534e6 6.534e6 6.534e6\n"
                                 "solar source sun\n0\n0\n4 0 -0.792329 0.610094 0.5\n");
    ASSERT_TRUE(scene.sun.has_value());
    // Normal irradiance = radiance × the disc's solid angle 2π(1 − cos 0.25°).
    const double irradiance = 6.534e6 * 2 * k_pi * (1 - std::cos(0.25 * k_pi / 180));
    EXPECT_NEAR(scene.sun->irradiance.g, irradiance, 1e-6 * irradiance);
    EXPECT_NEAR(irradiance, 390.8, 0.1);
    expect_vec(scene.sun->direction, normalize(Vec3(0, -0.792329, 0.610094)), 1e-12);
    EXPECT_DOUBLE_EQ(scene.sun->angular_diameter_deg, 0.5);
    EXPECT_FALSE(scene.sky.has_value());
}

TEST(Radiance, ConstantGlowHemispheresAreAUniformSkyAndGround) {
    const Scene scene = load_rad("void glow sky_glow\n0\n0\n4 2 2 2 0\n"
                                 "sky_glow source sky\n0\n0\n4 0 0 1 180\n"
                                 "void glow ground_glow\n0\n0\n4 .5 .5 .5 0\n"
                                 "ground_glow source ground\n0\n0\n4 0 0 -1 180\n");
    ASSERT_TRUE(scene.sky.has_value());
    EXPECT_TRUE(std::holds_alternative<UniformSky>(scene.sky->model));
    EXPECT_NEAR(scene.sky->zenith_radiance, 2.0, 1e-6);
    EXPECT_NEAR(scene.sky->ground_radiance.value_or(-1), 0.5, 1e-6);
    EXPECT_EQ(scene.sky->horizon, Horizon::sharp);
    expect_rgb(scene.sky->colour, Rgb(1.0f), 1e-6);
}

TEST(Radiance, SkybrightFunctionsGiveTheirSkyModels) {
    const std::string glows = "skyfunc glow sky_glow\n0\n0\n4 1 1 1 0\n"
                              "sky_glow source sky\n0\n0\n4 0 0 1 180\n"
                              "skyfunc glow ground_glow\n0\n0\n4 1 1 1 0\n"
                              "ground_glow source ground\n0\n0\n4 0 0 -1 180\n";
    const Scene overcast = load_rad(
        "void brightfunc skyfunc\n2 skybr skybright.cal\n0\n3 2 2.286e+01 3.557e+00\n" + glows);
    ASSERT_TRUE(overcast.sky.has_value());
    EXPECT_TRUE(std::holds_alternative<CieOvercastSky>(overcast.sky->model));
    EXPECT_DOUBLE_EQ(overcast.sky->zenith_radiance, 22.86);
    EXPECT_DOUBLE_EQ(overcast.sky->ground_radiance.value_or(-1), 3.557);
    EXPECT_EQ(overcast.sky->horizon, Horizon::radiance_blend);

    const Scene uniform =
        load_rad("void brightfunc skyfunc\n2 skybr skybright.cal\n0\n3 3 10 2\n" + glows);
    EXPECT_TRUE(std::holds_alternative<UniformSky>(uniform.sky->model));

    const Scene clear = load_rad("void brightfunc skyfunc\n2 skybr skybright.cal\n0\n"
                                 "7 1 7.794e+00 1.803e+01 4.715e-01 0.000000 -0.792329 0.610094\n" +
                                 glows);
    ASSERT_TRUE(std::holds_alternative<CieGeneralSky>(clear.sky->model));
    EXPECT_EQ(std::get<CieGeneralSky>(clear.sky->model).type, 12);
    // skybright.cal divides by 0.274 where ISO 15469's φ(0) is 1 − e^−0.32 = 0.27385: its
    // zenith is A2 × 0.99945; A4 = 0.4715 is printed to 4 digits (±1e-4 relative).
    EXPECT_NEAR(clear.sky->zenith_radiance, 7.794 * 0.99945, 7.794 * 2e-4);
    EXPECT_DOUBLE_EQ(clear.sky->ground_radiance.value_or(-1), 18.03);
    expect_vec(clear.sky->sun_direction, normalize(Vec3(0, -0.792329, 0.610094)), 1e-12);
}

TEST(Radiance, XformMovesRotatesScalesAndMirrors) {
    const std::string dir = test::temp_dir("radiance-xform");
    std::ofstream(dir + "/part.rad") << "void plastic grey\n0\n0\n5 .5 .5 .5 0 0\n"
                                        "grey polygon tile\n" +
                                            k_square;
    std::ofstream(dir + "/test.rad") << k_lamp << "!xform -s 2 -rz 90 -t 10 0 0 part.rad\n"
                                     << "!xform -mx part.rad\n"
                                     << "!xform -a 3 -t 0 0 1 part.rad\n"
                                     << "!xform -I \\\n -t 0 0 -1 part.rad\n";
    std::ofstream(dir + "/scene.json") << R"({"geometry": ["test.rad"]})";
    const Scene scene = load_scene(dir + "/scene.json");
    ASSERT_EQ(scene.polygons.size(), 1u + 1 + 1 + 3 + 1);
    // Scaled by 2, turned 90° counter-clockwise about z, then moved 10 along x:
    // (1, 1, 0) → (2, 2, 0) → (−2, 2, 0) → (8, 2, 0).
    expect_vec(scene.polygons[1].vertices[2], Vec3(8, 2, 0), 1e-12);
    // Mirrored in x: the vertex order is reversed so that the front stays up (+z).
    const Polygon& mirrored = scene.polygons[2];
    expect_vec(mirrored.vertices[0], Vec3(0, 1, 0), 1e-12);
    expect_vec(mirrored.vertices[1], Vec3(-1, 1, 0), 1e-12);
    const Vec3 n = cross(mirrored.vertices[1] - mirrored.vertices[0],
                         mirrored.vertices[2] - mirrored.vertices[0]);
    EXPECT_GT(n.z, 0);
    for (int k = 0; k < 3; ++k) // an array of 3: copies 0, 1 and 2 steps up
        EXPECT_DOUBLE_EQ(scene.polygons[3 + std::size_t(k)].vertices[0].z, double(k));
    // -I turns the tile over: reversed order, front down; the continued line was read.
    const Polygon& inverted = scene.polygons[6];
    expect_vec(inverted.vertices[0], Vec3(0, 1, -1), 1e-12);
    EXPECT_EQ(scene.materials.size(), 2u); // the re-read definition of grey is the same one
}

TEST(Radiance, XformRotatesTheSunAndTheSky) {
    const std::string dir = test::temp_dir("radiance-xform-sky");
    std::ofstream(dir + "/sky.rad") << "void light solar\n0\n0\n3 1e6 1e6 1e6\n"
                                       "solar source sun\n0\n0\n4 0 -1 1 0.5\n"
                                       "void brightfunc skyfunc\n2 skybr skybright.cal\n0\n"
                                       "3 2 10 2\nskyfunc glow sky_glow\n0\n0\n4 1 1 1 0\n"
                                       "sky_glow source sky\n0\n0\n4 0 0 1 180\n";
    std::ofstream(dir + "/test.rad") << k_lamp << "!xform -rx -90 sky.rad\n";
    std::ofstream(dir + "/scene.json") << R"({"geometry": ["test.rad"]})";
    const Scene scene = load_scene(dir + "/scene.json");
    // −90° about x takes z to y and y to −z: the scene is y-up, north toward −z.
    ASSERT_TRUE(scene.sun && scene.sky);
    expect_vec(scene.sun->direction, normalize(Vec3(0, 1, 1)), 1e-12);
    expect_vec(scene.sky->compass.up, Vec3(0, 1, 0), 1e-12);
    expect_vec(scene.sky->compass.north, Vec3(0, 0, -1), 1e-12);
}

TEST(Radiance, ModifiersCarryOverToLaterFilesInGeometryOrder) {
    const std::string materials = "void plastic wall\n0\n0\n5 .5 .5 .5 0 0\n";
    const std::string walls = "wall polygon w\n" + k_square;
    const Scene scene =
        load_scene(write_scene({{"lamp.rad", k_lamp}, {"m.rad", materials}, {"w.rad", walls}}));
    EXPECT_EQ(scene.materials[polygon_named(scene, "w").material].name, "wall");
    expect_error(write_scene({{"lamp.rad", k_lamp}, {"w.rad", walls}, {"m.rad", materials}}),
                 {"w.rad:1:", "unknown modifier 'wall'"});
}

TEST(Radiance, ErrorsInIncludedFilesNameThatFile) {
    const std::string dir = test::temp_dir("radiance-nested");
    std::ofstream(dir + "/inner.rad") << "\n\nvoid cone c\n0\n0\n8 0 0 0 0 0 1 1 0\n";
    std::ofstream(dir + "/test.rad") << k_lamp << "!xform -t 1 0 0 inner.rad\n";
    std::ofstream(dir + "/scene.json") << R"({"geometry": ["test.rad"]})";
    expect_error(dir + "/scene.json", {"inner.rad:3:", "'c'", "'cone'"});
}

TEST(Radiance, SunGivenTwiceIsAnError) {
    const std::string sun = "void light solar\n0\n0\n3 1e6 1e6 1e6\n"
                            "solar source sun\n0\n0\n4 0 -1 1 0.5\n";
    expect_error(write_scene({{"test.rad", k_lamp + sun}},
                             R"(, "sun": {"direction": [0, 0, 1], "illuminance_lx": 1000})"),
                 {"'sun'", "given twice", "test.rad:14"});
}

TEST(Radiance, ErrorsNameFileAndLine) {
    expect_rad_error("void sphere ball\n0\n0\n4 0 0 0 1\n", 1,
                     {"'ball'", "'sphere'", "not supported"});
    expect_rad_error("\nvoid plastic p\n0\n0\n4 .5 .5 .5 0\n", 2,
                     {"plastic 'p'", "5 real", "got 0, 0 and 4"});
    expect_rad_error("nothing polygon x\n" + k_square, 1, {"unknown modifier 'nothing'"});
    expect_rad_error("void polygon x\n" + k_square, 1, {"polygon 'x'", "void"});
    expect_rad_error("void plastic p\n0\n0\n5 .5 .5 .5 0 0\np polygon x\n0\n0\n6 0 0 0 1 0 0\n", 5,
                     {"polygon 'x'", "3 × n ≥ 9"});
    // A bad word is reported at its own line, an early end at the primitive's.
    expect_rad_error("void plastic p\n0\n0\n5 .5 .5 .5 0 zero\n", 4,
                     {"real argument 5", "'p'", "'zero'"});
    expect_rad_error("void plastic p\n0\n0\n5 .5 .5\n", 1,
                     {"the file ends", "real argument 3", "'p'"});
    expect_rad_error("void plastic p\n0\n0\n5 1.5 .5 .5 0 0\n", 1, {"plastic 'p'", "[0, 1)"});
    expect_rad_error("\n!genbox grey box 1 1 1\n", 2, {"'!genbox'", "not supported"});
    expect_rad_error("!gendaylit 3 21 12 -W 800 100 -O 1\n", 1,
                     {"!gendaylit", "'-O'", "not supported"});
    expect_rad_error("\n!gendaylit 3 21 12 -P 3 0.2\n", 2, {"!gendaylit", "'-P'", "not supported"});
    expect_rad_error("!gendaylit -ang 30 0 -W 800 100\n", 1, {"!gendaylit", "-ang"});
    expect_rad_error("!gendaylit 3 21 12 -a 45\n", 1, {"!gendaylit", "-W, -L or -G"});
    expect_rad_error("!gendaylit 3 21 12 -W 800\n", 1, {"!gendaylit", "too few"});
    expect_rad_error("!gendaylit 3 21 12 -W -1 100\n", 1, {"!gendaylit", "-W", ">= 0"});
    expect_rad_error("!gendaylit 3 21 EST -W 800 100\n", 1, {"!gendaylit", "hour", "'EST'"});
    expect_rad_error("!xform -n copy part.rad\n", 1, {"!xform", "-n", "not supported"});
    expect_rad_error("!xform -t 1 1 part.rad\n", 1, {"!xform", "-t", "'part.rad'"});
    expect_rad_error("!xform missing.rad\n", 1, {"!xform", "missing.rad", "not found"});
    expect_rad_error("void plastic p\n0\n0\n5 .5 .5 .5 0 0\nvoid plastic p\n0\n0\n5 .4 .4 .4 0 0\n",
                     5, {"'p'", "defined again", "test.rad:10"});
    expect_rad_error("void brightfunc f\n2 skybright perezlum.cal\n0\n3 1 2 3\n", 1,
                     {"brightfunc 'f'", "10 real"});
    expect_rad_error("void brightfunc f\n2 skybr perezlum.cal\n0\n3 1 2 3\n", 1,
                     {"brightfunc 'f'", "perezlum.cal's 'skybright'"});
    expect_rad_error("void brightfunc f\n2 skybr skybright.cal\n0\n7 5 1 1 1 0 0 1\n", 1,
                     {"brightfunc 'f'", "sky type", "got 5"});
    expect_rad_error("void brightfunc f\n2 other my.cal\n0\n3 2 1 1\n", 1,
                     {"brightfunc 'f'", "skybright.cal"});
    expect_rad_error("void light s\n0\n0\n3 1 1 1\ns source a\n0\n0\n4 0 0 1 0.5\n"
                     "s source b\n0\n0\n4 0 1 1 0.5\n",
                     9, {"source 'b'", "second sun", "test.rad:14"});
    expect_rad_error("void light s\n0\n0\n3 1 1 1\ns source a\n0\n0\n4 0 1 1 45\n", 5,
                     {"source 'a'", "45°"});
    expect_rad_error("void glow g\n0\n0\n4 1 1 1 0\ng source ground\n0\n0\n4 0 0 -1 180\n", 5,
                     {"ground hemisphere needs a sky"});
    expect_rad_error("!gensky 3 21 +12 -y 2024\n", 1, {"!gensky", "'-y'"});
    expect_rad_error("!gensky 13 21 +12\n", 1, {"!gensky", "month"});
    expect_rad_error("!gensky 3 21 12EST\n", 1, {"!gensky", "time-zone"});
    expect_rad_error("!gensky 3 21 +12 -x\n", 1, {"!gensky", "'-x'"});
}

} // namespace
} // namespace penumbra
