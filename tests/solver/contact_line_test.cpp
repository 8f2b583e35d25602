// Issue #27: values where surfaces meet (contact lines, a room's corners), with the surfaces
// exactly meeting, one ending on the other (touching) and crossing each other (overlapping).
// A vertex on such a line once gathered its direct light from the line itself: its rays
// started on, or were lifted behind, the surface meeting it there (which blocked them all),
// and it saw that surface edge-on; the Cornell box's image had a dark line along every wall
// junction.

#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "common/bake_util.h"
#include "common/test_util.h"
#include "mesher/exact_direct.h"

namespace penumbra {
namespace {

using test::add_material;
using test::add_rect;

enum class Junction { meeting, touching, overlapping };

std::string name_of(Junction j) {
    switch (j) {
    case Junction::meeting:
        return "meeting";
    case Junction::touching:
        return "touching";
    case Junction::overlapping:
        return "overlapping";
    }
    return "";
}

// How far a surface runs past the line where it meets another: the floor and ceiling run past
// the walls when touching (the walls end on them), every surface runs past every other when
// overlapping.
constexpr double k_past = 0.005;

struct Reach {
    double floor, wall; ///< run past the contact lines, metres
};

Reach reach(Junction j) {
    switch (j) {
    case Junction::meeting:
        return {0, 0};
    case Junction::touching:
        return {k_past, 0};
    case Junction::overlapping:
        return {k_past, k_past};
    }
    return {0, 0};
}

// Vertices whose elements all lie in the box [lo, hi] on the front side: the inside of the
// box, without the strips that run past it.
std::vector<std::uint32_t> vertices_inside(const RadiosityMesh& mesh, const Vec3& lo,
                                           const Vec3& hi) {
    const double tol = 1e-5; // contact splitting moves junction vertices by up to 2 µm
    auto inside = [&](const Vec3& p) {
        return p.x >= lo.x - tol && p.y >= lo.y - tol && p.z >= lo.z - tol && p.x <= hi.x + tol &&
               p.y <= hi.y + tol && p.z <= hi.z + tol;
    };
    std::vector<std::uint8_t> used(mesh.vertex_count(), 0), outside(mesh.vertex_count(), 0);
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
        const bool in =
            !mesh.patch_of(std::uint32_t(e)).back && inside(mesh.centroid(std::uint32_t(e)));
        for (std::uint32_t v : mesh.triangles[e]) {
            used[v] = 1;
            outside[v] |= in ? 0 : 1;
        }
    }
    std::vector<std::uint32_t> out;
    for (std::uint32_t v = 0; v < mesh.vertex_count(); ++v)
        if (used[v] && !outside[v])
            out.push_back(v);
    return out;
}

// ---- Furnace: every surface emits E and reflects ρ, so B = E / (1 − ρ) everywhere ----

class ContactFurnace : public ::testing::TestWithParam<Junction> {};

TEST_P(ContactFurnace, EveryVertexAtEOverOneMinusRho) {
    const Reach r = reach(GetParam());
    const double x = 1, y = 1.5, z = 0.8; // not a cube
    const float rho = 0.5f, E = 1.0f;
    Scene scene;
    auto m = add_material(scene, "furnace", Rgb(rho), Rgb(float(E / k_pi)));
    const double f = r.floor, w = r.wall;
    add_rect(scene, "floor", m, {-f, -f, 0}, {x + 2 * f, 0, 0}, {0, y + 2 * f, 0});
    add_rect(scene, "ceiling", m, {-f, -f, z}, {0, y + 2 * f, 0}, {x + 2 * f, 0, 0});
    add_rect(scene, "x0", m, {0, -w, -w}, {0, y + 2 * w, 0}, {0, 0, z + 2 * w});
    add_rect(scene, "x1", m, {x, -w, -w}, {0, 0, z + 2 * w}, {0, y + 2 * w, 0});
    add_rect(scene, "y0", m, {-w, 0, -w}, {0, 0, z + 2 * w}, {x + 2 * w, 0, 0});
    add_rect(scene, "y1", m, {-w, y, -w}, {x + 2 * w, 0, 0}, {0, 0, z + 2 * w});
    scene.mesher.max_edge_length = 0.3;
    scene.solver.min_area = 0.01; // as HierarchicalFurnace: two levels below the roots
    scene.solver.residual = 1e-6;
    const app::BakeResult b = test::bake(scene);
    ASSERT_EQ(b.solution.vertex_radiosity.size(), b.mesh.vertex_count());
    const double expected = E / (1 - rho);
    const std::vector<std::uint32_t> inside = vertices_inside(b.mesh, {0, 0, 0}, {x, y, z});
    ASSERT_GT(inside.size(), 100u);
    double worst = 0;
    std::uint32_t worst_v = 0;
    std::size_t on_lines = 0;
    for (std::uint32_t v : inside) {
        const Vec3 p = b.mesh.vertex(v);
        auto on = [](double c, double plane) { return std::abs(c - plane) < 1e-5; };
        const int on_planes =
            (on(p.x, 0) || on(p.x, x)) + (on(p.y, 0) || on(p.y, y)) + (on(p.z, 0) || on(p.z, z));
        on_lines += on_planes >= 2 ? 1 : 0;
        const double err = std::abs(b.solution.vertex_radiosity[v].g - expected) / expected;
        if (err > worst) {
            worst = err;
            worst_v = v;
        }
    }
    EXPECT_GT(on_lines, 50u) << "the junctions' vertices are among those checked";
    const Vec3 p = b.mesh.vertex(worst_v);
    EXPECT_LT(worst, 0.005) << name_of(GetParam()) << ": vertex at (" << p.x << ", " << p.y << ", "
                            << p.z << ")";
}

INSTANTIATE_TEST_SUITE_P(Junctions, ContactFurnace,
                         ::testing::Values(Junction::meeting, Junction::touching,
                                           Junction::overlapping),
                         [](const auto& info) { return name_of(info.param); });

// ---- An area light over a floor that meets a wall: direct light next to the wall ----

class ContactDirect : public ::testing::TestWithParam<Junction> {};

TEST_P(ContactDirect, FloorBesideTheWallMatchesLambert) {
    const Reach r = reach(GetParam());
    const double wall_x = 2, depth = 2, height = 1.5;
    Scene scene;
    auto grey = add_material(scene, "grey", Rgb(0.5f));
    const double radiance = 5;
    auto lamp = add_material(scene, "lamp", Rgb(0.0f), Rgb(float(radiance)), false);
    const std::uint32_t floor = std::uint32_t(scene.polygons.size());
    add_rect(scene, "floor", grey, {0, 0, 0}, {wall_x + r.floor, 0, 0}, {0, depth, 0});
    add_rect(scene, "wall", grey, {wall_x, -r.wall, -r.wall}, {0, 0, height + r.wall},
             {0, depth + 2 * r.wall, 0}); // faces -x
    const std::uint32_t light = std::uint32_t(scene.polygons.size());
    add_rect(scene, "light", lamp, {1.4, 0.7, 1.0}, {0, 0.6, 0}, {0.5, 0, 0}); // faces down
    const std::vector<Vec3> light_polygon = scene.polygons[light].vertices;
    const Vec3 up{0, 0, 1};
    for (double gap : {0.0001, 0.0005, 0.001})
        for (double y : {0.5, 1.0, 1.3})
            scene.sensors.push_back({"floor", {wall_x - gap, y, 0}, up});
    scene.mesher.max_edge_length = 0.25;
    const app::BakeResult b = test::bake(scene);
    auto exact = [&](const Vec3& p) {
        return radiance * test::polygon_irradiance(p, up, light_polygon);
    };
    std::size_t checked = 0;
    for (std::size_t e = 0; e < b.mesh.element_count(); ++e) {
        const Patch& patch = b.mesh.patch_of(std::uint32_t(e));
        if (patch.polygon != floor || patch.back || b.mesh.centroid(std::uint32_t(e)).x > wall_x)
            continue;
        for (std::uint32_t v : b.mesh.triangles[e]) {
            const Vec3 p = b.mesh.vertex(v);
            if (p.x < wall_x - 0.001)
                continue;
            ++checked;
            const double h = b.solution.vertex_irradiance_direct[v].g;
            EXPECT_NEAR(h, exact(p), 0.01 * exact(p))
                << name_of(GetParam()) << ": vertex at (" << p.x << ", " << p.y << ")";
        }
    }
    EXPECT_GT(checked, 10u);
    for (std::size_t s = 0; s < scene.sensors.size(); ++s) {
        const Vec3 p = scene.sensors[s].position;
        EXPECT_NEAR(b.sensors[s].irradiance_direct.g, exact(p), 0.01 * exact(p))
            << name_of(GetParam()) << ": sensor at (" << p.x << ", " << p.y << ")";
    }
}

INSTANTIATE_TEST_SUITE_P(Junctions, ContactDirect,
                         ::testing::Values(Junction::meeting, Junction::touching,
                                           Junction::overlapping),
                         [](const auto& info) { return name_of(info.param); });

} // namespace
} // namespace penumbra
