// Sensor grids (scene key `grids`): lattice points counted and placed by hand from the
// documented layout (a lattice centred in the outline's bounding box, points at least
// wall_offset from the outline), and one-line errors naming the key.

#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/scene_io.h"

#include "common/test_util.h"

namespace penumbra {
namespace {

/// A scene with an emitting square at z = 3, a 4 m × 6 m floor named "floor" at z = 0 (facing
/// up), an east wall at x = 4 facing -x (6 m × 3 m), plus \p extra keys.
std::string room_scene(const std::string& extra, const std::string& units = "m") {
    const double k = units == "mm" ? 1000 : 1;
    return fmt::format(R"json({{
  "units": "{}",
  "materials": {{"lamp": {{"emission": 1}}, "grey": {{"reflectance": 0.5}}}},
  "polygons": [
    {{"name": "lamp", "material": "lamp", "vertices": [[1,1,{k3}],[1,2,{k3}],[2,2,{k3}],[2,1,{k3}]]}},
    {{"name": "floor", "material": "grey",
      "vertices": [[0,0,0],[{k4},0,0],[{k4},{k6},0],[0,{k6},0]]}},
    {{"name": "east_wall", "material": "grey",
      "vertices": [[{k4},0,0],[{k4},0,{k3}],[{k4},{k6},{k3}],[{k4},{k6},0]]}}
  ]{}
}})json",
                       units, extra, fmt::arg("k3", 3 * k), fmt::arg("k4", 4 * k),
                       fmt::arg("k6", 6 * k));
}

Scene load(const std::string& grids, const std::string& units = "m") {
    return parse_scene(room_scene(",\n  \"grids\": " + grids, units), "scene.json", ".");
}

void expect_error(const std::string& grids, std::initializer_list<std::string> parts) {
    test::expect_one_line_input_error([&] { load(grids); }, parts, grids);
}

void expect_point(const Vec3& got, const Vec3& expected) {
    EXPECT_NEAR(got.x, expected.x, 1e-12);
    EXPECT_NEAR(got.y, expected.y, 1e-12);
    EXPECT_NEAR(got.z, expected.z, 1e-12);
}

// The office of ../shared/scenes/office: its 77 sensors of sensors_workplane.pts are the work
// plane at 0.85 m over the 4 m × 6 m floor, spacing 0.5 m, 0.5 m from the walls, x fastest.
TEST(SensorGrid, WorkPlaneOverANamedFloor) {
    const Scene scene = load(
        R"({"workplane": {"floor": "floor", "height": 0.85, "spacing": 0.5, "wall_offset": 0.5}})");
    ASSERT_EQ(scene.grids.size(), 1u);
    const SensorGrid& grid = scene.grids[0];
    EXPECT_EQ(grid.name, "workplane");
    EXPECT_EQ(grid.kind, GridKind::work_plane);
    EXPECT_EQ(grid.rows, 11);
    EXPECT_EQ(grid.columns, 7);
    ASSERT_EQ(scene.sensors.size(), 77u);
    for (int r = 0; r < 11; ++r)
        for (int c = 0; c < 7; ++c) {
            const std::uint32_t i = std::uint32_t(7 * r + c);
            EXPECT_EQ(grid.sensor_at(r, c), i);
            const Sensor& s = scene.sensors[i];
            EXPECT_EQ(s.position, Vec3(0.5 + 0.5 * c, 0.5 + 0.5 * r, 0.85)) << s.name;
            EXPECT_EQ(s.normal, Vec3(0, 0, 1));
            EXPECT_EQ(s.name, fmt::format("workplane:{}:{}", r, c));
            expect_point(grid.point(r, c), s.position);
        }
    EXPECT_EQ(grid.outline.size(), 4u);
}

// Units apply to every length of a grid; the inline sensors come first.
TEST(SensorGrid, LengthsInTheScenesUnits) {
    const Scene scene = parse_scene(room_scene(R"(,
  "sensors": [[100, 100, 0, 0, 0, 1]],
  "grids": {"g": {"floor": "floor", "height": 850, "spacing": 1000, "wall_offset": 1000}})",
                                               "mm"),
                                    "scene.json", ".");
    // x: 0, 1, ..., 4 m, kept 1 to 3; y: 0 to 6 m, kept 1 to 5.
    ASSERT_EQ(scene.sensors.size(), 1u + 3 * 5);
    expect_point(scene.sensors[1].position, {1, 1, 0.85});
    expect_point(scene.sensors.back().position, {3, 5, 0.85});
    EXPECT_EQ(scene.grids[0].sensor_at(0, 0), 1u);
}

