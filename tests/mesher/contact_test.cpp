// Contact and intersection splitting, near-contacts and hidden parts (issue #5).

#include "mesher/mesher.h"

#include <mutex>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "core/rng.h"
#include "mesher/mesh_checks.h"

namespace penumbra {
namespace {

using test::add_material;
using test::add_rect;

class CaptureSink final : public LogSink {
public:
    void write(LogLevel level, std::string_view message) override {
        std::lock_guard lock(mutex_);
        if (level >= LogLevel::warn)
            lines.emplace_back(message);
    }
    std::vector<std::string> lines;

private:
    std::mutex mutex_;
};

RadiosityMesh mesh_of(const Scene& scene, std::shared_ptr<CaptureSink> sink = nullptr) {
    Context ctx = test::quiet_context();
    if (sink)
        ctx.log = sink;
    return mesher::build_mesh(scene, ctx);
}

// Floor [0,4]², with a wall of height 2.5 standing on the line x = 2.13, y in [0.5, 3.5].
Scene wall_on_floor(double gap) {
    Scene scene;
    auto m = add_material(scene, "white", Rgb(0.5f));
    add_rect(scene, "floor", m, {0, 0, 0}, {4, 0, 0}, {0, 4, 0});
    add_rect(scene, "wall", m, {2.13, 0.5, gap}, {0, 3, 0}, {0, 0, 2.5 - gap});
    scene.mesher.max_edge_length = 0.5;
    return scene;
}

TEST(Contacts, WallOnFloorSplitsTheFloor) {
    const Scene scene = wall_on_floor(0.0);
    const RadiosityMesh mesh = mesh_of(scene);
    const auto floor = std::uint32_t(test::find_patch(mesh, 0));
    const Vec3 a(2.13, 0.5, 0), b(2.13, 3.5, 0);
    EXPECT_TRUE(test::segment_on_element_edges(mesh, floor, a, b, 1e-5));
    EXPECT_FALSE(test::element_straddles(mesh, floor, a, b, 1e-4));
    // The wall stands on a slit: both of its sides are boundary, its vertices are not shared.
    test::expect_conforming(mesh, floor, 16.0 + 2 * 3.0);
    EXPECT_NEAR(test::patch_area(mesh, floor), 16.0, 1e-4);
}

TEST(Contacts, WallFloatingOneMillimetreIsClosed) {
    const Scene scene = wall_on_floor(0.001);
    const RadiosityMesh mesh = mesh_of(scene);
    const auto wall = std::uint32_t(test::find_patch(mesh, 1));
    double lowest = 1;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
        if (mesh.vertex_patch[v] == wall)
            lowest = std::min(lowest, mesh.vertex(std::uint32_t(v)).z);
    EXPECT_NEAR(lowest, 0.0, 1e-7); // moved down onto the floor
    const auto floor = std::uint32_t(test::find_patch(mesh, 0));
    EXPECT_TRUE(test::segment_on_element_edges(mesh, floor, {2.13, 0.5, 0}, {2.13, 3.5, 0}, 1e-5));
}

TEST(Contacts, NoSplittingWhenTurnedOff) {
    Scene scene = wall_on_floor(0.001);
    scene.mesher.split_contacts = false;
    scene.mesher.discontinuity.enabled = false;
    const RadiosityMesh mesh = mesh_of(scene);
    const auto floor = std::uint32_t(test::find_patch(mesh, 0));
    EXPECT_TRUE(test::element_straddles(mesh, floor, {2.13, 0.5, 0}, {2.13, 3.5, 0}, 1e-4));
    const auto wall = std::uint32_t(test::find_patch(mesh, 1));
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        if (mesh.vertex_patch[v] == wall) { // gtest's macros are an if-else of their own
            EXPECT_GE(mesh.vertex(std::uint32_t(v)).z, 0.001 - 1e-7);
        }
    }
}

TEST(Contacts, WallThroughFloorAndCeilingSplitsAllThree) {
    Scene scene;
    auto m = add_material(scene, "white", Rgb(0.5f));
    add_rect(scene, "floor", m, {0, 0, 0}, {4, 0, 0}, {0, 4, 0});
    add_rect(scene, "ceiling", m, {0, 0, 3}, {0, 4, 0}, {4, 0, 0});
    add_rect(scene, "wall", m, {1.37, 0, -0.5}, {0, 4, 0}, {0, 0, 4});
    scene.mesher.max_edge_length = 0.5;
    const RadiosityMesh mesh = mesh_of(scene);
    const auto floor = std::uint32_t(test::find_patch(mesh, 0));
    const auto ceiling = std::uint32_t(test::find_patch(mesh, 1));
    const auto wall = std::uint32_t(test::find_patch(mesh, 2));
    EXPECT_FALSE(test::element_straddles(mesh, floor, {1.37, 0, 0}, {1.37, 4, 0}, 1e-4));
    EXPECT_FALSE(test::element_straddles(mesh, ceiling, {1.37, 0, 3}, {1.37, 4, 3}, 1e-4));
    EXPECT_TRUE(test::segment_on_element_edges(mesh, wall, {1.37, 0, 0}, {1.37, 4, 0}, 1e-5));
    EXPECT_TRUE(test::segment_on_element_edges(mesh, wall, {1.37, 0, 3}, {1.37, 4, 3}, 1e-5));
    // Nothing of it is hidden; vertex copies on the two contact lines move 1e-6 × diagonal.
    EXPECT_NEAR(test::patch_area(mesh, wall), 16.0, 2e-4);
}

// A box of footprint [x0, x0 + w] × [y0, y0 + d], rotated by angle about its first corner.
void add_box(Scene& scene, std::uint32_t m, double x0, double y0, double w, double d, double h,
             double angle, double lift, bool bottom) {
    const Vec3 o(x0, y0, lift);
    const Vec3 u = Vec3(std::cos(angle), std::sin(angle), 0) * w;
    const Vec3 v = Vec3(-std::sin(angle), std::cos(angle), 0) * d;
    const Vec3 up(0, 0, h);
    add_rect(scene, "box_top", m, o + up, u, v);
    add_rect(scene, "box_s0", m, o, u, up);
    add_rect(scene, "box_s1", m, o + u, v, up);
    add_rect(scene, "box_s2", m, o + u + v, u * -1.0, up);
    add_rect(scene, "box_s3", m, o + v, v * -1.0, up);
    if (bottom)
        add_rect(scene, "box_bottom", m, o, v, u);
}

struct BoxCase {
    const char* name;
    double angle, lift;
    bool bottom;
};

class BoxOnFloor : public ::testing::TestWithParam<BoxCase> {};

TEST_P(BoxOnFloor, HiddenAreaIsTheFootprint) {
    const BoxCase& c = GetParam();
    Scene scene;
    auto m = add_material(scene, "white", Rgb(0.5f));
    add_rect(scene, "floor", m, {0, 0, 0}, {4, 0, 0}, {0, 4, 0});
    add_box(scene, m, 1.3, 1.1, 0.9, 0.7, 0.8, c.angle, c.lift, c.bottom);
    scene.mesher.max_edge_length = 0.3;
    const RadiosityMesh mesh = mesh_of(scene);
    const double footprint = 0.9 * 0.7;
    EXPECT_NEAR(mesh.surfaces[0].hidden_front_m2, footprint, 1e-9) << c.name;
    EXPECT_NEAR(test::patch_area(mesh, std::uint32_t(test::find_patch(mesh, 0))), 16.0 - footprint,
                1e-6)
        << c.name;
    // The inside of the box (its faces' back sides) is hidden too.
    for (std::uint32_t face = 1; face <= 5; ++face) {
        EXPECT_EQ(test::find_patch(mesh, face, true), -1) << c.name << " face " << face;
        EXPECT_GE(test::find_patch(mesh, face, false), 0) << c.name << " face " << face;
        EXPECT_NEAR(mesh.surfaces[face].hidden_back_m2, mesh.surfaces[face].area_m2, 1e-9);
    }
    if (!c.bottom) {
        EXPECT_EQ(mesh.surfaces[0].hidden_back_m2, 0.0) << c.name;
    } else if (c.lift == 0) {
        // Coincident with the floor: the bottom's front stands in for the floor's back.
        EXPECT_NEAR(mesh.surfaces[0].hidden_back_m2, footprint, 1e-9) << c.name;
        EXPECT_GE(test::find_patch(mesh, 6, false), 0) << c.name;
        EXPECT_EQ(test::find_patch(mesh, 6, true), -1) << c.name;
    } else {
        // 1 mm above the floor: the bottom faces the floor and is hidden on both sides.
        EXPECT_EQ(mesh.surfaces[0].hidden_back_m2, 0.0) << c.name;
        EXPECT_EQ(test::find_patch(mesh, 6, false), -1) << c.name;
        EXPECT_EQ(test::find_patch(mesh, 6, true), -1) << c.name;
    }
}

INSTANTIATE_TEST_SUITE_P(Cases, BoxOnFloor,
                         ::testing::Values(BoxCase{"open bottom", 0.0, 0.0, false},
                                           BoxCase{"closed", 0.0, 0.0, true},
                                           BoxCase{"rotated", 0.4, 0.0, false},
                                           BoxCase{"floating 1 mm, closed", 0.3, 0.001, true},
                                           BoxCase{"floating 1 mm, open", 0.0, 0.001, false}),
                         [](const auto& info) {
                             std::string s = info.param.name;
                             for (char& ch : s)
                                 if (!std::isalnum(static_cast<unsigned char>(ch)))
                                     ch = '_';
                             return s;
                         });

TEST(Contacts, CoincidentDuplicateIsHiddenWithAWarning) {
    Scene scene;
    auto m = add_material(scene, "white", Rgb(0.5f));
    add_rect(scene, "floor", m, {0, 0, 0}, {4, 0, 0}, {0, 4, 0});
    add_rect(scene, "rug", m, {1, 1, 0}, {1, 0, 0}, {0, 1, 0});
    auto sink = std::make_shared<CaptureSink>();
    const RadiosityMesh mesh = mesh_of(scene, sink);
    ASSERT_FALSE(sink->lines.empty());
    EXPECT_NE(sink->lines[0].find("'rug'"), std::string::npos) << sink->lines[0];
    EXPECT_EQ(test::find_patch(mesh, 1, false), -1);
    EXPECT_EQ(test::find_patch(mesh, 1, true), -1);
    EXPECT_NEAR(test::patch_area(mesh, std::uint32_t(test::find_patch(mesh, 0))), 16.0, 1e-6);
}

TEST(Contacts, BackToBackSlabKeepsBothFronts) {
    Scene scene;
    auto m = add_material(scene, "white", Rgb(0.5f));
    add_rect(scene, "upper_floor", m, {0, 0, 3}, {4, 0, 0}, {0, 4, 0});   // faces up
    add_rect(scene, "lower_ceiling", m, {0, 0, 3}, {0, 4, 0}, {4, 0, 0}); // faces down
    const RadiosityMesh mesh = mesh_of(scene);
    EXPECT_GE(test::find_patch(mesh, 0, false), 0);
    EXPECT_GE(test::find_patch(mesh, 1, false), 0);
    EXPECT_EQ(test::find_patch(mesh, 0, true), -1);
    EXPECT_EQ(test::find_patch(mesh, 1, true), -1);
}

TEST(Contacts, ThinPanelOnWallHidesTheWallBehindIt) {
    Scene scene;
    auto m = add_material(scene, "white", Rgb(0.5f));
    add_rect(scene, "wall", m, {0, 0, 0}, {0, 4, 0}, {0, 0, 3});       // faces +x
    add_rect(scene, "panel", m, {0.0015, 1, 1}, {0, 1, 0}, {0, 0, 1}); // 1.5 mm off it
    const RadiosityMesh mesh = mesh_of(scene);
    EXPECT_NEAR(mesh.surfaces[0].hidden_front_m2, 1.0, 1e-9);
    EXPECT_NEAR(mesh.surfaces[1].hidden_back_m2, 1.0, 1e-9);
    EXPECT_EQ(mesh.surfaces[0].hidden_back_m2, 0.0);
}

TEST(Contacts, DegenerateInputNeverCrashes) {
    Scene scene;
    auto m = add_material(scene, "white", Rgb(0.5f));
    add_rect(scene, "floor", m, {0, 0, 0}, {4, 0, 0}, {0, 4, 0});
    Polygon collinear{{{1, 1, 0}, {2, 1, 0}, {3, 1, 0}}, m, "collinear", "test:collinear"};
    Polygon sliver{
        {{0.5, 0.5, 0.2}, {3.5, 0.5, 0.2}, {3.5, 0.5 + 1e-7, 0.2}}, m, "sliver", "test:sliver"};
    Polygon bowtie{{{1, 2, 1}, {2, 3, 1}, {2, 2, 1}, {1, 3, 1}}, m, "bowtie", "test:bowtie"};
    Polygon repeated{
        {{3, 3, 0.5}, {3, 3, 0.5}, {3.5, 3, 0.5}, {3.5, 3.5, 0.5}}, m, "repeated", "test:repeated"};
    scene.polygons.push_back(collinear);
    scene.polygons.push_back(sliver);
    scene.polygons.push_back(bowtie);
    scene.polygons.push_back(repeated);
    add_rect(scene, "overlap_a", m, {0.2, 0.2, 2}, {1, 0, 0}, {0, 1, 0});
    add_rect(scene, "overlap_b", m, {0.7, 0.7, 2}, {1, 0, 0}, {0, 1, 0});
    add_rect(scene, "corner_touch", m, {1.2, 1.2, 2}, {1, 0, 0}, {0, 1, 0});
    scene.mesher.max_edge_length = 0.4;
    auto sink = std::make_shared<CaptureSink>();
    RadiosityMesh mesh;
    ASSERT_NO_THROW(mesh = mesh_of(scene, sink));
    bool named = false;
    for (const std::string& line : sink->lines)
        named = named || line.find("'collinear'") != std::string::npos;
    EXPECT_TRUE(named);
    EXPECT_GT(mesh.element_count(), 0u);
    for (double a : mesh.element_area)
        EXPECT_GT(a, 0.0);
}

// A soup of random rectangles (many coplanar and crossing, some floating 1 mm above others),
// collinear "polygons" and small lights: meshing never throws and every element has area.
TEST(Contacts, RandomSoupNeverCrashes) {
    for (std::uint64_t seed = 0; seed < 6; ++seed) {
        Scene scene;
        auto white = add_material(scene, "white", Rgb(0.5f));
        auto lamp = add_material(scene, "lamp", Rgb(0.0f), Rgb(5.0f), false);
        Pcg32 rng = Pcg32::for_stream(RngPurpose::pixel_sample, seed, 0, 0, 1);
        auto r = [&](double a, double b) { return a + (b - a) * rng.next_double(); };
        for (int i = 0; i < 50; ++i) {
            Vec3 o(r(0, 3), r(0, 3), r(0, 3));
            Vec3 u(r(-1, 1), r(-1, 1), r(-1, 1)), v(r(-1, 1), r(-1, 1), r(-1, 1));
            const int kind = i % 4;
            if (kind == 0) { // horizontal, on a few heights: coplanar overlaps
                u = {r(0.1, 1.5), 0, 0};
                v = {0, r(0.1, 1.5), 0};
                o.z = std::round(o.z * 2) / 2;
            } else if (kind == 1) { // vertical, standing on or floating 1 mm above a height
                u = {r(0.1, 1.5), 0, 0};
                v = {0, 0, r(0.1, 1.5)};
                o.z = std::round(o.z * 2) / 2 + (i % 3 == 0 ? 0.001 : 0.0);
            }
            Polygon p{{o, o + u, o + u + v, o + v},
                      i % 9 == 0 ? lamp : white,
                      "p" + std::to_string(i),
                      "soup"};
            if (kind == 3)
                p.vertices = {o, o + u, o + u * 2.0}; // collinear
            scene.polygons.push_back(p);
        }
        scene.mesher.max_edge_length = 0.3;
        RadiosityMesh mesh;
        ASSERT_NO_THROW(mesh = mesh_of(scene, std::make_shared<CaptureSink>())) << seed;
        EXPECT_GT(mesh.element_count(), 100u);
        for (double a : mesh.element_area)
            ASSERT_GT(a, 0.0) << "seed " << seed;
    }
}

} // namespace
} // namespace penumbra
