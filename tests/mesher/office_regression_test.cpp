// The mesh of small generated office floors (tests/support/office_scene.h) against figures recorded
// before the mesher was made to scale (linear assembly and manifold check, source culling
// in the enclosure test, ordered BVH traversal): the same elements, vertices, patches and
// areas, as input and with contact splitting and hidden regions. Also the mesh does not
// depend on the thread count. Timings are measured by bench/mesh_bench, never asserted.

#include "mesher/mesher.h"

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "office_scene.h"

namespace penumbra {
namespace {

Scene office(bool contacts) {
    bench::OfficeParams p;
    p.rooms_x = 3;
    p.rooms_y = 2;
    p.tessellation = 2;
    p.windows_per_room = 1;
    Scene scene = bench::office_floor(p);
    // The floor as it was recorded: one-sided panels (the generator now keeps their backs).
    for (Material& m : scene.materials)
        if (m.name == "panel")
            m.two_sided = false;
    bench::mesh_input_as_is(scene);
    scene.mesher.split_contacts = contacts;
    return scene;
}

struct Figures {
    std::size_t elements, vertices, patches;
    double area_m2, hidden_m2;
};

Figures figures(const RadiosityMesh& mesh) {
    Figures f{mesh.element_count(), mesh.vertex_count(), mesh.patches.size(), 0.0, 0.0};
    for (double a : mesh.element_area)
        f.area_m2 += a;
    for (const SurfaceInfo& s : mesh.surfaces)
        f.hidden_m2 += s.hidden_front_m2 + s.hidden_back_m2;
    return f;
}

void expect_figures(const Scene& scene, const Figures& expected) {
    const Figures got = figures(mesher::build_mesh(scene, test::quiet_context()));
    EXPECT_EQ(got.elements, expected.elements);
    EXPECT_EQ(got.vertices, expected.vertices);
    EXPECT_EQ(got.patches, expected.patches);
    EXPECT_NEAR(got.area_m2, expected.area_m2, 1e-9 * expected.area_m2);
    EXPECT_NEAR(got.hidden_m2, expected.hidden_m2, 1e-9 * expected.area_m2);
}

TEST(OfficeMesh, AsInputIsTheRecordedMesh) {
    expect_figures(office(false), {7832, 13664, 3024, 775.36399999985917, 0.0});
}

TEST(OfficeMesh, WithContactsIsTheRecordedMesh) {
    expect_figures(office(true), {6857, 9606, 1468, 706.68800984231598, 68.672000000000367});
}

// A bulb inside a cabinet (an open box standing on the floor): the enclosure test must see it
// from inside, so the cabinet's inside stays meshed.
TEST(OfficeMesh, BulbInACabinetIsTheRecordedMesh) {
    Scene scene = office(true);
    PointLight bulb;
    bulb.name = "bulb";
    bulb.position = {3.4, 0.2, 0.6};
    bulb.intensity = Rgb(1.0f);
    scene.point_lights.push_back(bulb);
    expect_figures(scene, {6929, 9728, 1484, 710.20781332321906, 65.152000000000598});
}

TEST(OfficeMesh, SameMeshForAnyThreadCount) {
    const Scene scene = office(true);
    const RadiosityMesh one = mesher::build_mesh(scene, test::quiet_context(1));
    const RadiosityMesh two = mesher::build_mesh(scene, test::quiet_context(2));
    ASSERT_EQ(one.element_count(), two.element_count());
    EXPECT_EQ(one.positions, two.positions);
    EXPECT_EQ(one.triangles, two.triangles);
    EXPECT_EQ(one.element_patch, two.element_patch);
    EXPECT_EQ(one.element_twin, two.element_twin);
    EXPECT_EQ(one.element_area, two.element_area);
    EXPECT_EQ(one.geometry_elements, two.geometry_elements);
    EXPECT_EQ(one.vertex_patch, two.vertex_patch);
}

} // namespace
} // namespace penumbra
