// The lightmap fill's emitters per polygon (issue #29): a lamp behind a wall is left out of a
// polygon's list, and leaving it out changes no bit of the direct light gathered there.

#include <algorithm>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "common/bake_util.h"
#include "common/test_util.h"
#include "lightmap_emitters.h"
#include "raytrace/raytrace.h"
#include "solver/solver.h"

namespace penumbra {
namespace {

using test::add_material;
using test::add_rect;

// Two rooms' floors either side of a wall up to z = 1.2 (a box without a bottom, faces
// outwards), each under a lamp facing down at z = 1: no line joins a lamp to the other floor.
Scene two_rooms() {
    Scene s;
    const auto grey = add_material(s, "grey", Rgb(0.5f));
    const auto lamp = add_material(s, "lamp", Rgb(0.0f), Rgb(10.0f), false);
    const double x0 = 2.0, x1 = 2.1, y0 = -0.5, y1 = 2.5, h = 1.2;
    add_rect(s, "floor_a", grey, {0, 0, 0}, {x0, 0, 0}, {0, 2, 0});
    add_rect(s, "floor_b", grey, {x1, 0, 0}, {4 - x1, 0, 0}, {0, 2, 0});
    add_rect(s, "wall", grey, {x0, y0, h}, {x1 - x0, 0, 0}, {0, y1 - y0, 0});
    add_rect(s, "wall", grey, {x0, y0, 0}, {x1 - x0, 0, 0}, {0, 0, h});
    add_rect(s, "wall", grey, {x1, y0, 0}, {0, y1 - y0, 0}, {0, 0, h});
    add_rect(s, "wall", grey, {x1, y1, 0}, {x0 - x1, 0, 0}, {0, 0, h});
    add_rect(s, "wall", grey, {x0, y1, 0}, {0, y0 - y1, 0}, {0, 0, h});
    add_rect(s, "lamp_a", lamp, {0.5, 0.5, 1.0}, {0, 1, 0}, {1, 0, 0});
    add_rect(s, "lamp_b", lamp, {2.6, 0.5, 1.0}, {0, 1, 0}, {1, 0, 0});
    s.mesher.max_edge_length = 0.25;
    return s;
}

// The emitting elements of \p mesh on polygon \p polygon (increasing).
std::vector<std::uint32_t> emitters_on(const RadiosityMesh& mesh, std::uint32_t polygon) {
    std::vector<std::uint32_t> out;
    for (std::uint32_t e = 0; e < mesh.element_count(); ++e)
        if (mesh.patch_of(e).polygon == polygon && !mesh.patch_of(e).emission.is_black())
            out.push_back(e);
    return out;
}

TEST(LightmapEmitters, ALampBehindAWallIsLeftOutAndNoBitChanges) {
    const Scene scene = two_rooms();
    const app::BakeResult bake = test::bake(scene);
    const raytrace::EmbreeScene rt(bake.mesh);
    const Context ctx = test::quiet_context();
    const auto seen = app::emitters_seen_by_polygons(bake.mesh, bake.mesh, rt, ctx);
    // Polygons in scene order: floor_a 0, floor_b 1, the wall's five faces 2–6, lamps 7, 8.
    const std::vector<std::uint32_t> lamp_a = emitters_on(bake.mesh, 7),
                                     lamp_b = emitters_on(bake.mesh, 8);
    ASSERT_FALSE(lamp_a.empty());
    ASSERT_FALSE(lamp_b.empty());
    EXPECT_EQ(seen[0], lamp_a);
    EXPECT_EQ(seen[1], lamp_b);
    // The wall's top faces up, behind both lamps, and its ends face away from them; its
    // sides each see the lamp of their room.
    for (std::uint32_t p : {2u, 3u, 5u})
        EXPECT_TRUE(seen[p].empty()) << "polygon " << p;
    EXPECT_EQ(seen[4], lamp_b);
    EXPECT_EQ(seen[6], lamp_a);

    // Points over both floors: gathered from each floor's list or from every emitter, the
    // same bits (the other room's lamp is wholly hidden at every point).
    std::vector<Vec3> points, normals;
    std::vector<std::uint32_t> lists;
    for (double x = 0.05; x < 4; x += 0.1)
        for (double y = 0.05; y < 2; y += 0.15) {
            if (x > 1.95 && x < 2.15)
                continue;
            points.push_back({x, y, 1e-4});
            normals.push_back({0, 0, 1});
            lists.push_back(x < 2 ? 0 : 1);
        }
    const auto all = solver::direct_irradiance_at(scene, bake.mesh, rt, points, normals, ctx);
    solver::DirectLightOptions narrowed;
    narrowed.list_of_point = lists;
    narrowed.emitter_lists = seen;
    const auto listed =
        solver::direct_irradiance_at(scene, bake.mesh, rt, points, normals, ctx, narrowed);
    ASSERT_EQ(all.size(), listed.size());
    EXPECT_EQ(std::memcmp(all.data(), listed.data(), all.size() * sizeof(Rgb)), 0);
    EXPECT_TRUE(std::all_of(all.begin(), all.end(), [](const Rgb& e) { return e.g > 0; }));
}

} // namespace
} // namespace penumbra
