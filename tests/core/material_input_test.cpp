// Material input (docs/scene-format.md): the scene file's material types, the MTL and glTF
// mappings key by key, the bundled cornell-spheres scene, smooth shading normals, the render,
// lightmap and background keys, and one-line errors for bad values.

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/scene_io.h"

#include "common/test_util.h"

namespace penumbra {
namespace {

std::string write_file(const std::string& dir, const std::string& name, const std::string& text) {
    const std::string path = dir + "/" + name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

const Material& material_named(const Scene& scene, const std::string& name) {
    for (const Material& m : scene.materials)
        if (m.name == name)
            return m;
    throw std::runtime_error("no material " + name);
}

template <class L> const L& lobe_of(const Scene& scene, const std::string& name) {
    const Material& m = material_named(scene, name);
    if (!m.lobe || !std::holds_alternative<L>(*m.lobe))
        throw std::runtime_error("material " + name + " has another lobe");
    return std::get<L>(*m.lobe);
}

/// A scene of one emitting square and one square per material of \p materials (JSON object
/// members), each polygon named after its material.
std::string squares_scene(const std::vector<std::string>& names, const std::string& materials,
                          const std::string& extra = "") {
    std::string polygons = R"({"name": "lamp", "material": "lamp",
        "vertices": [[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]]})";
    for (const std::string& name : names)
        polygons += R"(, {"name": ")" + name + R"(", "material": ")" + name +
                    R"(", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]})";
    return R"({"polygons": [)" + polygons + R"(], "materials": {"lamp": {"emission": 1}, )" +
           materials + "}" + extra + "}";
}

Scene parse(const std::string& text) {
    return parse_scene(text, "s.json", ".");
}

void expect_error(const std::string& text, const std::vector<std::string>& parts) {
    std::vector<std::string> with_file = parts;
    with_file.push_back("s.json");
    test::expect_one_line_input_error([&] { parse(text); }, with_file, text);
}

// ---- Scene file ---------------------------------------------------------------------------------

