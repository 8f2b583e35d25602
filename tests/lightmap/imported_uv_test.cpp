// The lightmap UV set of a glTF file (TEXCOORD_1) through the scene loader, in glTF's
// convention, and the charts it gives.

#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "core/scene_io.h"
#include "lightmap/atlas.h"
#include "lightmap/charts.h"
#include "lightmap/layout_checks.h"
#include "lightmap/texels.h"

namespace penumbra::test {
namespace {

using namespace lightmap;

// Triangle (0,0,0), (2,0,0), (0,1,0) facing +z; TEXCOORD_0 all zero, TEXCOORD_1 below.
const float k_buffer[] = {0,    0,    0,    2,     0,     0,   0, 1, 0, // POSITION
                          0,    0,    0,    0,     0,     0,            // TEXCOORD_0
                          0.1f, 0.2f, 0.7f, 0.25f, 0.15f, 0.9f};        // TEXCOORD_1

std::string triangle_gltf(bool lightmap_uv) {
    const std::string attributes = lightmap_uv
                                       ? R"("POSITION": 0, "TEXCOORD_0": 1, "TEXCOORD_1": 2)"
                                       : R"("POSITION": 0, "TEXCOORD_0": 1)";
    return R"json({
  "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"name": "panel", "mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {)json" +
           attributes + R"json(}, "material": 0}]}],
  "materials": [{"name": "glow", "emissiveFactor": [1, 1, 1],
                 "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1]}}],
  "buffers": [{"uri": "tri.bin", "byteLength": 84}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                  {"buffer": 0, "byteOffset": 36, "byteLength": 24},
                  {"buffer": 0, "byteOffset": 60, "byteLength": 24}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [2, 1, 0]},
                {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"},
                {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"}]
})json";
}

Scene load_triangle(bool lightmap_uv) {
    const std::string dir = temp_dir("lightmap-gltf");
    std::ofstream(dir + "/tri.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(k_buffer), sizeof(k_buffer));
    std::ofstream(dir + "/tri.gltf") << triangle_gltf(lightmap_uv);
    std::ofstream(dir + "/scene.json") << R"json({"geometry": "tri.gltf"})json";
    return load_scene(dir + "/scene.json");
}

TEST(ImportedUv, GltfTexcoord1ArrivesInGltfConvention) {
    const Scene scene = load_triangle(true);
    ASSERT_EQ(scene.polygons.size(), 1u);
    const auto& uv = scene.polygons[0].lightmap_uv;
    ASSERT_EQ(uv.size(), 3u);
    const double expected[3][2] = {{0.1, 0.2}, {0.7, 0.25}, {0.15, 0.9}};
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_NEAR(uv[i].x, expected[i][0], 1e-7) << i;
        EXPECT_NEAR(uv[i].y, expected[i][1], 1e-7) << i;
    }
}

TEST(ImportedUv, WithoutTexcoord1ThereIsNoLightmapUv) {
    EXPECT_TRUE(load_triangle(false).polygons[0].lightmap_uv.empty());
}

TEST(ImportedUv, ValidationRejectsAMismatchedOrNonFiniteUvSet) {
    Scene scene = load_triangle(true);
    scene.polygons[0].lightmap_uv.pop_back();
    expect_one_line_input_error([&] { validate_scene(scene); },
                                {"panel", "has 2 lightmap UVs for 3 vertices"}, "short UV set");
    scene.polygons[0].lightmap_uv = {{0, 0}, {1, 0}, {0, std::nan("")}};
    expect_one_line_input_error([&] { validate_scene(scene); },
                                {"panel", "lightmap UV 3 is not finite"}, "NaN UV");
}

TEST(ImportedUv, GltfTexcoord1BecomesOneImportedChart) {
    const Scene scene = load_triangle(true);
    const Context ctx = quiet_context();
    const Charts charts = build_charts(scene, {}, ctx);
    ASSERT_EQ(charts.charts.size(), 1u);
    EXPECT_EQ(charts.charts[0].kind, ChartKind::imported);
    EXPECT_EQ(charts.charts[0].object, "panel");
    const AtlasLayout layout = pack_atlases(charts, {.texels_per_metre = 40, .size = 128}, ctx);
    expect_valid_layout(charts, layout, rasterize(charts, layout, ctx));

    // The file's layout keeps its axes: atlas edges are the file's edges scaled and turned by
    // a multiple of 90°.
    const auto& file = scene.polygons[0].lightmap_uv;
    const auto& atlas = layout.placements[0].texel_uv;
    ASSERT_EQ(charts.charts[0].vertices.size(), 3u);
    auto edge = [](const Vec2& a, const Vec2& b) { return Vec2{b.x - a.x, b.y - a.y}; };
    const Vec2 f1 = edge(file[0], file[1]), f2 = edge(file[0], file[2]);
    const Vec2 a1 = edge(atlas[0], atlas[1]), a2 = edge(atlas[0], atlas[2]);
    const double scale = std::hypot(a1.x, a1.y) / std::hypot(f1.x, f1.y);
    bool quarter_turn = false;
    Vec2 r1 = f1, r2 = f2;
    for (int turn = 0; turn < 4; ++turn) {
        quarter_turn =
            quarter_turn ||
            (std::abs(a1.x - scale * r1.x) < 1e-9 && std::abs(a1.y - scale * r1.y) < 1e-9 &&
             std::abs(a2.x - scale * r2.x) < 1e-9 && std::abs(a2.y - scale * r2.y) < 1e-9);
        r1 = {-r1.y, r1.x};
        r2 = {-r2.y, r2.x};
    }
    EXPECT_TRUE(quarter_turn);

    ChartSettings generated;
    generated.use_imported_uv = false;
    EXPECT_EQ(build_charts(scene, generated, ctx).charts[0].kind, ChartKind::planar);
}

} // namespace
} // namespace penumbra::test