// A side that is not a whole number of spacings leaves equal margins at both ends.
TEST(SensorGrid, LatticeIsCentredInTheOutline) {
    const Scene scene = load(R"({"g": {"floor": [[0,0,0],[4.2,0,0],[4.2,1.1,0],[0,1.1,0]],
                                        "height": 0, "spacing": 0.5}})");
    const SensorGrid& grid = scene.grids[0];
    EXPECT_EQ(grid.columns, 9); // 0.1, 0.6, ..., 4.1
    EXPECT_EQ(grid.rows, 3);    // 0.05, 0.55, 1.05
    ASSERT_EQ(scene.sensors.size(), 27u);
    expect_point(scene.sensors[0].position, {0.1, 0.05, 0});
    expect_point(scene.sensors[26].position, {4.1, 1.05, 0});
}

// An L-shaped floor: the notch holds no points, and the offset counts from every edge,
// the re-entrant corner (2, 2) included. Lattice 0..4 × 0..4 (spacing 1), offset 0.5: kept
// (1,1), (2,1), (3,1), (1,2), (1,3); (2,2) lies on the outline.
TEST(SensorGrid, ConcaveFloorAndItsReentrantCorner) {
    const Scene scene = load(R"({"l": {"floor": [[0,0,0],[4,0,0],[4,2,0],[2,2,0],[2,4,0],[0,4,0]],
                                        "height": 1, "spacing": 1, "wall_offset": 0.5}})");
    const SensorGrid& grid = scene.grids[0];
    EXPECT_EQ(grid.rows, 3);
    EXPECT_EQ(grid.columns, 3);
    ASSERT_EQ(scene.sensors.size(), 5u);
    const std::vector<Vec3> expected{{1, 1, 1}, {2, 1, 1}, {3, 1, 1}, {1, 2, 1}, {1, 3, 1}};
    for (std::size_t i = 0; i < expected.size(); ++i)
        expect_point(scene.sensors[i].position, expected[i]);
    EXPECT_FALSE(grid.sensor_at(1, 1)); // (2, 2)
    EXPECT_FALSE(grid.sensor_at(2, 2)); // (3, 3), in the notch
    EXPECT_EQ(grid.outline.size(), 6u);
}

// A floor of two triangles under one name: their shared diagonal is not an outline edge, so
// points on it stay and the offset counts from the square's sides only.
TEST(SensorGrid, TriangulatedFloorUnderOneName) {
    const Scene scene = parse_scene(R"json({
  "materials": {"lamp": {"emission": 1}, "grey": {"reflectance": 0.5}},
  "polygons": [
    {"name": "lamp", "material": "lamp", "vertices": [[0,0,3],[0,1,3],[1,1,3],[1,0,3]]},
    {"name": "tri", "material": "grey", "vertices": [[0,0,0],[2,0,0],[2,2,0]]},
    {"name": "tri", "material": "grey", "vertices": [[0,0,0],[2,2,0],[0,2,0]]}
  ],
  "grids": {"g": {"floor": "tri", "height": 0.5, "spacing": 0.5, "wall_offset": 0.5}}
})json",
                                    "scene.json", ".");
    // 0.5, 1.0, 1.5 in x and y: 9 points, (1, 1) and (0.5, 0.5) on the diagonal included.
    ASSERT_EQ(scene.sensors.size(), 9u);
    EXPECT_EQ(scene.grids[0].outline.size(), 4u);
    expect_point(scene.sensors[4].position, {1, 1, 0.5});
}

