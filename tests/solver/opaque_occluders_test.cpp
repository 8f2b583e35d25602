// Occluder certificates count only opaque surfaces (solver/src/visibility/occluders.h): in a
// wall at x = 0 made of an opaque square and a pane of glazing beside it, a shaft through the
// opaque square is blocked and one through the pane is not, as through a hole.

#include <array>
#include <vector>

#include <gtest/gtest.h>

#include "core/mesh.h"
#include "hierarchy/hierarchy.h"
#include "visibility/occluders.h"

namespace penumbra {
namespace {

// Two unit squares in the plane x = 0, facing +x: y in [0, 1] (patch 0) and y in [1, 2]
// (patch 1), each of two triangles, with the opacity flags \p wall_opaque and \p pane_opaque.
RadiosityMesh wall_with_pane(bool wall_opaque, bool pane_opaque) {
    RadiosityMesh mesh;
    for (int square = 0; square < 2; ++square) {
        const auto base = std::uint32_t(mesh.positions.size());
        const float y = float(square);
        mesh.positions.insert(mesh.positions.end(),
                              {{0, y, 0}, {0, y + 1, 0}, {0, y + 1, 1}, {0, y, 1}});
        for (int k = 0; k < 4; ++k)
            mesh.vertex_patch.push_back(std::uint32_t(square));
        mesh.triangles.push_back({base, base + 1, base + 2});
        mesh.triangles.push_back({base, base + 2, base + 3});
        Patch patch;
        patch.polygon = patch.surface = patch.material = std::uint32_t(square);
        patch.normal = Vec3(1, 0, 0);
        const bool opaque = square == 0 ? wall_opaque : pane_opaque;
        patch.glazing = opaque ? std::nullopt : std::optional<ThinGlass>(ThinGlass{});
        mesh.patches.push_back(patch);
        for (int k = 0; k < 2; ++k) {
            mesh.element_patch.push_back(std::uint32_t(square));
            mesh.element_twin.push_back(-1);
            mesh.element_area.push_back(0.5);
            mesh.element_level.push_back(0);
        }
    }
    mesh.scene_diagonal = 3;
    return mesh;
}

// The corners of a 0.2 m cube centred at (x, y, 0.5).
std::vector<Vec3> cube(double x, double y) {
    std::vector<Vec3> out;
    for (int k = 0; k < 8; ++k)
        out.emplace_back(x + (k & 1 ? 0.1 : -0.1), y + (k & 2 ? 0.1 : -0.1),
                         0.5 + (k & 4 ? 0.1 : -0.1));
    return out;
}

struct Shafts {
    bool through_wall = false, through_pane = false;
};

Shafts blocked(bool wall_opaque, bool pane_opaque) {
    const RadiosityMesh mesh = wall_with_pane(wall_opaque, pane_opaque);
    const solver::Hierarchy h(mesh);
    const solver::OccluderPlanes planes(h);
    EXPECT_EQ(planes.size(), 1u); // the pane lies in its wall's plane
    const std::uint32_t plane = planes.plane_of_root(0);
    EXPECT_EQ(planes.plane_of_root(3), plane);
    return {planes.blocks(plane, cube(-1, 0.5), cube(1, 0.5)),
            planes.blocks(plane, cube(-1, 1.5), cube(1, 1.5))};
}

TEST(OpaqueOccluders, AllOpaqueBlocksBothShafts) {
    const Shafts s = blocked(true, true);
    EXPECT_TRUE(s.through_wall);
    EXPECT_TRUE(s.through_pane);
}

TEST(OpaqueOccluders, PaneIsAHoleInItsPlane) {
    const Shafts s = blocked(true, false);
    EXPECT_TRUE(s.through_wall);
    EXPECT_FALSE(s.through_pane);
}

TEST(OpaqueOccluders, PlaneOfGlazingOnlyBlocksNothing) {
    const Shafts s = blocked(false, false);
    EXPECT_FALSE(s.through_wall);
    EXPECT_FALSE(s.through_pane);
}

} // namespace
} // namespace penumbra