TEST(MaterialTypes, ParseEveryType) {
    const Scene scene = parse(squares_scene(
        {"metal", "coated", "chrome", "water", "pane", "matte"},
        R"("metal": {"type": "ggx", "alpha": 0.05, "specular": 0.9, "fresnel": "none"},
           "coated": {"type": "plastic", "alpha": 0.2, "reflectance": [0.5, 0.4, 0.3]},
           "chrome": {"type": "mirror", "specular": [0.9, 0.8, 0.7]},
           "water": {"type": "glass", "ior": 1.33, "solid": false, "transmittance": 0.9},
           "pane": {"type": "thin_glass", "transmissivity": 0.9},
           "matte": {"type": "diffuse", "reflectance": 0.2})"));
    const GgxGlossy& metal = lobe_of<GgxGlossy>(scene, "metal");
    EXPECT_EQ(metal.alpha, 0.05);
    EXPECT_EQ(metal.specular, Rgb(0.9f));
    EXPECT_TRUE(std::holds_alternative<FresnelNone>(metal.fresnel));
    EXPECT_FALSE(metal.diffuse_base);
    EXPECT_TRUE(radiosity_response(material_named(scene, "metal")).reflectance.is_black());
    // A plastic's default coat is a dielectric of index 1.5, white.
    const GgxGlossy& coated = lobe_of<GgxGlossy>(scene, "coated");
    EXPECT_TRUE(coated.diffuse_base);
    EXPECT_EQ(std::get<FresnelDielectric>(coated.fresnel).ior, 1.5);
    EXPECT_EQ(coated.specular, Rgb(1.0f));
    EXPECT_EQ(radiosity_response(material_named(scene, "coated")).reflectance,
              Rgb(0.5f, 0.4f, 0.3f));
    EXPECT_EQ(lobe_of<Mirror>(scene, "chrome").colour, Rgb(0.9f, 0.8f, 0.7f));
    const Dielectric& water = lobe_of<Dielectric>(scene, "water");
    EXPECT_EQ(water.ior, 1.33);
    EXPECT_FALSE(water.solid);
    EXPECT_EQ(water.transmittance, Rgb(0.9f));
    EXPECT_EQ(lobe_of<ThinGlass>(scene, "pane").transmissivity, Rgb(0.9f));
    EXPECT_FALSE(material_named(scene, "matte").lobe);
    for (const char* name : {"metal", "chrome", "water", "pane"})
        EXPECT_TRUE(material_named(scene, name).reflectance.is_black()) << name;
}

TEST(MaterialTypes, FresnelChoices) {
    const Scene scene = parse(squares_scene(
        {"a", "b"}, R"("a": {"type": "ggx", "fresnel": "schlick", "specular": [0.95, 0.64, 0.54]},
                       "b": {"type": "ggx", "fresnel": "dielectric", "ior": 1.7})"));
    EXPECT_TRUE(std::holds_alternative<FresnelSchlick>(lobe_of<GgxGlossy>(scene, "a").fresnel));
    EXPECT_EQ(std::get<FresnelDielectric>(lobe_of<GgxGlossy>(scene, "b").fresnel).ior, 1.7);
}

TEST(MaterialTypes, BadValuesAreOneLineErrors) {
    const auto one = [](const std::string& material) {
        return squares_scene({"m"}, R"("m": )" + material);
    };
    expect_error(one(R"({"type": "velvet"})"), {"materials.m.type", "unknown material type"});
    expect_error(one(R"({"type": "ggx", "alpha": 0})"), {"materials.m.alpha", "(0, 1]"});
    expect_error(one(R"({"type": "ggx", "alpha": -0.1})"), {"materials.m.alpha", "(0, 1]"});
    expect_error(one(R"({"type": "plastic", "alpha": 1.5})"), {"materials.m.alpha", "(0, 1]"});
    expect_error(one(R"({"type": "glass", "ior": 0.9})"), {"materials.m.ior", "[1, 10]"});
    expect_error(one(R"({"type": "plastic", "ior": 0.5})"), {"materials.m.ior", "[1, 10]"});
    expect_error(one(R"({"type": "ggx", "specular": 1.2})"), {"materials.m.specular", "[0, 1]"});
    expect_error(one(R"({"type": "mirror", "specular": [0.5, -0.1, 0.5]})"),
                 {"materials.m.specular", "[0, 1]"});
    expect_error(one(R"({"type": "ggx", "fresnel": "fancy"})"),
                 {"materials.m.fresnel", "unknown fresnel"});
    expect_error(one(R"({"type": "ggx", "ior": 1.5})"),
                 {"materials.m.ior", "only used with \"fresnel\": \"dielectric\""});
    expect_error(one(R"({"type": "ggx", "reflectance": 0.5})"),
                 {"materials.m.reflectance", "not a key of a 'ggx' material"});
    expect_error(one(R"({"alpha": 0.1})"),
                 {"materials.m.alpha", "not a key of a 'diffuse' material"});
    expect_error(one(R"({"type": "mirror", "solid": true})"), {"materials.m.solid"});
}

// A type replaces an imported material's lobe; the keys it omits take their defaults.
TEST(MaterialTypes, TypeOverridesAnImportedMaterial) {
    const std::string dir = test::temp_dir("material-override");
    write_file(dir, "a.mtl",
               "newmtl shiny\nKd 0.5 0.5 0.5\nKs 0.9 0.9 0.9\nPr 0.5\nillum 3\n"
               "newmtl lamp\nKe 1 1 1\n");
    write_file(dir, "a.obj",
               "mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl shiny\nf 1 2 3\n"
               "usemtl lamp\nf 3 2 1\n");
    write_file(dir, "s.json", R"({"geometry": "a.obj",
        "materials": {"shiny": {"type": "mirror"}}})");
    const Scene scene = load_scene(dir + "/s.json");
    EXPECT_EQ(lobe_of<Mirror>(scene, "shiny").colour, Rgb(1.0f));
    EXPECT_TRUE(material_named(scene, "shiny").reflectance.is_black());
}

// ---- MTL ---------------------------------------------------------------------------------------

Scene load_mtl(const std::string& dir, const std::string& mtl,
               const std::vector<std::string>& names) {
    write_file(dir, "m.mtl", "newmtl lamp\nKe 1 1 1\n" + mtl);
    std::string obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl lamp\nf 1 2 3\n";
    for (const std::string& name : names)
        obj += "usemtl " + name + "\nf 1 2 3\n";
    write_file(dir, "m.obj", obj);
    write_file(dir, "s.json", R"({"geometry": "m.obj"})");
    return load_scene(dir + "/s.json");
}

TEST(MtlMaterials, MapsEachKey) {
    const Scene scene =
        load_mtl(test::temp_dir("mtl-map"),
                 "newmtl glass\nKd 0 0 0\nNi 1.5\nTf 1 0.9 0.8\nillum 7\n"
                 "newmtl metal\nKd 0 0 0\nKs 0.9 0.9 0.9\nPr 0.2236\nillum 3\n"
                 "newmtl phong\nKd 0 0 0\nKs 0.5 0.5 0.5\nNs 98\nillum 3\n"
                 "newmtl mirror\nKd 0 0 0\nKs 0.8 0.8 0.8\nillum 3\n"
                 "newmtl coated\nKd 0.5 0.5 0.5\nKs 0.04 0.04 0.04\nNs 48\nillum 3\n"
                 "newmtl veil\nKd 0.3 0.3 0.3\nd 0.25\nTf 1 1 0.5\n"
                 "newmtl tr\nKd 0.3 0.3 0.3\nTr 0.6\nNi 1.6\n"
                 "newmtl plain\nKd 0.3 0.3 0.3\nKs 0.5 0.5 0.5\nNs 250\nillum 2\n",
                 {"glass", "metal", "phong", "mirror", "coated", "veil", "tr", "plain"});
    const Dielectric& glass = lobe_of<Dielectric>(scene, "glass");
    EXPECT_FLOAT_EQ(float(glass.ior), 1.5f);
    EXPECT_TRUE(glass.solid);
    EXPECT_EQ(glass.transmittance, Rgb(1, 0.9f, 0.8f));
    const GgxGlossy& metal = lobe_of<GgxGlossy>(scene, "metal");
    EXPECT_NEAR(metal.alpha, 0.05, 1e-4); // Pr² = 0.2236²
    EXPECT_EQ(metal.specular, Rgb(0.9f));
    EXPECT_TRUE(std::holds_alternative<FresnelNone>(metal.fresnel));
    EXPECT_FALSE(metal.diffuse_base);
    EXPECT_NEAR(lobe_of<GgxGlossy>(scene, "phong").alpha, std::sqrt(2.0 / 100.0), 1e-7);
    EXPECT_EQ(lobe_of<Mirror>(scene, "mirror").colour, Rgb(0.8f));
    const GgxGlossy& coated = lobe_of<GgxGlossy>(scene, "coated");
    EXPECT_NEAR(coated.alpha, 0.2, 1e-7); // √(2 / 50)
    EXPECT_TRUE(coated.diffuse_base);
    EXPECT_EQ(material_named(scene, "coated").reflectance, Rgb(0.5f));
    const ThinGlass& veil = lobe_of<ThinGlass>(scene, "veil");
    EXPECT_EQ(veil.transmissivity, Rgb(0.75f, 0.75f, 0.375f)); // (1 − d) Tf
    EXPECT_EQ(veil.ior, ThinGlass{}.ior);
    EXPECT_TRUE(material_named(scene, "veil").reflectance.is_black());
    const ThinGlass& tr = lobe_of<ThinGlass>(scene, "tr");
    EXPECT_NEAR(tr.transmissivity.g, 0.6f, 1e-6);
    EXPECT_FLOAT_EQ(float(tr.ior), 1.6f);
    EXPECT_FALSE(material_named(scene, "plain").lobe); // illum 2's highlight is not kept
    EXPECT_EQ(material_named(scene, "plain").reflectance, Rgb(0.3f));
    for (const char* name : {"glass", "metal", "phong", "mirror"})
        EXPECT_TRUE(radiosity_response(material_named(scene, name)).reflectance.is_black());
}

TEST(MtlMaterials, BadValuesNameTheMaterialAndKey) {
    const std::string dir = test::temp_dir("mtl-bad");
    test::expect_one_line_input_error([&] { load_mtl(dir, "newmtl g\nNi 0.5\nillum 7\n", {"g"}); },
                                      {"m.obj", "'g.Ni'", "[1, 10]"}, "Ni 0.5");
    test::expect_one_line_input_error(
        [&] { load_mtl(dir, "newmtl g\nKs 1 1 1\nPr 1.5\nillum 3\n", {"g"}); },
        {"m.obj", "'g.Pr'", "[0, 1]"}, "Pr 1.5");
    test::expect_one_line_input_error(
        [&] { load_mtl(dir, "newmtl g\nKs 1.5 1 1\nillum 3\n", {"g"}); },
        {"m.obj", "'g.Ks'", "[0, 1]"}, "Ks 1.5");
}

// ---- glTF --------------------------------------------------------------------------------------

/// One triangle facing +z with vertex normals (1, 1, 0)/√2 ... in tri.bin: positions then
/// normals.
void write_triangle_bin(const std::string& dir) {
    const float s = float(1 / std::sqrt(2.0));
    const float data[18] = {0, 0, 0, 1, 0, 0, 0, 1, 0, s, s, 0, s, s, 0, 0, 0, 1};
    std::ofstream(dir + "/tri.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(data), sizeof(data));
}

/// A glTF of one node per material (node i uses mesh i and material i), node 0 scaled by
/// \p scale.
std::string materials_gltf(const std::vector<std::string>& materials, const std::string& scale) {
    std::string nodes, meshes, list;
    for (std::size_t i = 0; i < materials.size(); ++i) {
        const std::string sep = i ? ", " : "";
        nodes += sep + R"({"name": "n)" + std::to_string(i) + R"(", "mesh": )" + std::to_string(i) +
                 (i == 0 ? R"(, "scale": )" + scale : "") + "}";
        meshes += sep +
                  R"({"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "material": )" +
                  std::to_string(i) + "}]}";
        list += sep + materials[i];
    }
    std::string scene_nodes;
    for (std::size_t i = 0; i < materials.size(); ++i)
        scene_nodes += (i ? ", " : "") + std::to_string(i);
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [)" + scene_nodes +
           R"(]}], "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior",
           "KHR_materials_volume"], "nodes": [)" +
           nodes + R"(], "meshes": [)" + meshes + R"(], "materials": [)" + list + R"(],
  "buffers": [{"uri": "tri.bin", "byteLength": 72}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]},
                {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"}]})";
}