// Points on a wall face its front, at `distance` in front of it; columns run horizontally
// (up × normal = −y here) and rows upward. Lattice y 0..6, z 0..3 (spacing 1), offset 0.5.
TEST(SensorGrid, PointsOnAWall) {
    const Scene scene = load(
        R"({"east": {"wall": "east_wall", "distance": 0.1, "spacing": 1, "wall_offset": 0.5}})");
    const SensorGrid& grid = scene.grids[0];
    EXPECT_EQ(grid.kind, GridKind::wall);
    EXPECT_EQ(grid.columns, 5); // y = 5, 4, 3, 2, 1
    EXPECT_EQ(grid.rows, 2);    // z = 1, 2
    ASSERT_EQ(scene.sensors.size(), 10u);
    expect_point(grid.u, {0, -1, 0});
    expect_point(grid.v, {0, 0, 1});
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 5; ++c) {
            const Sensor& s = scene.sensors[*grid.sensor_at(r, c)];
            expect_point(s.position, {3.9, 5.0 - c, 1.0 + r});
            expect_point(s.normal, {-1, 0, 0});
        }
}

TEST(SensorGrid, ErrorsNameTheKey) {
    expect_error(R"({"g": {"floor": "flor", "height": 1, "spacing": 1}})",
                 {"scene.json", "grids.g.floor", "no polygon is named 'flor'", "floor"});
    expect_error(R"({"g": {"floor": "floor", "wall": "floor", "height": 1, "spacing": 1}})",
                 {"grids.g", "exactly one of 'floor'"});
    expect_error(R"({"g": {"wall": "east_wall", "height": 1, "spacing": 1}})",
                 {"grids.g.height", "only used with 'floor'"});
    expect_error(R"({"g": {"floor": "floor", "height": 1, "spacing": 0}})",
                 {"grids.g.spacing", "must be > 0"});
    expect_error(R"({"g": {"floor": "floor", "spacing": 1}})", {"grids.g.height", "missing"});
    expect_error(R"({"g": {"floor": "floor", "height": -1, "spacing": 1}})",
                 {"grids.g.height", ">= 0"});
    expect_error(R"({"g": {"floor": "east_wall", "height": 1, "spacing": 1}})",
                 {"grids.g.floor", "horizontal", "tilts 90°"});
    expect_error(R"({"g": {"floor": "floor", "height": 1, "spacing": 1, "wall_offset": 2.5}})",
                 {"grids.g", "no lattice point"});
    expect_error(R"({"g": {"floor": "floor", "height": 1, "spacing": 0.001}})",
                 {"grids.g.spacing", "larger spacing"});
    expect_error(R"({"a/b": {"floor": "floor", "height": 1, "spacing": 1}})",
                 {"grids.a/b", "names its files"});
    expect_error(R"({"g": {"floor": "floor", "height": 1, "spacing": 1, "offset": 1}})",
                 {"grids.g.offset", "unknown key"});
    expect_error(R"({"g": {"floor": [[0,0,0],[1,0,0]], "height": 1, "spacing": 1}})",
                 {"grids.g.floor", "at least 3 vertices"});
    expect_error(R"({"g": {"wall": {"name": "x"}, "spacing": 1}})",
                 {"grids.g.wall", "polygon name or an array"});
}

TEST(SensorGrid, PolygonsOfOneNameMustShareAPlane) {
    try {
        parse_scene(R"json({
  "materials": {"lamp": {"emission": 1}},
  "polygons": [
    {"name": "lamp", "material": "lamp", "vertices": [[0,0,3],[0,1,3],[1,1,3],[1,0,3]]},
    {"name": "lamp", "material": "lamp", "vertices": [[0,0,2],[0,1,2],[1,1,2],[1,0,2]]}
  ],
  "grids": {"g": {"wall": "lamp", "spacing": 0.5}}
})json",
                    "scene.json", ".");
        ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("grids.g.wall"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("one plane"), std::string::npos) << e.what();
    }
}

// validate_scene checks grids of scenes built in code: an index beyond the sensors.
TEST(SensorGrid, ValidateSceneChecksCodeBuiltGrids) {
    Scene scene = load(R"({"g": {"floor": "floor", "height": 1, "spacing": 1}})");
    scene.grids[0].sensors[0] = std::uint32_t(scene.sensors.size());
    EXPECT_THROW(validate_scene(scene), InputError);
}

} // namespace
} // namespace penumbra
