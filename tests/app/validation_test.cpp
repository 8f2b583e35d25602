// End-to-end validation of the bake pipeline (mesher → solver → sensors) against analytic
// values. Numbers come from shared/validation/README.md, section given at each test.
// Ambient term off everywhere.

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "app/pipeline.h"
#include "common/test_util.h"
#include "core/scene_io.h"

namespace penumbra {
namespace {

using test::add_material;
using test::add_rect;

// These tests validate the progressive shooting solver (issue #3); the hierarchical solver
// has its own in hierarchical_test.cpp, and runs CIE 171 5.8 here too.
app::BakeResult bake_no_render(Scene scene, int threads = 0,
                               const std::string& method = "shooting") {
    scene.solver.method = method;
    app::BakeOptions options;
    options.render = false;
    return app::bake(scene, options, test::quiet_context(threads));
}

// Area mean over the elements of the patches of polygon \p polygon on side \p back.
Rgb polygon_mean(const app::BakeResult& r, const std::vector<Rgb>& values, std::uint32_t polygon,
                 bool back = false) {
    RgbD sum;
    double area = 0;
    for (std::size_t e = 0; e < r.mesh.element_count(); ++e) {
        const Patch& p = r.mesh.patch_of(std::uint32_t(e));
        if (p.polygon != polygon || p.back != back)
            continue;
        sum += RgbD(values[e]) * r.mesh.element_area[e];
        area += r.mesh.element_area[e];
    }
    return Rgb(float(sum.r / area), float(sum.g / area), float(sum.b / area));
}

// ---- Form factors through the whole pipeline (§1): emitter E = 1 W/m², black receiver ----

struct FormFactorCase {
    const char* name;
    Vec3 e_origin, e_u, e_v; // emitter rectangle, faces e_u × e_v
    Vec3 r_origin, r_u, r_v; // receiver rectangle
    double expected;         // F from emitter to receiver
};

class FormFactorPipeline : public ::testing::TestWithParam<FormFactorCase> {};

TEST_P(FormFactorPipeline, WithinHalfPercent) {
    const FormFactorCase& c = GetParam();
    Scene scene;
    auto light = add_material(scene, "emitter", Rgb(0), Rgb(float(1 / k_pi)), false);
    auto black = add_material(scene, "receiver", Rgb(0), {}, false);
    add_rect(scene, "emitter", light, c.e_origin, c.e_u, c.e_v);
    add_rect(scene, "receiver", black, c.r_origin, c.r_u, c.r_v);
    scene.mesher.max_edge_length = 0.1;
    app::BakeResult r = bake_no_render(scene);
    const double a_e = length(cross(c.e_u, c.e_v)), a_r = length(cross(c.r_u, c.r_v));
    const double h = polygon_mean(r, r.solution.irradiance_direct, 1).r;
    const double f = h * a_r / (1.0 * a_e);
    EXPECT_NEAR(f, c.expected, 0.005 * c.expected) << c.name;
}

INSTANTIATE_TEST_SUITE_P(
    Howell, FormFactorPipeline,
    ::testing::Values(
        FormFactorCase{"parallel squares 1 apart", {0, 0, 0}, {1, 0, 0}, {0, 1, 0},
                       {0, 0, 1}, {0, 1, 0}, {1, 0, 0}, 0.199825},
        FormFactorCase{"parallel squares 0.5 apart", {0, 0, 0}, {1, 0, 0}, {0, 1, 0},
                       {0, 0, 0.5}, {0, 1, 0}, {1, 0, 0}, 0.415253},
        FormFactorCase{"parallel 2x1 rectangles 1 apart", {0, 0, 0}, {2, 0, 0}, {0, 1, 0},
                       {0, 0, 1}, {0, 1, 0}, {2, 0, 0}, 0.285875},
        FormFactorCase{"perpendicular squares sharing an edge", {0, 0, 0}, {1, 0, 0},
                       {0, 1, 0}, {0, 0, 0}, {0, 1, 0}, {0, 0, 1}, 0.200044}));

// ---- Furnace (§2): closed box, uniform E and ρ → B = E / (1 − ρ) everywhere ----

TEST(Furnace, UniformEmissionAndReflectance) {
    Scene scene;
    const float rho = 0.5f, E = 1.0f;
    auto m = add_material(scene, "furnace", Rgb(rho), Rgb(float(E / k_pi)));
    test::add_room(scene, {0, 0, 0}, {1, 1.5, 0.8}, m); // not a cube: any shape works
    scene.mesher.max_edge_length = 0.1;
    scene.solver.residual = 1e-5;
    app::BakeResult r = bake_no_render(scene);
    const double expected = E / (1 - rho);
    double worst = 0;
    for (std::size_t e = 0; e < r.mesh.element_count(); ++e) {
        if (r.mesh.patch_of(std::uint32_t(e)).back)
            continue; // the outside of the box sees nothing
        worst = std::max(worst, std::abs(r.solution.radiosity[e].g - expected) / expected);
    }
    EXPECT_LT(worst, 0.005);
    EXPECT_NEAR(r.stats.power.escaped.sum(), 0.0, 1e-12);
}

// ---- CIE 171 5.8 (§2): 4 m cube, 10 000 lm isotropic point source at the centre ----

Scene cie171_cube(double rho) {
    Scene scene;
    auto m = add_material(scene, "wall", Rgb(float(rho)), {}, false);
    test::add_room(scene, {0, 0, 0}, {4, 4, 4}, m);
    PointLight light;
    light.name = "source";
    light.position = {2, 2, 2};
    light.intensity = from_photometric(10000.0 / (4 * k_pi), Rgb(1.0f));
    scene.point_lights.push_back(light);
    scene.solver.residual = 1e-4;
    return scene;
}

// Every face's area means of direct and indirect illuminance within \p tolerance (relative).
void expect_cube_face_means(const app::BakeResult& r, double rho, double tolerance) {
    const double s_t = 96.0, phi = 10000.0;
    const double direct_expected = phi / s_t;
    const double indirect_expected = rho * phi / (s_t * (1 - rho));
    for (std::uint32_t face = 0; face < 6; ++face) {
        double direct = to_photometric(polygon_mean(r, r.solution.irradiance_direct, face));
        double indirect = to_photometric(polygon_mean(r, r.solution.irradiance_indirect, face));
        EXPECT_NEAR(direct, direct_expected, tolerance * direct_expected) << "face " << face;
        EXPECT_NEAR(indirect, indirect_expected, tolerance * indirect_expected)
            << "face " << face;
    }
}

class Cie171Cube : public ::testing::TestWithParam<double> {};

TEST_P(Cie171Cube, FaceMeansOfDirectAndIndirectIlluminance) {
    const double rho = GetParam();
    Scene scene = cie171_cube(rho);
    scene.mesher.max_edge_length = 0.5;
    app::BakeResult r = bake_no_render(scene);
    expect_cube_face_means(r, rho, 0.01);
    EXPECT_NEAR(r.stats.power.relative_imbalance(), 0.0, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Reflectances, Cie171Cube, ::testing::Values(0.2, 0.8, 0.95));

// The same on the hierarchical solver (issue #4), within 0.5 %, on coarse roots (1 m) and
// leaves (0.05 m²) at ε = 1e-2: links between coarse nodes must neither take the bright middle
// of a wall at its area share (the mean fell 0.6 % short at ρ = 0.2) nor give the corners more
// than their own form factors (it rose 1.8 % at ρ = 0.95, the error of each bounce compounded).
// The imbalance follows the face means: the absorbed power is (1 − ρ) × the mean irradiance.
class Cie171CubeHierarchical : public ::testing::TestWithParam<double> {};

TEST_P(Cie171CubeHierarchical, FaceMeansOfDirectAndIndirectIlluminance) {
    const double rho = GetParam();
    Scene scene = cie171_cube(rho);
    scene.mesher.max_edge_length = 1.0;
    scene.solver.epsilon = 1e-2;
    scene.solver.min_area = 0.05;
    app::BakeResult r = bake_no_render(scene, 0, "hierarchical");
    ASSERT_EQ(*std::max_element(r.mesh.element_level.begin(), r.mesh.element_level.end()), 2);
    expect_cube_face_means(r, rho, 0.005);
    EXPECT_NEAR(r.stats.power.relative_imbalance(), 0.0, 5e-3);
}

INSTANTIATE_TEST_SUITE_P(Reflectances, Cie171CubeHierarchical,
                         ::testing::Values(0.2, 0.8, 0.95));

// ---- CIE 171 5.3 (§3): 1 × 1 m panel of 1000 cd/m² in the ceiling, all surfaces black ----

TEST(Cie171AreaSource, DirectIlluminanceAtSensors) {
    Scene scene;
    auto black = add_material(scene, "black", Rgb(0), {}, false);
    auto panel = add_material(scene, "panel", Rgb(0), from_photometric(1000.0, Rgb(1.0f)), false);
    const double H = 3;
    add_rect(scene, "floor", black, {0, 0, 0}, {4, 0, 0}, {0, 4, 0});
    add_rect(scene, "wall_y0", black, {0, 0, 0}, {0, 0, H}, {4, 0, 0});
    add_rect(scene, "wall_y4", black, {0, 4, 0}, {4, 0, 0}, {0, 0, H});
    add_rect(scene, "wall_x0", black, {0, 0, 0}, {0, 4, 0}, {0, 0, H});
    add_rect(scene, "wall_x4", black, {4, 0, 0}, {0, 0, H}, {0, 4, 0});
    // Ceiling in four pieces around the panel (x, y in [1.5, 2.5]), all facing down.
    add_rect(scene, "ceiling_s", black, {0, 0, H}, {4, 0, 0}, {0, 1.5, 0});
    add_rect(scene, "ceiling_n", black, {0, 2.5, H}, {4, 0, 0}, {0, 1.5, 0});
    add_rect(scene, "ceiling_w", black, {0, 1.5, H}, {1.5, 0, 0}, {0, 1, 0});
    add_rect(scene, "ceiling_e", black, {2.5, 1.5, H}, {1.5, 0, 0}, {0, 1, 0});
    add_rect(scene, "panel", panel, {1.5, 1.5, H}, {1, 0, 0}, {0, 1, 0});
    // add_rect's front is u × v: flip the ceiling pieces and panel to face down.
    for (std::size_t p = 5; p < scene.polygons.size(); ++p)
        std::reverse(scene.polygons[p].vertices.begin(), scene.polygons[p].vertices.end());
    const double floor_y[] = {0.25, 0.75, 1.25, 1.75};
    const double floor_lx[] = {61.42, 79.26, 95.67, 105.78};
    const double wall_z[] = {2.75, 2.25, 1.75, 1.25, 0.75, 0.25};
    const double wall_lx[] = {32.68, 75.19, 81.32, 69.06, 53.40, 40.00};
    for (double y : floor_y)
        scene.sensors.push_back({"floor", {2, y, 0}, {0, 0, 1}});
    for (double z : wall_z)
        scene.sensors.push_back({"wall", {2, 0, z}, {0, 1, 0}});
    scene.mesher.max_edge_length = 0.25;
    app::BakeResult r = bake_no_render(scene);
    ASSERT_EQ(r.sensors.size(), 10u);
    for (std::size_t i = 0; i < 10; ++i) {
        const double exact = i < 4 ? floor_lx[i] : wall_lx[i - 4];
        const Sensor& s = scene.sensors[i];
        // The README's exact values are rounded to 0.01 lx; allow that on top of 0.1 %.
        EXPECT_NEAR(r.sensors[i].illuminance_direct_lx, exact, 0.001 * exact + 0.005)
            << s.name << " sensor " << i;
        auto interpolated = interpolate_at(r.mesh, r.solution.vertex_irradiance_direct,
                                           s.position, s.normal, 1e-6);
        ASSERT_TRUE(interpolated.has_value()) << "sensor " << i << " not on the mesh";
        EXPECT_NEAR(to_photometric(*interpolated), exact, 0.02 * exact) << "mesh, sensor " << i;
    }
}

// ---- Units (§4): the Cornell light, given in mm, emits πLA ----

TEST(Units, CornellLightPowerFromMillimetreScene) {
    Scene scene = load_scene(test::source_path("data/cornell/scene.json"));
    RgbD emitted;
    for (const Polygon& p : scene.polygons) {
        const Material& m = scene.materials[p.material];
        if (m.emission.is_black())
            continue;
        Vec3 n = cross(p.vertices[1] - p.vertices[0], p.vertices[2] - p.vertices[0]);
        emitted += RgbD(m.emission) * (k_pi * length(n)); // a rectangle: |n| is its area
    }
    EXPECT_NEAR(emitted.r, 0.729, 0.0005);
    EXPECT_NEAR(emitted.g, 0.515, 0.0005);
    EXPECT_NEAR(emitted.b, 0.172, 0.0005);
    // The same through the solver's bookkeeping.
    scene.mesher.max_edge_length = 0.15;
    scene.solver.residual = 0.05;
    app::BakeResult r = bake_no_render(scene);
    EXPECT_NEAR(r.stats.power.emitted.r, emitted.r, 1e-6 * emitted.r);
    EXPECT_NEAR(r.stats.power.emitted.b, emitted.b, 1e-6 * emitted.b);
}

} // namespace
} // namespace penumbra