TEST(GltfMaterials, MetallicRoughnessTransmissionAndIor) {
    const std::string dir = test::temp_dir("gltf-materials");
    write_triangle_bin(dir);
    write_file(
        dir, "m.gltf",
        materials_gltf(
            {
                R"({"name": "lamp", "emissiveFactor": [1, 1, 1],
            "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0}})",
                R"({"name": "metal", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.8, 0.7, 1],
            "metallicFactor": 1, "roughnessFactor": 0.3}})",
                R"({"name": "plastic", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.3, 0.4, 1],
            "metallicFactor": 0, "roughnessFactor": 0.5}})",
                R"({"name": "half", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1],
            "metallicFactor": 0.5, "roughnessFactor": 0}})",
                R"({"name": "pane", "pbrMetallicRoughness": {"baseColorFactor": [1, 0.9, 0.8, 1],
            "metallicFactor": 0, "roughnessFactor": 0},
            "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.9},
                           "KHR_materials_ior": {"ior": 1.45}}})",
                R"({"name": "solid", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0},
            "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                           "KHR_materials_volume": {"thicknessFactor": 0.1}}})",
                R"({"name": "default"})"},
            "[2, 1, 1]"));
    write_file(dir, "s.json", R"({"geometry": "m.gltf"})");
    const Scene scene = load_scene(dir + "/s.json");

    const GgxGlossy& metal = lobe_of<GgxGlossy>(scene, "metal");
    EXPECT_NEAR(metal.alpha, 0.09, 1e-7); // r²
    EXPECT_EQ(metal.specular, Rgb(0.9f, 0.8f, 0.7f));
    EXPECT_TRUE(std::holds_alternative<FresnelSchlick>(metal.fresnel));
    EXPECT_FALSE(metal.diffuse_base);
    EXPECT_TRUE(material_named(scene, "metal").reflectance.is_black());
    const GgxGlossy& plastic = lobe_of<GgxGlossy>(scene, "plastic");
    EXPECT_NEAR(plastic.alpha, 0.25, 1e-7);
    EXPECT_EQ(plastic.specular, Rgb(0.04f));
    EXPECT_TRUE(plastic.diffuse_base);
    EXPECT_EQ(material_named(scene, "plastic").reflectance, Rgb(0.2f, 0.3f, 0.4f));
    const GgxGlossy& half = lobe_of<GgxGlossy>(scene, "half");
    EXPECT_NEAR(half.specular.g, 0.5 * 0.04 + 0.5 * 0.5, 1e-6); // mix(0.04, base, m)
    EXPECT_NEAR(material_named(scene, "half").reflectance.g, 0.25, 1e-6);
    EXPECT_EQ(half.alpha, 1e-3); // roughness 0: the smallest imported α
    const ThinGlass& pane = lobe_of<ThinGlass>(scene, "pane"); // thin-walled without a volume
    EXPECT_NEAR(pane.transmissivity.g, 0.9 * 0.9, 1e-6);
    EXPECT_NEAR(pane.ior, 1.45, 1e-6);
    const Dielectric& solid = lobe_of<Dielectric>(scene, "solid");
    EXPECT_NEAR(solid.ior, 1.5, 1e-6); // KHR_materials_ior's default
    EXPECT_EQ(solid.transmittance, Rgb(1.0f));
    // glTF's defaults: metallic 1, roughness 1.
    const GgxGlossy& fallback = lobe_of<GgxGlossy>(scene, "default");
    EXPECT_FALSE(fallback.diffuse_base);
    EXPECT_EQ(fallback.alpha, 1.0);
}

