// The glTF copy of a lightmap bake (issue #29): the Khronos validator finds nothing but the
// notice that it does not know MOZ_lightmap; assimp reads it back with TEXCOORD_1 on every mesh
// and the scene's triangles and area; a z-up scene comes out +Y up; the MOZ_lightmap PNG holds
// 179 lm/W × irradiance / intensity.

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <png.h>

#include "app/lightmap.h"
#include "common/bake_util.h"
#include "common/test_util.h"
#include "core/image.h"
#include "core/rgb.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

// Standard output of a shell command; its exit status in \p status.
std::string run(const std::string& command, int& status) {
    std::string out;
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe)
        return out;
    std::array<char, 4096> buf{};
    while (std::fgets(buf.data(), int(buf.size()), pipe))
        out += buf.data();
    const int raw = ::pclose(pipe);
    status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    return out;
}

TEST(LightmapGltf, CornellPassesTheKhronosValidator) {
    const std::string validator = test::source_path("client/validate_gltf.js");
    ASSERT_TRUE(fs::exists(test::source_path("client/node_modules/gltf-validator")))
        << "gltf-validator is not installed: run scripts/setup.sh --deps (npm ci in client/)";
    const fs::path out = test::temp_dir("lightmap-gltf-validate");
    const test::RunResult bake =
        test::run_cli("lightmap " + test::source_path("data/cornell/scene.json") + " -o " +
                      out.string() + " -q --atlas 256 --texels-per-metre 100");
    ASSERT_EQ(bake.exit_code, 0) << bake.err;
    int status = -1;
    const std::string report =
        run("node " + validator + " " + (out / "scene.gltf").string() + " 2>&1", status);
    ASSERT_EQ(status, 0) << report;
    const auto j = nlohmann::json::parse(report);
    EXPECT_TRUE(j["errors"].empty()) << j["errors"].dump(2);
    // The validator knows KHR_materials_emissive_strength but not the vendor extension: it
    // says so (an info in validator 2.0.0-dev.3.10, a warning in some versions) and, not
    // knowing that MOZ_lightmap reads the texture and TEXCOORD_1, calls them unused (infos).
    bool moz_unsupported = false;
    for (const char* severity : {"warnings", "infos"})
        for (const auto& issue : j[severity]) {
            const bool moz =
                issue["code"] == "UNSUPPORTED_EXTENSION" &&
                issue["message"].get<std::string>().find("MOZ_lightmap") != std::string::npos;
            moz_unsupported |= moz;
            EXPECT_TRUE(moz ||
                        (severity == std::string("infos") && issue["code"] == "UNUSED_OBJECT"))
                << severity << ": " << issue.dump();
        }
    EXPECT_TRUE(moz_unsupported);
    EXPECT_TRUE(j["hints"].empty()) << j["hints"].dump(2);
    std::printf("validator %s: %zu errors, %zu warnings, %zu infos, %zu hints\n",
                j["validator"].get<std::string>().c_str(), j["errors"].size(), j["warnings"].size(),
                j["infos"].size(), j["hints"].size());
    fs::remove_all(out);
}

// Area of a planar polygon (Newell's normal), m².
double polygon_area(const Polygon& p) {
    Vec3 n;
    for (std::size_t i = 0; i < p.vertices.size(); ++i)
        n += cross(p.vertices[i], p.vertices[(i + 1) % p.vertices.size()]);
    return length(n) / 2;
}

double triangle_area(const aiVector3D& a, const aiVector3D& b, const aiVector3D& c) {
    return ((b - a) ^ (c - a)).Length() / 2;
}

TEST(LightmapGltf, ReadsBackThroughAssimpWithTheScenesTrianglesAndArea) {
    const Scene scene = test::cornell_box(0.15);
    app::LightmapOptions options;
    options.atlas.texels_per_metre = 40;
    options.atlas.size = 128;
    const app::LightmapResult r = app::bake_lightmaps(scene, options, test::quiet_context());
    const fs::path out = test::temp_dir("lightmap-gltf-assimp");
    app::write_lightmaps(out.string(), scene, options, r);

    Assimp::Importer importer;
    const aiScene* read = importer.ReadFile((out / "scene.gltf").string(), 0);
    ASSERT_NE(read, nullptr) << importer.GetErrorString();
    std::size_t triangles = 0;
    double area = 0;
    for (unsigned m = 0; m < read->mNumMeshes; ++m) {
        const aiMesh& mesh = *read->mMeshes[m];
        ASSERT_TRUE(mesh.HasTextureCoords(1)) << mesh.mName.C_Str();
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
            const aiFace& face = mesh.mFaces[f];
            ASSERT_EQ(face.mNumIndices, 3u);
            area +=
                triangle_area(mesh.mVertices[face.mIndices[0]], mesh.mVertices[face.mIndices[1]],
                              mesh.mVertices[face.mIndices[2]]);
            for (int k = 0; k < 3; ++k) {
                const aiVector3D& uv = mesh.mTextureCoords[1][face.mIndices[k]];
                EXPECT_TRUE(uv.x >= 0 && uv.x <= 1 && uv.y >= 0 && uv.y <= 1);
            }
        }
        triangles += mesh.mNumFaces;
    }
    // The scene's convex polygons, each fanned into n − 2 triangles.
    std::size_t expected_triangles = 0;
    double expected_area = 0;
    for (const Polygon& p : scene.polygons) {
        expected_triangles += p.vertices.size() - 2;
        expected_area += polygon_area(p);
    }
    EXPECT_EQ(triangles, expected_triangles);
    EXPECT_NEAR(area, expected_area, 1e-5 * expected_area);
    fs::remove_all(out);
}

