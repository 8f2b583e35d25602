// The enclosure test's source culling with tessellated blockers (mesher/src/hidden.cpp):
// coplanar surfaces that tile a convex region block sources as one; a tiled face with a hole
// does not, nor does glazing.

#include <gtest/gtest.h>

#include "hidden.h"
#include "surface_bvh.h"
#include "surfaces.h"

namespace penumbra::mesher {
namespace {

// Adds the parallelogram origin + [0, 1]·u + [0, 1]·v (normal along u × v) split into k × k
// quads, leaving out the quads [hole_lo, hole_hi) in both directions.
void add_tiles(std::vector<Surface>& out, const Vec3& origin, const Vec3& u, const Vec3& v, int k,
               int hole_lo = 0, int hole_hi = 0) {
    for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j) {
            if (i >= hole_lo && i < hole_hi && j >= hole_lo && j < hole_hi)
                continue;
            const Vec3 a = origin + u * (double(i) / k) + v * (double(j) / k);
            const Vec3 du = u / double(k), dv = v / double(k);
            Surface s;
            ASSERT_TRUE(make_surface({a, a + du, a + du + dv, a + dv}, s));
            s.id = std::uint32_t(out.size());
            out.push_back(s);
        }
}

// A closed unit box, faces pointing out, each face tiled k × k; the top face without its
// middle quad when \p hole (k odd): a hole of 1/k. An emitting panel faces down above the box
// at z = 3, off the box's axis.
struct Setup {
    std::vector<Surface> surfaces;
    std::uint32_t bottom = 0; ///< a bottom tile near the middle
};

Setup tiled_box(int k, bool hole) {
    Setup b;
    const Vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1), o(0, 0, 0);
    add_tiles(b.surfaces, o, y, x, k); // bottom, normal −z
    b.bottom = std::uint32_t((k / 2) * k + k / 2);
    add_tiles(b.surfaces, o + z, x, y, k, hole ? k / 2 : 0, hole ? k / 2 + 1 : 0); // top, +z
    add_tiles(b.surfaces, o, x, z, k);     // y = 0, normal −y
    add_tiles(b.surfaces, o + y, z, x, k); // y = 1, +y
    add_tiles(b.surfaces, o, z, y, k);     // x = 0, −x
    add_tiles(b.surfaces, o + x, y, z, k); // x = 1, +x
    // Panel [0.46, 1.26]² at z = 3, facing down: the centre of its sources' box is not above
    // the hole, but the source near its corner, at (0.5, 0.5, 3), is seen through it from the
    // bottom's middle.
    Surface panel;
    EXPECT_TRUE(
        make_surface({{0.46, 0.46, 3}, {0.46, 1.26, 3}, {1.26, 1.26, 3}, {1.26, 0.46, 3}}, panel));
    panel.id = std::uint32_t(b.surfaces.size());
    panel.emits_front = true;
    b.surfaces.push_back(panel);
    return b;
}

bool bottom_enclosed(const Setup& b) {
    MeshParams params;
    params.diagonal = std::sqrt(1.26 * 1.26 * 2 + 9);
    params.snap = 2e-7 * params.diagonal;
    const SurfaceBvh bvh(b.surfaces);
    const EnclosureTest test(Scene{}, b.surfaces, bvh, params);
    // The inside of the bottom face, at its middle, looking up (its back side).
    return test.enclosed({0.5, 0.5, 0}, {0, 0, 1}, b.bottom, 0.05);
}

TEST(EnclosureTest, TiledClosedBoxHidesItsInside) {
    EXPECT_TRUE(bottom_enclosed(tiled_box(25, false)));
}

// Glazing encloses nothing: with a glass top, probes and the panel's light pass through it.
TEST(EnclosureTest, GlazedTopDoesNotEnclose) {
    auto b = tiled_box(5, false); // "Setup" would name gtest's Test::Setup here
    EXPECT_TRUE(bottom_enclosed(b));
    for (std::uint32_t i = 25; i < 50; ++i) // the top's tiles
        b.surfaces[i].opaque = false;
    EXPECT_FALSE(bottom_enclosed(b));
}

// The top's tiles, with a hole of 0.04 in their middle (which no probe ray goes through),
// span the same convex hull as a closed top: taken as one blocker they would hide the
// panel's corner seen through the hole.
TEST(EnclosureTest, TiledFaceWithAHoleDoesNotBlockAsOne) {
    EXPECT_FALSE(bottom_enclosed(tiled_box(25, true)));
}

} // namespace
} // namespace penumbra::mesher
