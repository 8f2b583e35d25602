// Basic surface meshing: sides and twins, areas, size and angle bounds, conformity, fans.

#include "mesher/mesher.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/test_util.h"
#include "core/error.h"
#include "core/scene_io.h"
#include "mesher/mesh_checks.h"

namespace penumbra {
namespace {

using test::add_material;
using test::add_rect;

TEST(Mesher, SquareBecomesTwoSidedMesh) {
    Scene scene;
    auto m = add_material(scene, "white", Rgb(0.5f));
    add_rect(scene, "floor", m, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    scene.mesher.max_edge_length = 0.25;
    RadiosityMesh mesh = mesher::build_mesh(scene, test::quiet_context());
    ASSERT_EQ(mesh.patches.size(), 2u);
    EXPECT_EQ(mesh.element_count() % 2, 0u);
    EXPECT_EQ(mesh.geometry_elements.size(), mesh.element_count() / 2);
    EXPECT_GE(mesh.element_count() / 2, 32u); // at least the 4 × 4 × 2 triangles of a grid
    EXPECT_LE(mesh.element_count() / 2, 64u);
    EXPECT_NEAR(test::patch_area(mesh, 0), 1.0, 1e-9);
    EXPECT_NEAR(test::patch_area(mesh, 1), 1.0, 1e-9);
    EXPECT_NEAR(mesh.patches[0].normal.z, 1.0, 1e-12);
    EXPECT_NEAR(mesh.patches[1].normal.z, -1.0, 1e-12);
    EXPECT_LE(test::longest_edge(mesh), 0.25 * std::sqrt(2.0) + 1e-9);
    EXPECT_GE(test::smallest_angle_deg(mesh, 0), 20.0);
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
        ASSERT_GE(mesh.element_twin[e], 0);
        EXPECT_EQ(mesh.element_twin[std::size_t(mesh.element_twin[e])], std::int32_t(e));
        // Winding agrees with the side's normal.
        const auto& t = mesh.triangles[e];
        Vec3 n =
            cross(mesh.vertex(t[1]) - mesh.vertex(t[0]), mesh.vertex(t[2]) - mesh.vertex(t[0]));
        EXPECT_GT(dot(n, mesh.patch_of(std::uint32_t(e)).normal), 0);
    }
    test::expect_conforming(mesh, 0, 4.0);
    test::expect_conforming(mesh, 1, 4.0);
    ASSERT_EQ(mesh.surfaces.size(), 1u);
    EXPECT_NEAR(mesh.surfaces[0].area_m2, 1.0, 1e-12);
    EXPECT_EQ(mesh.surfaces[0].hidden_front_m2, 0.0);
}

TEST(Mesher, OneSidedMaterialHasNoBack) {
    Scene scene;
    auto m = add_material(scene, "panel", Rgb(0.5f), Rgb(1.0f), /*two_sided=*/false);
    add_rect(scene, "panel", m, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    scene.mesher.max_edge_length = 0.5;
    RadiosityMesh mesh = mesher::build_mesh(scene, test::quiet_context());
    EXPECT_EQ(mesh.patches.size(), 1u);
    EXPECT_EQ(mesh.geometry_elements.size(), mesh.element_count());
    for (std::int32_t twin : mesh.element_twin)
        EXPECT_EQ(twin, -1);
    EXPECT_NEAR(mesh.patches[0].emission.r, k_pi, 1e-6); // E = πL
}

TEST(Mesher, ConcavePolygonIsRefined) {
    Scene scene;
    auto m = add_material(scene, "white", Rgb(0.5f), {}, false);
    Polygon l_shape; // an L of area 3, perimeter 8
    l_shape.name = "L";
    l_shape.material = m;
    l_shape.vertices = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
    scene.polygons.push_back(l_shape);
    scene.mesher.max_edge_length = 0.3;
    RadiosityMesh mesh = mesher::build_mesh(scene, test::quiet_context());
    EXPECT_NEAR(test::patch_area(mesh, 0), 3.0, 1e-9);
    EXPECT_LE(test::longest_edge(mesh), 0.3 * std::sqrt(2.0) + 1e-9);
    EXPECT_GE(test::smallest_angle_deg(mesh, 0), 20.0);
    test::expect_conforming(mesh, 0, 8.0);
}

TEST(Mesher, TriangleIsRefinedToTheSizeBound) {
    Scene scene;
    auto m = add_material(scene, "white", Rgb(0.5f), {}, false);
    Polygon tri;
    tri.material = m;
    tri.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    scene.polygons.push_back(tri);
    scene.mesher.max_edge_length = 0.2;
    RadiosityMesh mesh = mesher::build_mesh(scene, test::quiet_context());
    EXPECT_NEAR(test::patch_area(mesh, 0), 0.5, 1e-9);
    EXPECT_LE(test::longest_edge(mesh), 0.2 * std::sqrt(2.0) + 1e-9);
    EXPECT_GE(test::smallest_angle_deg(mesh, 0), 20.0);
    test::expect_conforming(mesh, 0, 2.0 + std::sqrt(2.0));
}

// A sliver whose short edge is below the constraint merge distance (1 % of the element size:
// 4 mm here) keeps its whole area: the outline is the geometry, and its own vertices never
// split its other edges. A UV sphere's quads by the poles are such slivers; 22 % of their area
// was lost (an outline vertex split the opposite long edge, and the parity of the inside
// flipped between them).
TEST(Mesher, SliverBelowTheMergeDistanceKeepsItsArea) {
    Scene scene;
    auto m = add_material(scene, "white", Rgb(0.5f), {}, false);
    add_rect(scene, "floor", m, {-4, -4, 0}, {8, 0, 0}, {0, 8, 0});
    Polygon sliver; // a trapezoid: parallel sides 2 mm and 4 mm, 33 mm apart
    sliver.name = "sliver";
    sliver.material = m;
    sliver.vertices = {{0, 0, 1}, {0.033, -0.002, 1}, {0.033, 0.002, 1}, {0, 0.001, 1}};
    scene.polygons.push_back(sliver);
    scene.mesher.max_edge_length = 0.4;
    RadiosityMesh mesh = mesher::build_mesh(scene, test::quiet_context());
    ASSERT_EQ(mesh.patches.size(), 2u);
    const double exact = 0.5 * (0.001 + 0.004) * 0.033;
    EXPECT_NEAR(test::patch_area(mesh, 1), exact, 1e-9 * exact + 1e-15);
    EXPECT_NEAR(test::patch_area(mesh, 0), 64.0, 1e-9);
}

TEST(Mesher, NonPlanarQuadIsFanTriangulatedFromFirstVertex) {
    Scene scene;
    auto m = add_material(scene, "red", Rgb(0.5f), {}, false);
    Polygon quad; // the fourth vertex lifted by 3 % of the size
    quad.material = m;
    quad.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.03}, {0, 1, 0}};
    scene.polygons.push_back(quad);
    scene.mesher.max_edge_length = 2.0;
    RadiosityMesh mesh = mesher::build_mesh(scene, test::quiet_context());
    ASSERT_EQ(mesh.patches.size(), 2u); // fan triangles (0,1,2) and (0,2,3)
    EXPECT_NE(mesh.patches[0].surface, mesh.patches[1].surface);
    ASSERT_EQ(mesh.element_count(), 2u);
    // Vertices are not shared across the crease, and both triangles have the diagonal from
    // the first vertex.
    EXPECT_EQ(mesh.vertex_count(), 6u);
    for (const auto& t : mesh.triangles) {
        int on_diagonal = 0;
        for (std::uint32_t v : t)
            on_diagonal += length(mesh.vertex(v) - Vec3(0, 0, 0)) < 1e-6 ||
                           length(mesh.vertex(v) - Vec3(1, 1, 0.03)) < 1e-6;
        EXPECT_EQ(on_diagonal, 2);
    }
}

TEST(Mesher, ElementBudgetCoarsensTheMesh) {
    Scene scene;
    auto m = add_material(scene, "white", Rgb(0.5f), {}, false);
    add_rect(scene, "floor", m, {0, 0, 0}, {4, 0, 0}, {0, 4, 0});
    scene.mesher.max_edge_length = 0.05;
    scene.mesher.element_budget = 2000;
    RadiosityMesh mesh = mesher::build_mesh(scene, test::quiet_context());
    EXPECT_LE(mesh.element_count(), 2000u);
    EXPECT_GE(mesh.element_count(), 1000u);
    EXPECT_NEAR(test::patch_area(mesh, 0), 16.0, 1e-9);
}

Scene load_with_mesher(const std::string& mesher_json) {
    const std::string dir = test::temp_dir("mesher-keys");
    const std::string path = dir + "/scene.json";
    std::ofstream(path) << R"({"units": "mm", "materials": {"lamp": {"emission": 1}},
        "polygons": [{"material": "lamp", "vertices": [[0,0,0],[1000,0,0],[1000,1000,0]]}],
        "mesher": )" << mesher_json
                        << "}";
    return load_scene(path);
}

