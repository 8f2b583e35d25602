// `penumbra lightmap` as a user runs it: the files it writes, and one-line errors for bad
// flags before anything is solved or written.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/test_util.h"
#include "core/image.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

// A 1 m lamp above a 1 m floor.
const char* k_scene = R"({
  "materials": {"lamp": {"emission": [1, 1, 1], "reflectance": 0}, "floor": {"reflectance": 0.5}},
  "polygons": [
    {"name": "lamp", "material": "lamp", "vertices": [[0,0,1],[0,1,1],[1,1,1],[1,0,1]]},
    {"name": "floor", "material": "floor", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}
  ],
  "mesher": {"max_edge_length": 0.5}
}
)";

class LightmapCli : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::temp_dir("lightmap-cli");
        std::ofstream(dir_ / "scene.json") << k_scene;
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string command(const std::string& flags) const {
        return "lightmap " + (dir_ / "scene.json").string() + " -o " + (dir_ / "out").string() +
               " -q " + flags;
    }
    fs::path dir_;
};

TEST_F(LightmapCli, WritesTheAtlasesAndTheManifest) {
    const test::RunResult r = test::run_cli(command("--texels-per-metre 16 --atlas 64 --float"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const fs::path out = dir_ / "out";
    for (const char* f : {"lightmap_0.exr", "lightmap_0.png", "lightmap_0_preview.png",
                          "scene.gltf", "scene.bin", "lightmaps.json"})
        EXPECT_TRUE(fs::exists(out / f)) << f;
    EXPECT_FALSE(fs::exists(out / "lightmap_1.exr"));
    EXPECT_FALSE(fs::exists(out / "preview.exr")); // the scene has no camera
    for (const auto& entry : fs::directory_iterator(out))
        EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos);
    const auto manifest = nlohmann::json::parse(std::ifstream(out / "lightmaps.json"));
    EXPECT_EQ(manifest["atlas_size"], 64);
    EXPECT_EQ(manifest["texels_per_metre"], 16.0);
    EXPECT_EQ(manifest["padding"], 2);
    EXPECT_EQ(manifest["exr_pixels"], "float");
    ASSERT_EQ(manifest["atlases"].size(), 1u);
    EXPECT_GT(manifest["atlases"][0]["coverage"].get<double>(), 0.0);
    ASSERT_EQ(manifest["polygons"].size(), 2u);
    EXPECT_EQ(manifest["polygons"][1]["object"], "floor");
    EXPECT_EQ(manifest["polygons"][1]["atlases"], nlohmann::json::array({0}));
    const Image atlas = read_exr((out / "lightmap_0.exr").string());
    EXPECT_EQ(atlas.width, 64);
    EXPECT_EQ(atlas.height, 64);
    // The floor's centre, 1 m under the middle of the 1 m lamp of exitance π W/m², receives
    // π F = 0.7523 W/m² (F = 4 × (2/2π) (X/√(1 + X²)) atan(X/√(1 + X²)), X = 0.5: four
    // corner rectangles); the lamp reflects nothing. Its texels are the brightest, and the
    // irradiance is flat there (within 0.2 % over a texel).
    double brightest = 0;
    for (const Rgb& h : atlas.pixels)
        brightest = std::max(brightest, double(h.g));
    EXPECT_NEAR(brightest, 0.7523, 0.005 * 0.7523);
}

// The scene's `lightmap` key asks `bake` for the lightmaps too, at its atlas size.
TEST_F(LightmapCli, BakeHonoursTheScenesLightmapKey) {
    std::string scene = k_scene;
    scene.insert(scene.rfind('}'), R"(, "lightmap": {"size": 32})");
    std::ofstream(dir_ / "keyed.json") << scene;
    const fs::path out = dir_ / "out";
    const test::RunResult r = test::run_cli("bake " + (dir_ / "keyed.json").string() + " -o " +
                                            out.string() + " --no-render --no-state -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* f : {"mesh.vtu", "lightmap_0.exr", "lightmap_0.png", "lightmaps.json"})
        EXPECT_TRUE(fs::exists(out / f)) << f;
    const auto manifest = nlohmann::json::parse(std::ifstream(out / "lightmaps.json"));
    EXPECT_EQ(manifest["atlas_size"], 32);
    EXPECT_EQ(manifest["exr_pixels"], "half");
    EXPECT_EQ(read_exr((out / "lightmap_0.exr").string()).width, 32);
}

TEST_F(LightmapCli, BadFlagsAreOneLineErrors) {
    for (const char* flags : {"--texels-per-metre 0", "--texels-per-metre nan", "--atlas 0",
                              "--atlas 9000", "--padding -1", "--atlas 16 --padding 8"}) {
        const test::RunResult r = test::run_cli(command(flags));
        EXPECT_EQ(r.exit_code, 3) << flags << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << flags << ": " << r.err;
        EXPECT_EQ(r.err.rfind("penumbra: error: ", 0), 0u) << r.err;
        EXPECT_FALSE(fs::exists(dir_ / "out")) << flags;
    }
}

} // namespace
} // namespace penumbra