// A z-up scene: a 1 m lamp facing down 1 m above a 1 m floor.
Scene lamp_over_floor() {
    Scene s;
    s.up = {0, 0, 1};
    const auto lamp = test::add_material(s, "lamp", Rgb(0.0f), Rgb(1.0f), false);
    const auto floor = test::add_material(s, "floor", Rgb(0.5f));
    test::add_rect(s, "lamp", lamp, {0, 0, 1}, {0, 1, 0}, {1, 0, 0});
    test::add_rect(s, "floor", floor, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    s.mesher.max_edge_length = 0.5;
    return s;
}

// 8-bit RGB pixels of a PNG.
std::vector<std::uint8_t> read_png_rgb(const fs::path& path, int& width, int& height) {
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&png, path.c_str()))
        return {};
    png.format = PNG_FORMAT_RGB;
    std::vector<std::uint8_t> pixels(PNG_IMAGE_SIZE(png));
    png_image_finish_read(&png, nullptr, pixels.data(), 0, nullptr);
    width = int(png.width);
    height = int(png.height);
    return pixels;
}

double srgb_to_linear(double s) {
    return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
}

TEST(LightmapGltf, ZUpSceneComesOutYUpWithMozLightmapEncoding) {
    const Scene scene = lamp_over_floor();
    app::LightmapOptions options;
    options.atlas.texels_per_metre = 16;
    options.atlas.size = 64;
    const app::LightmapResult r = app::bake_lightmaps(scene, options, test::quiet_context());
    const fs::path out = test::temp_dir("lightmap-gltf-up");
    app::write_lightmaps(out.string(), scene, options, r);

    Assimp::Importer importer;
    const aiScene* read = importer.ReadFile((out / "scene.gltf").string(), 0);
    ASSERT_NE(read, nullptr) << importer.GetErrorString();
    ASSERT_EQ(read->mNumMeshes, 2u);
    for (unsigned m = 0; m < read->mNumMeshes; ++m) {
        const aiMesh& mesh = *read->mMeshes[m];
        const bool lamp = std::string(mesh.mName.C_Str()).find("lamp") != std::string::npos;
        for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
            EXPECT_NEAR(mesh.mVertices[v].y, lamp ? 1.0 : 0.0, 1e-6);
            EXPECT_NEAR(mesh.mNormals[v].y, lamp ? -1.0 : 1.0, 1e-6);
        }
    }
    // MOZ_lightmap: intensity = 179 × the atlas's brightest channel, which the PNG holds as 255;
    // every texel decodes to 179 × E / intensity within 8-bit sRGB rounding.
    const auto gltf = nlohmann::json::parse(std::ifstream(out / "scene.gltf"));
    const auto& moz = gltf["materials"][0]["extensions"]["MOZ_lightmap"];
    EXPECT_EQ(moz["texture"]["texCoord"], 1);
    const double intensity = moz["intensity"].get<double>();
    double peak = 0;
    for (const Rgb& e : r.atlases[0].pixels)
        peak = std::max(peak, double(e.g));
    EXPECT_NEAR(intensity, k_luminous_efficacy_lm_per_w * peak, 1e-9 * intensity);
    int w = 0, h = 0;
    const auto png = read_png_rgb(out / "lightmap_0.png", w, h);
    ASSERT_EQ(w, 64);
    ASSERT_EQ(h, 64);
    for (std::size_t i = 0; i < r.atlases[0].pixels.size(); ++i) {
        const double lux = k_luminous_efficacy_lm_per_w * r.atlases[0].pixels[i].g;
        const double s = png[3 * i + 1] / 255.0;
        // Half a code step in sRGB, as linear: at most |d linear / d s| × 0.5/255.
        const double step =
            std::max(srgb_to_linear(std::min(1.0, s + 0.5 / 255)) - srgb_to_linear(s),
                     srgb_to_linear(s) - srgb_to_linear(std::max(0.0, s - 0.5 / 255)));
        EXPECT_NEAR(srgb_to_linear(s) * intensity, lux, step * intensity + 1e-9) << "texel " << i;
    }
    fs::remove_all(out);
}

} // namespace
} // namespace penumbra