// Normals go through the inverse transpose: node 0's scale (2, 1, 1) turns (1, 1, 0)/√2 into
// (1/2, 1, 0) normalised.
TEST(GltfMaterials, VertexNormalsFollowTheNodeTransform) {
    const std::string dir = test::temp_dir("gltf-normals");
    write_triangle_bin(dir);
    write_file(dir, "m.gltf",
               materials_gltf({R"({"name": "lamp", "emissiveFactor": [1, 1, 1]})"}, "[2, 1, 1]"));
    write_file(dir, "s.json", R"({"geometry": "m.gltf"})");
    const Scene scene = load_scene(dir + "/s.json");
    ASSERT_EQ(scene.polygons.size(), 1u);
    const std::vector<Vec3>& n = scene.polygons[0].normals;
    ASSERT_EQ(n.size(), 3u);
    const Vec3 expected = normalize(Vec3(0.5, 1, 0));
    EXPECT_NEAR(length(n[0] - expected), 0.0, 1e-6);
    EXPECT_NEAR(length(n[2] - Vec3(0, 0, 1)), 0.0, 1e-6);
}

// ---- cornell-spheres and the top-level keys ---------------------------------------------------

TEST(CornellSpheres, LoadsAsSpecified) {
    const Scene scene = load_scene(test::source_path("data/cornell-spheres/cornell_spheres.json"));
    const Dielectric& glass = lobe_of<Dielectric>(scene, "glass");
    EXPECT_EQ(glass.ior, 1.5);
    EXPECT_TRUE(glass.solid);
    EXPECT_EQ(glass.transmittance, Rgb(1.0f));
    const GgxGlossy& metal = lobe_of<GgxGlossy>(scene, "metal");
    EXPECT_EQ(metal.alpha, 0.05);
    EXPECT_EQ(metal.specular, Rgb(0.9f));
    EXPECT_TRUE(std::holds_alternative<FresnelNone>(metal.fresnel));
    EXPECT_FALSE(metal.diffuse_base);
    for (const char* name : {"glass", "metal"})
        EXPECT_TRUE(radiosity_response(material_named(scene, name)).reflectance.is_black());
    EXPECT_FALSE(material_named(scene, "light").emission_two_sided);
    ASSERT_TRUE(scene.camera);
    EXPECT_EQ(scene.camera->samples_per_pixel, 64);
    EXPECT_EQ(scene.render.max_bounces, 16);
    EXPECT_EQ(scene.render.pixel_filter, PixelFilter::box);
    EXPECT_EQ(scene.render.filter_width_px, 1.0);
    ASSERT_TRUE(scene.lightmap);
    EXPECT_EQ(scene.lightmap->atlas_size, 512);
    EXPECT_TRUE(scene.background.is_black());
    // The spheres (96 × 48 UV spheres) keep their normals; the walls have none.
    std::size_t smooth = 0;
    for (const Polygon& p : scene.polygons) {
        const bool sphere = p.name == "glass_sphere" || p.name == "metal_sphere";
        EXPECT_EQ(p.normals.empty(), !sphere) << p.name;
        if (sphere) {
            ++smooth;
            ASSERT_EQ(p.normals.size(), p.vertices.size());
        }
    }
    EXPECT_EQ(smooth, 2u * 96 * 48);
}

