// Charts: triangulation of concave polygons, planar charts without distortion, LSCM on
// curved patches without flips, imported UV sets.

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "core/error.h"
#include "lightmap/charts.h"
#include "lightmap/shapes.h"

namespace penumbra::test {
namespace {

using namespace lightmap;

double uv_area(const Chart& chart, const ChartTriangle& t) {
    const Vec2 a = chart.vertices[t.vertices[0]].uv, b = chart.vertices[t.vertices[1]].uv,
               c = chart.vertices[t.vertices[2]].uv;
    return 0.5 * ((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
}

double triangle_area(const Chart& chart, const ChartTriangle& t) {
    const Vec3 a = chart.vertices[t.vertices[0]].position;
    return 0.5 * length(cross(chart.vertices[t.vertices[1]].position - a,
                              chart.vertices[t.vertices[2]].position - a));
}

TEST(Charts, ConcavePolygonIsOnePlanarChartOfItsArea) {
    Scene scene;
    const auto white = add_material(scene, "white", Rgb(0.5, 0.5, 0.5));
    // An L of three unit squares in the plane x + y + z = 1 rotated out of the axes.
    const Vec3 u = normalize(Vec3(1, -1, 0)), v = normalize(Vec3(1, 1, -2));
    Polygon l;
    for (const auto& [x, y] : {std::pair{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}})
        l.vertices.push_back(u * double(x) + v * double(y));
    l.name = "l";
    l.material = white;
    scene.polygons.push_back(l);
    const Charts charts = build_charts(scene, {}, quiet_context());
    ASSERT_EQ(charts.charts.size(), 1u);
    const Chart& chart = charts.charts[0];
    EXPECT_EQ(chart.kind, ChartKind::planar);
    EXPECT_EQ(chart.triangles.size(), 4u); // six corners
    EXPECT_NEAR(chart.area_m2(), 3.0, 1e-12);
    for (const ChartTriangle& t : chart.triangles) {
        EXPECT_GT(uv_area(chart, t), 0);
        EXPECT_NEAR(uv_area(chart, t), triangle_area(chart, t), 1e-12);
    }
}

TEST(Charts, RoomWallsArePlanarChartsPerObject) {
    Scene scene;
    add_room(scene, {0, 0, 0}, {4, 3, 2.5}, add_material(scene, "white", Rgb(0.5, 0.5, 0.5)));
    const Charts charts = build_charts(scene, {}, quiet_context());
    ASSERT_EQ(charts.charts.size(), 6u);
    const char* names[] = {"floor", "ceiling", "wall_y0", "wall_y1", "wall_x0", "wall_x1"};
    for (std::size_t i = 0; i < 6; ++i) {
        EXPECT_EQ(charts.charts[i].object, names[i]);
        EXPECT_EQ(charts.charts[i].kind, ChartKind::planar);
    }
    EXPECT_EQ(charts.split_charts, 0u);
}

TEST(Charts, CoplanarPolygonsOfOneObjectShareAChart) {
    Scene scene;
    const auto white = add_material(scene, "white", Rgb(0.5, 0.5, 0.5));
    for (int i = 0; i < 3; ++i) // three tiles in a row, sharing edges
        add_rect(scene, "floor", white, {double(i), 0, 0}, {1, 0, 0}, {0, 1, 0});
    add_rect(scene, "other", white, {3, 0, 0}, {1, 0, 0}, {0, 1, 0}); // another object
    const Charts charts = build_charts(scene, {}, quiet_context());
    ASSERT_EQ(charts.charts.size(), 2u);
    EXPECT_EQ(charts.charts[0].triangles.size(), 6u);
    EXPECT_EQ(charts.charts[0].vertices.size(), 8u); // welded
    EXPECT_NEAR(charts.charts[0].area_m2(), 3.0, 1e-12);
}

TEST(Charts, WallPiecesAroundAWindowAreOneChart) {
    // A 4 × 3 m wall cut around a 1 × 1 m window: the pieces meet at T-junctions.
    Scene scene;
    const auto white = add_material(scene, "white", Rgb(0.5, 0.5, 0.5));
    const Vec3 x(1, 0, 0), z(0, 0, 1);
    add_rect(scene, "wall", white, {0, 0, 0}, x * 4, z);  // below the window
    add_rect(scene, "wall", white, {0, 0, 2}, x * 4, z);  // above
    add_rect(scene, "wall", white, {0, 0, 1}, x, z);      // left
    add_rect(scene, "wall", white, {2, 0, 1}, x * 2, z);  // right
    add_rect(scene, "other", white, {0, 0, 3}, x * 4, z); // another object on top
    const Charts charts = build_charts(scene, {}, quiet_context());
    ASSERT_EQ(charts.charts.size(), 2u);
    EXPECT_EQ(charts.charts[0].object, "wall");
    EXPECT_EQ(charts.charts[0].kind, ChartKind::planar);
    EXPECT_NEAR(charts.charts[0].area_m2(), 11.0, 1e-12);
}

TEST(Charts, BoxFacesAreSeparateCharts) {
    // Faces at 90° exceed the 40° normal deviation: one planar chart each.
    Scene scene;
    add_room(scene, {0, 0, 0}, {1, 1, 1}, add_material(scene, "white", Rgb(0.5, 0.5, 0.5)));
    for (Polygon& p : scene.polygons)
        p.name = "box";
    const Charts charts = build_charts(scene, {}, quiet_context());
    ASSERT_EQ(charts.charts.size(), 6u);
    for (const Chart& c : charts.charts)
        EXPECT_EQ(c.kind, ChartKind::planar);
}

// LSCM of a developable patch is an isometry up to scale; charts scale to their 3D area, so
// every edge keeps its length.
TEST(Charts, CylinderPatchFlattensWithoutDistortion) {
    Scene scene;
    add_cylinder_patch(scene, "cylinder", add_material(scene, "white", Rgb(0.5, 0.5, 0.5)), 1.0,
                       2.0, 70 * k_pi / 180, 14);
    const Charts charts = build_charts(scene, {}, quiet_context());
    ASSERT_GE(charts.charts.size(), 2u); // 70° > the 40° deviation from any seed facet
    std::size_t curved = 0;
    for (const Chart& chart : charts.charts) {
        curved += chart.kind == ChartKind::curved;
        for (const ChartTriangle& t : chart.triangles) {
            EXPECT_GT(uv_area(chart, t), 0);
            for (int k = 0; k < 3; ++k) {
                const ChartVertex& a = chart.vertices[t.vertices[std::size_t(k)]];
                const ChartVertex& b = chart.vertices[t.vertices[std::size_t((k + 1) % 3)]];
                const double uv_length = std::hypot(a.uv.x - b.uv.x, a.uv.y - b.uv.y);
                EXPECT_NEAR(uv_length, length(a.position - b.position), 1e-6);
            }
        }
    }
    EXPECT_GE(curved, 1u);
}

TEST(Charts, SphereChartsHaveNoFlipsAndCoverTheSphere) {
    Scene scene;
    add_sphere(scene, "sphere", add_material(scene, "white", Rgb(0.5, 0.5, 0.5)), {0, 0, 0}, 1.0,
               16, 32);
    const Charts charts = build_charts(scene, {}, quiet_context());
    double area = 0;
    std::size_t triangles = 0, curved = 0;
    for (const Chart& chart : charts.charts) {
        EXPECT_EQ(chart.object, "sphere");
        EXPECT_NE(chart.kind, ChartKind::imported);
        curved += chart.kind == ChartKind::curved;
        area += chart.area_m2();
        triangles += chart.triangles.size();
        for (const ChartTriangle& t : chart.triangles)
            EXPECT_GT(uv_area(chart, t), 0);
    }
    EXPECT_EQ(triangles, 32u * 2 + 32u * 14 * 2); // caps and quads
    // The polyhedron's area, computed from its faces directly.
    double expected = 0;
    for (const Polygon& p : scene.polygons)
        for (std::size_t i = 1; i + 1 < p.vertices.size(); ++i)
            expected += 0.5 * length(cross(p.vertices[i] - p.vertices[0],
                                           p.vertices[i + 1] - p.vertices[0]));
    EXPECT_NEAR(area, expected, 1e-9 * expected);
    // A facet that no neighbour within the deviation joins stays a planar chart.
    EXPECT_GE(curved, charts.charts.size() / 2);
    EXPECT_LE(charts.charts.size(), 40u) << "the sphere falls apart into small charts";
}

// The largest number of triangles of the chart that hold one point strictly inside, over a
// grid of points across its uv bounding box: 1 for a chart without overlaps.
int most_layers(const Chart& chart, int grid) {
    Vec2 lo{1e300, 1e300}, hi{-1e300, -1e300};
    for (const ChartVertex& v : chart.vertices) {
        lo = {std::min(lo.x, v.uv.x), std::min(lo.y, v.uv.y)};
        hi = {std::max(hi.x, v.uv.x), std::max(hi.y, v.uv.y)};
    }
    int most = 0;
    for (int j = 0; j < grid; ++j)
        for (int i = 0; i < grid; ++i) {
            const Vec2 p{lo.x + (hi.x - lo.x) * (i + 0.5) / grid,
                         lo.y + (hi.y - lo.y) * (j + 0.5) / grid};
            int layers = 0;
            for (const ChartTriangle& t : chart.triangles) {
                bool inside = true;
                for (int k = 0; k < 3; ++k) {
                    const Vec2 a = chart.vertices[t.vertices[std::size_t(k)]].uv;
                    const Vec2 b = chart.vertices[t.vertices[std::size_t((k + 1) % 3)]].uv;
                    inside = inside && (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x) > 1e-9;
                }
                layers += inside;
            }
            most = std::max(most, layers);
        }
    return most;
}

// A ramp winding one and a half times around a pole: its normals stay within a few degrees
// of vertical, so it grows into one chart, whose flattening overlaps itself; splitting must
// end in charts that do not.
TEST(Charts, SelfOverlappingSpiralIsSplitUntilValid) {
    Scene scene;
    const auto white = add_material(scene, "white", Rgb(0.5, 0.5, 0.5));
    const int segments = 108;
    for (int s = 0; s < segments; ++s) {
        auto at = [](double r, int step) {
            const double angle = 3 * k_pi * step / 108;
            return Vec3(r * std::cos(angle), r * std::sin(angle), 0.2 * angle / (2 * k_pi));
        };
        Polygon p;
        p.vertices = {at(1, s), at(2, s), at(2, s + 1), at(1, s + 1)};
        p.name = "ramp";
        p.material = white;
        scene.polygons.push_back(p);
    }
    const Charts charts = build_charts(scene, {}, quiet_context());
    EXPECT_GE(charts.split_charts, 1u);
    EXPECT_GE(charts.charts.size(), 2u);
    for (const Chart& chart : charts.charts) {
        for (const ChartTriangle& t : chart.triangles)
            EXPECT_GT(uv_area(chart, t), 0);
        EXPECT_LE(most_layers(chart, 200), 1);
    }
}

TEST(Charts, ImportedUvSetIsOneChartScaledToItsArea) {
    Scene scene;
    const auto white = add_material(scene, "white", Rgb(0.5, 0.5, 0.5));
    add_rect(scene, "panel", white, {0, 0, 0}, {2, 0, 0}, {0, 1, 0});
    add_rect(scene, "panel", white, {0, 2, 0}, {2, 0, 0}, {0, 1, 0}); // not touching
    scene.polygons[0].lightmap_uv = {{0, 1}, {1, 1}, {1, 0.6}, {0, 0.6}};
    scene.polygons[1].lightmap_uv = {{0, 0.4}, {1, 0.4}, {1, 0}, {0, 0}};
    const Charts charts = build_charts(scene, {}, quiet_context());
    ASSERT_EQ(charts.charts.size(), 1u);
    const Chart& chart = charts.charts[0];
    EXPECT_EQ(chart.kind, ChartKind::imported);
    // v runs down, so the counter-clockwise faces are clockwise (negative) in uv: kept.
    for (const ChartTriangle& t : chart.triangles)
        EXPECT_LT(uv_area(chart, t), 0);
    double uv = 0;
    for (const ChartTriangle& t : chart.triangles)
        uv += std::abs(uv_area(chart, t));
    EXPECT_NEAR(uv, 4.0, 1e-12);
    // uv scale s with s² · 0.8 = 4: the panel's corner (2, 0) sits at s · (1, 1).
    const double s = std::sqrt(4.0 / 0.8);
    EXPECT_NEAR(chart.vertices[1].uv.x, s, 1e-12);
    EXPECT_NEAR(chart.vertices[1].uv.y, s, 1e-12);
}

TEST(Charts, OverlappingImportedUvFallsBackToGeneratedCharts) {
    Scene scene;
    const auto white = add_material(scene, "white", Rgb(0.5, 0.5, 0.5));
    add_rect(scene, "panel", white, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    add_rect(scene, "panel", white, {0, 2, 0}, {1, 0, 0}, {0, 1, 0});
    for (Polygon& p : scene.polygons)
        p.lightmap_uv = {{0, 1}, {1, 1}, {1, 0}, {0, 0}}; // both on the same square
    const Charts charts = build_charts(scene, {}, quiet_context());
    ASSERT_EQ(charts.charts.size(), 2u);
    for (const Chart& c : charts.charts)
        EXPECT_EQ(c.kind, ChartKind::planar);
}

TEST(Charts, BadSettingsAreConfigErrors) {
    Scene scene;
    ChartSettings settings;
    settings.max_normal_deviation_deg = 90;
    EXPECT_THROW(build_charts(scene, settings, quiet_context()), ConfigError);
    settings = {};
    settings.weld_tolerance_m = -1;
    EXPECT_THROW(build_charts(scene, settings, quiet_context()), ConfigError);
}

} // namespace
} // namespace penumbra::test
