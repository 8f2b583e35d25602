// Packing and rasterization: padding between charts, texels on their triangles, areas kept,
// the Cornell box and a sphere, several atlases, charts too large for an atlas, determinism.

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "core/error.h"
#include "core/scene_io.h"
#include "lightmap/atlas.h"
#include "lightmap/layout_checks.h"
#include "lightmap/shapes.h"
#include "lightmap/texels.h"

namespace penumbra::test {
namespace {

using namespace lightmap;

struct Bake {
    Charts charts;
    AtlasLayout layout;
    std::vector<AtlasTexels> atlases;
};

Bake bake(const Scene& scene, const AtlasSettings& settings, int threads = 0) {
    const Context ctx = quiet_context(threads);
    Bake b;
    b.charts = build_charts(scene, {}, ctx);
    b.layout = pack_atlases(b.charts, settings, ctx);
    b.atlases = rasterize(b.charts, b.layout, ctx);
    return b;
}

Scene cornell() {
    return load_scene(source_path("data/cornell/scene.json"));
}

Scene sphere_scene() {
    Scene scene;
    add_sphere(scene, "sphere", add_material(scene, "white", Rgb(0.5, 0.5, 0.5)), {0, 0, 0}, 1.0,
               16, 32);
    return scene;
}

double texel_area(const ChartPlacement& p, const ChartTriangle& t) {
    const Vec2 a = p.texel_uv[t.vertices[0]], b = p.texel_uv[t.vertices[1]],
               c = p.texel_uv[t.vertices[2]];
    return 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
}

const char* packer_name(AtlasPacker p) {
    return p == AtlasPacker::profiles ? "profiles" : "rectangles";
}

TEST(Atlas, PlanarChartAreasScaleWithDensitySquared) {
    Scene scene;
    const auto white = add_material(scene, "white", Rgb(0.5, 0.5, 0.5));
    add_room(scene, {0, 0, 0}, {4, 3, 2.5}, white);
    // A slanted, rotated parallelogram: packing turns it to its minimum-area rectangle.
    add_rect(scene, "slab", white, {1, 1, 1}, {0.7, 0.3, 0.2}, {-0.1, 0.5, 0.4});
    const Bake b = bake(scene, {.texels_per_metre = 37, .size = 512, .padding = 3});
    for (std::size_t c = 0; c < b.charts.charts.size(); ++c) {
        const Chart& chart = b.charts.charts[c];
        ASSERT_EQ(chart.kind, ChartKind::planar);
        const double density = b.layout.placements[c].texels_per_metre;
        EXPECT_EQ(density, 37.0);
        for (const ChartTriangle& t : chart.triangles) {
            const Vec3 p = chart.vertices[t.vertices[0]].position;
            const double area = 0.5 * length(cross(chart.vertices[t.vertices[1]].position - p,
                                                   chart.vertices[t.vertices[2]].position - p));
            EXPECT_NEAR(texel_area(b.layout.placements[c], t) / (density * density), area,
                        1e-9 * area);
        }
    }
    expect_valid_layout(b.charts, b.layout, b.atlases);
}

TEST(Atlas, AxisAlignedWallCoversExactlyItsTexels) {
    // A 1 m × 0.5 m wall at 20 texels/m: 20 × 10 texels, every centre on the wall.
    Scene scene;
    add_rect(scene, "wall", add_material(scene, "white", Rgb(0.5, 0.5, 0.5)), {0, 0, 0}, {1, 0, 0},
             {0, 0, 0.5});
    const Bake b = bake(scene, {.texels_per_metre = 20, .size = 64, .padding = 2});
    ASSERT_EQ(b.atlases.size(), 1u);
    EXPECT_EQ(b.atlases[0].texels.size(), 200u);
    const TexelRect r = b.layout.placements[0].rect;
    EXPECT_EQ(r.width * r.height, 200);
    EXPECT_NEAR(b.layout.coverage[0], 200.0 / (64 * 64), 1e-15);
    for (const Texel& t : b.atlases[0].texels) {
        EXPECT_DOUBLE_EQ(t.centre.texel_uv.x, t.x + 0.5);
        EXPECT_DOUBLE_EQ(t.centre.texel_uv.y, t.y + 0.5);
    }
    expect_valid_layout(b.charts, b.layout, b.atlases);
}

TEST(Atlas, CornellBoxGivesValidAtlases) {
    const Scene scene = cornell();
    for (double density : {20.0, 100.0}) {
        const Bake b = bake(scene, {.texels_per_metre = density, .size = 512, .padding = 2});
        EXPECT_EQ(b.layout.atlas_count, 1);
        expect_valid_layout(b.charts, b.layout, b.atlases);
        expect_no_flips(b.charts, b.layout);
        EXPECT_EQ(b.charts.split_charts, 0u);
        // One chart per face; the red wall's quad is not planar (1e-4 of its size, as the
        // mesher decides), so its two triangles are flattened by LSCM.
        ASSERT_EQ(b.charts.charts.size(), scene.polygons.size());
        for (const Chart& c : b.charts.charts)
            EXPECT_EQ(c.kind, c.object == "left_wall_red" ? ChartKind::curved : ChartKind::planar)
                << c.object;
        std::printf("Cornell box at %g texels/m, 512² atlas, padding 2: %zu charts, coverage "
                    "%.4f (%s)\n",
                    density, b.charts.charts.size(), b.layout.coverage[0],
                    packer_name(b.layout.packer));
        RecordProperty("coverage_" + std::to_string(int(density)), b.layout.coverage[0]);
    }
}

TEST(Atlas, SphereGivesValidAtlases) {
    const Bake b = bake(sphere_scene(), {.texels_per_metre = 64, .size = 512, .padding = 2});
    expect_valid_layout(b.charts, b.layout, b.atlases);
    expect_no_flips(b.charts, b.layout);
    std::printf("Sphere (16 × 32 faces, r = 1 m) at 64 texels/m: %zu charts, %d atlas(es), "
                "coverage %.4f (%s)\n",
                b.charts.charts.size(), b.layout.atlas_count, b.layout.coverage[0],
                packer_name(b.layout.packer));
}

TEST(Atlas, FullAtlasesOpenMore) {
    Scene scene;
    const auto white = add_material(scene, "white", Rgb(0.5, 0.5, 0.5));
    for (int i = 0; i < 12; ++i) // 12 separate 1 m² tiles, 20 × 20 texels each
        add_rect(scene, "tile" + std::to_string(i), white, {2.0 * i, 0, 0}, {1, 0, 0}, {0, 1, 0});
    const Bake b = bake(scene, {.texels_per_metre = 20, .size = 50, .padding = 2});
    // (50 − 2) / (20 + 2) = 2 tiles per row and column: 4 per atlas.
    EXPECT_EQ(b.layout.atlas_count, 3);
    expect_valid_layout(b.charts, b.layout, b.atlases);
}

// Right triangles fill half their bounding squares: our profile packer nests them, so it
// needs fewer atlases than rectangles would (25 squares of 20 + 2 texels per 128² atlas).
TEST(Atlas, ProfilePackerNestsTriangles) {
    Scene scene;
    const auto white = add_material(scene, "white", Rgb(0.5, 0.5, 0.5));
    for (int i = 0; i < 36; ++i) {
        Polygon p;
        p.vertices = {{3.0 * i, 0, 0}, {3.0 * i + 1, 0, 0}, {3.0 * i, 1, 0}};
        p.name = "triangle" + std::to_string(i);
        p.material = white;
        scene.polygons.push_back(p);
    }
    const Bake b = bake(scene, {.texels_per_metre = 20, .size = 128, .padding = 2});
    EXPECT_EQ(b.layout.packer, AtlasPacker::profiles);
    EXPECT_EQ(b.layout.atlas_count, 1);
    expect_valid_layout(b.charts, b.layout, b.atlases);
    expect_no_flips(b.charts, b.layout);
    std::printf("36 right triangles (1 m legs) at 20 texels/m in 128² atlases: %d atlas(es) "
                "(rectangles need 2), coverage of the first %.4f\n",
                b.layout.atlas_count, b.layout.coverage[0]);
}

TEST(Atlas, ChartTooLargeIsScaledDownToFit) {
    Scene scene;
    add_rect(scene, "floor", add_material(scene, "white", Rgb(0.5, 0.5, 0.5)), {0, 0, 0},
             {10, 0, 0}, {0, 4, 0});
    const Bake b = bake(scene, {.texels_per_metre = 100, .size = 256, .padding = 2});
    ASSERT_EQ(b.layout.atlas_count, 1);
    const ChartPlacement& p = b.layout.placements[0];
    EXPECT_LT(p.texels_per_metre, 100);
    EXPECT_NEAR(p.texels_per_metre, 252.0 / 10, 1e-6);
    EXPECT_EQ(std::max(p.rect.width, p.rect.height), 252);
    expect_valid_layout(b.charts, b.layout, b.atlases);
}

TEST(Atlas, BadSettingsAreConfigErrors) {
    const Charts none;
    const Context ctx = quiet_context();
    EXPECT_THROW(pack_atlases(none, {.texels_per_metre = 0}, ctx), ConfigError);
    EXPECT_THROW(pack_atlases(none, {.size = 0}, ctx), ConfigError);
    EXPECT_THROW(pack_atlases(none, {.size = 4, .padding = 2}, ctx), ConfigError);
    EXPECT_THROW(pack_atlases(none, {.padding = -1}, ctx), ConfigError);
}

void expect_same(const Bake& a, const Bake& b) {
    ASSERT_EQ(a.layout.atlas_count, b.layout.atlas_count);
    for (std::size_t c = 0; c < a.layout.placements.size(); ++c)
        for (std::size_t v = 0; v < a.layout.placements[c].texel_uv.size(); ++v) {
            EXPECT_EQ(a.layout.placements[c].texel_uv[v].x, b.layout.placements[c].texel_uv[v].x);
            EXPECT_EQ(a.layout.placements[c].texel_uv[v].y, b.layout.placements[c].texel_uv[v].y);
        }
    for (std::size_t i = 0; i < a.atlases.size(); ++i) {
        ASSERT_EQ(a.atlases[i].texels.size(), b.atlases[i].texels.size());
        for (std::size_t k = 0; k < a.atlases[i].texels.size(); ++k) {
            const Texel &s = a.atlases[i].texels[k], &t = b.atlases[i].texels[k];
            EXPECT_TRUE(s.x == t.x && s.y == t.y && s.chart == t.chart &&
                        s.centre.triangle == t.centre.triangle &&
                        s.centre.position == t.centre.position);
        }
    }
}

TEST(Atlas, DeterministicAcrossRunsAndThreadCounts) {
    Scene scene = cornell();
    const Scene sphere = sphere_scene();
    for (const Polygon& p : sphere.polygons) {
        scene.polygons.push_back(p);
        scene.polygons.back().material = 0;
    }
    const AtlasSettings settings{.texels_per_metre = 50, .size = 256, .padding = 2};
    const Bake one = bake(scene, settings, 1);
    expect_same(one, bake(scene, settings, 1));
    expect_same(one, bake(scene, settings, 2));
    expect_same(one, bake(scene, settings, 4));
}

} // namespace
} // namespace penumbra::test
