#include "mesher/mesher.h"

#include <map>
#include <utility>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "core/error.h"

namespace penumbra {
namespace {

using test::add_material;
using test::add_rect;

double max_edge_length(const RadiosityMesh& mesh) {
    double longest = 0;
    for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k)
            longest = std::max(longest, length(mesh.vertex(t[k]) - mesh.vertex(t[(k + 1) % 3])));
    return longest;
}

double patch_area(const RadiosityMesh& mesh, std::uint32_t patch) {
    double a = 0;
    for (std::size_t e = 0; e < mesh.element_count(); ++e)
        if (mesh.element_patch[e] == patch)
            a += mesh.element_area[e];
    return a;
}

// Conformity: inside a patch every edge is used by one triangle (boundary) or by two with
// opposite orientation (interior). A T-vertex would leave an unmatched half-edge whose length
// differs from the outline's, so the boundary length must equal the polygon's perimeter.
void expect_conforming(const RadiosityMesh& mesh, std::uint32_t patch, double perimeter) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> half_edges;
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
        if (mesh.element_patch[e] != patch)
            continue;
        const auto& t = mesh.triangles[e];
        for (int k = 0; k < 3; ++k)
            ++half_edges[{t[k], t[(k + 1) % 3]}];
    }
    double boundary = 0;
    for (const auto& [edge, count] : half_edges) {
        EXPECT_EQ(count, 1) << "half-edge used twice";
        if (!half_edges.count({edge.second, edge.first}))
            boundary += length(mesh.vertex(edge.first) - mesh.vertex(edge.second));
    }
    EXPECT_NEAR(boundary, perimeter, 1e-5 * perimeter);
}

TEST(Mesher, SquareBecomesTwoSidedGrid) {
    Scene scene;
    auto m = add_material(scene, "white", Rgb(0.5f));
    add_rect(scene, "floor", m, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    scene.mesher.max_edge_length = 0.25;
    RadiosityMesh mesh = mesher::build_mesh(scene, test::quiet_context());
    ASSERT_EQ(mesh.patches.size(), 2u);
    EXPECT_EQ(mesh.element_count(), 2u * 32u); // 4 × 4 cells, 2 triangles each, 2 sides
    EXPECT_EQ(mesh.geometry_elements.size(), 32u);
    EXPECT_NEAR(patch_area(mesh, 0), 1.0, 1e-9);
    EXPECT_NEAR(patch_area(mesh, 1), 1.0, 1e-9);
    EXPECT_NEAR(mesh.patches[0].normal.z, 1.0, 1e-12);
    EXPECT_NEAR(mesh.patches[1].normal.z, -1.0, 1e-12);
    EXPECT_LE(max_edge_length(mesh), 0.25 * std::sqrt(2.0) + 1e-9);
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
        ASSERT_GE(mesh.element_twin[e], 0);
        EXPECT_EQ(mesh.element_twin[std::size_t(mesh.element_twin[e])], std::int32_t(e));
        // Winding agrees with the side's normal.
        const auto& t = mesh.triangles[e];
        Vec3 n = cross(mesh.vertex(t[1]) - mesh.vertex(t[0]), mesh.vertex(t[2]) - mesh.vertex(t[0]));
        EXPECT_GT(dot(n, mesh.patch_of(std::uint32_t(e)).normal), 0);
    }
    expect_conforming(mesh, 0, 4.0);
    expect_conforming(mesh, 1, 4.0);
}

TEST(Mesher, OneSidedMaterialHasNoBack) {
    Scene scene;
    auto m = add_material(scene, "panel", Rgb(0.5f), Rgb(1.0f), /*two_sided=*/false);
    add_rect(scene, "panel", m, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    scene.mesher.max_edge_length = 0.5;
    RadiosityMesh mesh = mesher::build_mesh(scene, test::quiet_context());
    EXPECT_EQ(mesh.patches.size(), 1u);
    EXPECT_EQ(mesh.element_count(), 8u);
    EXPECT_NEAR(mesh.patches[0].emission.r, k_pi, 1e-6); // E = πL
}

TEST(Mesher, ConcavePolygonIsClippedAndRefined) {
    Scene scene;
    auto m = add_material(scene, "white", Rgb(0.5f), {}, false);
    Polygon l_shape; // an L of area 3, perimeter 8
    l_shape.name = "L";
    l_shape.material = m;
    l_shape.vertices = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
    scene.polygons.push_back(l_shape);
    scene.mesher.max_edge_length = 0.3;
    RadiosityMesh mesh = mesher::build_mesh(scene, test::quiet_context());
    EXPECT_NEAR(patch_area(mesh, 0), 3.0, 1e-9);
    EXPECT_LE(max_edge_length(mesh), 0.3 + 1e-9);
    expect_conforming(mesh, 0, 8.0);
}

TEST(Mesher, TriangleSplitsIntoCongruentTriangles) {
    Scene scene;
    auto m = add_material(scene, "white", Rgb(0.5f), {}, false);
    Polygon tri;
    tri.material = m;
    tri.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    scene.polygons.push_back(tri);
    scene.mesher.max_edge_length = 0.5;
    RadiosityMesh mesh = mesher::build_mesh(scene, test::quiet_context());
    // Longest edge √2 → k = 3 → 9 triangles of area 1/18.
    ASSERT_EQ(mesh.element_count(), 9u);
    for (double a : mesh.element_area)
        EXPECT_NEAR(a, 1.0 / 18.0, 1e-7); // positions are stored as float
    expect_conforming(mesh, 0, 2.0 + std::sqrt(2.0));
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
    // Vertices are not shared across the crease.
    EXPECT_EQ(mesh.vertex_count(), 6u);
    EXPECT_EQ(mesh.vertex(mesh.triangles[0][0]), Vec3(0, 0, 0));
    EXPECT_EQ(mesh.vertex(mesh.triangles[1][0]), Vec3(0, 0, 0));
}

} // namespace
} // namespace penumbra