TEST(MesherSettings, SceneKeysAreParsedInSceneUnits) {
    const Scene scene = load_with_mesher(
        R"({"contact_tolerance": 3, "split_contacts": false, "element_budget": 5000,
            "discontinuity": {"enabled": false, "max_order": 1}})");
    ASSERT_TRUE(scene.mesher.contact_tolerance.has_value());
    EXPECT_NEAR(*scene.mesher.contact_tolerance, 0.003, 1e-15);
    EXPECT_FALSE(scene.mesher.split_contacts);
    EXPECT_EQ(scene.mesher.element_budget, 5000);
    EXPECT_FALSE(scene.mesher.discontinuity.enabled);
    EXPECT_EQ(scene.mesher.discontinuity.max_order, 1);
    const Scene defaults = load_with_mesher("{}");
    EXPECT_FALSE(defaults.mesher.contact_tolerance.has_value());
    EXPECT_TRUE(defaults.mesher.split_contacts);
    EXPECT_EQ(defaults.mesher.discontinuity.max_order, 2);
}

TEST(MesherSettings, BadKeysAreOneLineErrors) {
    auto message = [](const std::string& json) {
        try {
            load_with_mesher(json);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message(R"({"discontinuity": {"max_order": 3}})")
                  .find("'mesher.discontinuity.max_order': expected an integer in [0, 2]"),
              std::string::npos);
    EXPECT_NE(message(R"({"discontinuity": {"order": 1}})").find("unknown key 'order'"),
              std::string::npos);
    EXPECT_NE(message(R"({"contact_tolerance": -1})").find("'mesher.contact_tolerance'"),
              std::string::npos);
    EXPECT_NE(message(R"({"element_budget": 1.5})").find("'mesher.element_budget'"),
              std::string::npos);
}

} // namespace
} // namespace penumbra