// The MTL alone says what the scene file says of the two spheres' materials.
TEST(CornellSpheres, MtlMatchesTheSceneFile) {
    const std::string dir = test::temp_dir("cornell-spheres-mtl");
    write_file(dir, "s.json",
               R"({"units": "mm", "geometry": ")" +
                   test::source_path("data/cornell-spheres/cornell_spheres.obj") + R"("})");
    const Scene scene = load_scene(dir + "/s.json");
    const Dielectric& glass = lobe_of<Dielectric>(scene, "glass");
    EXPECT_FLOAT_EQ(float(glass.ior), 1.5f);
    EXPECT_EQ(glass.transmittance, Rgb(1.0f));
    const GgxGlossy& metal = lobe_of<GgxGlossy>(scene, "metal");
    EXPECT_NEAR(metal.alpha, 0.05, 1e-4);
    EXPECT_EQ(metal.specular, Rgb(0.9f));
    EXPECT_TRUE(std::holds_alternative<FresnelNone>(metal.fresnel));
}

TEST(SceneKeys, BadRenderLightmapBackgroundAndSmoothObjects) {
    const std::string camera = R"(, "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]})";
    const auto scene = [](const std::string& extra) {
        return squares_scene({}, R"("x": {})", extra);
    };
    expect_error(scene(camera + R"(, "render": {"spp": 0})"), {"render.spp", "[1, 1048576]"});
    expect_error(scene(R"(, "render": {"spp": 16})"), {"render.spp", "needs a 'camera'"});
    expect_error(scene(camera + R"(, "image": {"spp": 4}, "render": {"spp": 16})"),
                 {"render.spp", "not both"});
    expect_error(scene(R"(, "render": {"pixel_filter": "mitchell"})"),
                 {"render.pixel_filter", "unknown pixel filter", "box, gaussian"});
    expect_error(scene(R"(, "render": {"max_bounces": -1})"), {"render.max_bounces"});
    expect_error(scene(R"(, "render": {"filter_width_px": 0})"), {"render.filter_width_px"});
    expect_error(scene(R"(, "render": {"bounces": 3})"), {"render.bounces", "unknown key"});
    expect_error(scene(R"(, "lightmap": {"size": 8})"), {"lightmap.size", "[16, 16384]"});
    expect_error(scene(R"(, "background": [0, -1, 0])"), {"background", ">= 0"});
    expect_error(scene(R"(, "background": 0, "sky": {"model": "uniform",
                 "zenith_luminance_cd_m2": 1})"),
                 {"background", "not both"});
    expect_error(scene(R"(, "smooth_objects": ["lamp"])"),
                 {"smooth_objects[0]", "'lamp'", "has vertex normals"});
    expect_error(scene(R"(, "smooth_objects": ["a", "a"])"), {"smooth_objects[1]", "twice"});
    expect_error(scene(R"(, "emission_two_sided": 1)"), {"emission_two_sided", "true or false"});
}

// The top-level emission_two_sided applies to every material that does not give its own.
TEST(SceneKeys, EmissionTwoSidedDefault) {
    const Scene scene = parse(squares_scene(
        {"a", "b"}, R"("a": {"emission": 2}, "b": {"emission": 2, "emission_two_sided": false})",
        R"(, "emission_two_sided": true)"));
    EXPECT_TRUE(material_named(scene, "lamp").emission_two_sided);
    EXPECT_TRUE(material_named(scene, "a").emission_two_sided);
    EXPECT_FALSE(material_named(scene, "b").emission_two_sided);
}

} // namespace
} // namespace penumbra
namespace penumbra {
namespace {

// `annual.blinds`: each entry is a copy of the scene's material of that name with the entry's
// keys applied (the pane turned diffusing, another's reflectance changed); the scene's own
// materials are unchanged. A name the scene lacks, or a shaded material out of range, is a
// one-line error naming the key.
TEST(SceneKeys, AnnualBlindsOverrideSceneMaterials) {
    const Scene scene = parse(squares_scene(
        {"pane", "wall"},
        R"("pane": {"type": "thin_glass", "transmissivity": 0.8}, "wall": {"reflectance": 0.5})",
        R"(, "annual": {"blinds": {
             "pane": {"type": "diffuse", "reflectance": 0.4, "diffuse_transmittance": 0.2},
             "wall": {"reflectance": 0.3}}})"));
    ASSERT_EQ(scene.annual.blinds.size(), 2u);
    const Material& pane = scene.annual.blinds[0];
    EXPECT_EQ(pane.name, "pane");
    EXPECT_FALSE(pane.lobe.has_value());
    EXPECT_EQ(pane.reflectance, Rgb(0.4f));
    EXPECT_EQ(pane.diffuse_transmittance, Rgb(0.2f));
    EXPECT_EQ(scene.annual.blinds[1].reflectance, Rgb(0.3f));
    EXPECT_TRUE(lobe_of<ThinGlass>(scene, "pane").transmissivity.g > 0.7f);
    EXPECT_EQ(material_named(scene, "wall").reflectance, Rgb(0.5f));
    expect_error(squares_scene({"wall"}, R"("wall": {"reflectance": 0.5})",
                               R"(, "annual": {"blinds": {"glass": {"reflectance": 0.3}}})"),
                 {"annual.blinds.glass", "no material"});
    expect_error(squares_scene({"wall"}, R"("wall": {"reflectance": 0.5})",
                               R"(, "annual": {"blinds": {"wall": {"reflectance": 0.3,
                                   "diffuse_transmittance": 0.8}}})"),
                 {"annual.blinds.wall.diffuse_transmittance"});
    expect_error(
        squares_scene({"wall"}, R"("wall": {"reflectance": 0.5})", R"(, "annual": {"shades": {}})"),
        {"annual", "shades"});
}

} // namespace
} // namespace penumbra
