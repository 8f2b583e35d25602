// End-to-end validation of the bake pipeline (mesher → solver → sensors) against analytic
// values. Numbers come from docs/validation.md, section given at each test.
// Ambient term off everywhere.

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "app/pipeline.h"
#include "common/bake_util.h"
#include "common/test_util.h"
#include "core/scene_io.h"

namespace penumbra {
namespace {

using test::add_material;
using test::add_rect;

// These tests validate the progressive shooting solver (issue #3); the hierarchical solver
// has its own in tests/solver/hierarchical_test.cpp, and runs CIE 171 5.8 here too.
app::BakeResult bake_no_render(Scene scene, int threads = 0,
                               const std::string& method = "shooting") {
    scene.solver.method = *parse_enum<SolverMethod>(method);
    return test::bake(scene, threads);
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

INSTANTIATE_TEST_SUITE_P(Howell, FormFactorPipeline,
                         ::testing::Values(FormFactorCase{"parallel squares 1 apart",
                                                          {0, 0, 0},
                                                          {1, 0, 0},
                                                          {0, 1, 0},
                                                          {0, 0, 1},
                                                          {0, 1, 0},
                                                          {1, 0, 0},
                                                          0.199825},
                                           FormFactorCase{"parallel squares 0.5 apart",
                                                          {0, 0, 0},
                                                          {1, 0, 0},
                                                          {0, 1, 0},
                                                          {0, 0, 0.5},
                                                          {0, 1, 0},
                                                          {1, 0, 0},
                                                          0.415253},
                                           FormFactorCase{"parallel 2x1 rectangles 1 apart",
                                                          {0, 0, 0},
                                                          {2, 0, 0},
                                                          {0, 1, 0},
                                                          {0, 0, 1},
                                                          {0, 1, 0},
                                                          {2, 0, 0},
                                                          0.285875},
                                           FormFactorCase{"perpendicular squares sharing an edge",
                                                          {0, 0, 0},
                                                          {1, 0, 0},
                                                          {0, 1, 0},
                                                          {0, 0, 0},
                                                          {0, 1, 0},
                                                          {0, 0, 1},
                                                          0.200044}),
                         [](const auto& info) { return test::case_name(info.param.name); });

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
        EXPECT_NEAR(indirect, indirect_expected, tolerance * indirect_expected) << "face " << face;
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

INSTANTIATE_TEST_SUITE_P(Reflectances, Cie171Cube, ::testing::Values(0.2, 0.8, 0.95),
                         [](const auto& info) {
                             return test::case_name(fmt::format("{}", info.param));
                         });

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

INSTANTIATE_TEST_SUITE_P(Reflectances, Cie171CubeHierarchical, ::testing::Values(0.2, 0.8, 0.95),
                         [](const auto& info) {
                             return test::case_name(fmt::format("{}", info.param));
                         });

// ---- CIE 171 5.3 (§3): 1 × 1 m panel of 1000 cd/m² in the ceiling, all surfaces black ----

TEST(Cie171AreaSource, DirectIlluminanceAtSensors) {
    Scene scene;
    auto black = add_material(scene, "black", Rgb(0), {}, false);
    auto panel = add_material(scene, "panel", Rgb(0), from_photometric(1000.0, Rgb(1.0f)), false);
    const double H = 3;
    test::add_cie171_room_without_ceiling(scene, black);
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
        // docs/validation.md's exact values are rounded to 0.01 lx; allow that on top of 0.1 %.
        EXPECT_NEAR(r.sensors[i].illuminance_direct_lx, exact, 0.001 * exact + 0.005)
            << s.name << " sensor " << i;
        auto interpolated =
            interpolate_at(r.mesh, r.solution.vertex_irradiance_direct, s.position, s.normal, 1e-6);
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

// ---- Spot lights: direct illuminance I·profile·cos θ / d² and power conservation ----

// A spot's profile and ∫ profile dω written out here, independently of core/src/scene.cpp:
// 1 within the beam, 0 beyond the cut-off, smoothstep in cos θ between (pbrt-v4's SpotLight).
double spot_profile(double cos_theta, double beam_deg, double cutoff_deg) {
    const double cb = std::cos(beam_deg * k_pi / 180), cc = std::cos(cutoff_deg * k_pi / 180);
    if (cos_theta >= cb)
        return 1;
    if (cos_theta <= cc)
        return 0;
    const double t = (cos_theta - cc) / (cb - cc);
    return t * t * (3 - 2 * t);
}

double spot_solid_angle_sr(double beam_deg, double cutoff_deg) {
    const double cb = std::cos(beam_deg * k_pi / 180), cc = std::cos(cutoff_deg * k_pi / 180);
    return 2 * k_pi * ((1 - cb) + (cb - cc) / 2);
}

PointLight make_spot(const Vec3& position, const Vec3& direction, double beam_deg,
                     double cutoff_deg, double intensity_cd) {
    PointLight light;
    light.name = "spot";
    light.position = position;
    light.intensity = from_photometric(intensity_cd, Rgb(1.0f));
    light.spot = SpotCone{normalize(direction), beam_deg, cutoff_deg};
    return light;
}

// A spot 2 m above a large black floor, tilted 17° from straight down; sensors along three
// lines across the beam, the falloff and beyond the cut-off. Sensors are gathered at the
// points themselves (exact up to float); the floor elements must catch exactly the spot's
// power (its cone lies within the floor), which checks the profile-weighted solid angles of
// the light links (hierarchical) and shots (shooting).
class SpotOverBlackFloor : public ::testing::TestWithParam<const char*> {};

TEST_P(SpotOverBlackFloor, DirectIlluminanceIsIProfileCosOverDSquared) {
    const double cd = 1000, beam = 20, cutoff = 35;
    const Vec3 position{0.2, -0.1, 2.0}, axis = normalize(Vec3(0.3, 0.1, -1));
    Scene scene;
    auto black = add_material(scene, "black", Rgb(0), {}, false);
    add_rect(scene, "floor", black, {-5, -5, 0}, {10, 0, 0}, {0, 10, 0});
    scene.point_lights.push_back(make_spot(position, axis, beam, cutoff, cd));
    for (double y : {-0.4, 0.0, 0.6})
        for (double x = -3.0; x <= 3.01; x += 0.2)
            scene.sensors.push_back({"floor", {x, y, 0}, {0, 0, 1}});
    scene.mesher.max_edge_length = 0.5;
    app::BakeResult r = bake_no_render(scene, 0, GetParam());
    ASSERT_EQ(r.sensors.size(), scene.sensors.size());
    int beam_count = 0, falloff_count = 0, outside_count = 0;
    double worst_beam = 0, worst_falloff = 0, worst_outside_lx = 0;
    for (std::size_t i = 0; i < r.sensors.size(); ++i) {
        const Vec3 d = scene.sensors[i].position - position;
        const double dist = length(d);
        const double cos_axis = dot(d, axis) / dist, cos_incidence = -d.z / dist;
        const double profile = spot_profile(cos_axis, beam, cutoff);
        const double expected = cd * profile * cos_incidence / (dist * dist);
        const double lx = r.sensors[i].illuminance_direct_lx;
        if (profile == 0) {
            ++outside_count;
            worst_outside_lx = std::max(worst_outside_lx, std::abs(lx));
            EXPECT_EQ(lx, 0.0) << "sensor " << i << " beyond the cut-off";
            continue;
        }
        const double error = std::abs(lx - expected) / expected;
        (profile == 1 ? worst_beam : worst_falloff) =
            std::max(profile == 1 ? worst_beam : worst_falloff, error);
        ++(profile == 1 ? beam_count : falloff_count);
        EXPECT_NEAR(lx, expected, 1e-3 * expected) << "sensor " << i << ", profile " << profile;
        EXPECT_NEAR(r.sensors[i].illuminance_total_lx, lx, 1e-9) << "black floor";
    }
    EXPECT_GE(beam_count, 5);
    EXPECT_GE(falloff_count, 5);
    EXPECT_GE(outside_count, 5);
    // The floor catches the whole cone: Σ H A = I ∫ profile dω.
    const double flux_lm = cd * spot_solid_angle_sr(beam, cutoff);
    double caught_lm = 0;
    for (std::size_t e = 0; e < r.mesh.element_count(); ++e)
        caught_lm += to_photometric(r.solution.irradiance_direct[e]) * r.mesh.element_area[e];
    const double caught_error = std::abs(caught_lm - flux_lm) / flux_lm;
    std::printf("spot over black floor (%s): sensors %d/%d/%d, worst rel. error beam %.2e, "
                "falloff %.2e, outside %.2e lx; floor flux rel. error %.2e\n",
                GetParam(), beam_count, falloff_count, outside_count, worst_beam, worst_falloff,
                worst_outside_lx, caught_error);
    EXPECT_LT(caught_error, 1e-3);
    EXPECT_NEAR(to_photometric(r.stats.power.emitted), flux_lm, 1e-6 * flux_lm);
    EXPECT_NEAR(to_photometric(r.stats.power.escaped), 0.0, 1e-9 * flux_lm);
}

INSTANTIATE_TEST_SUITE_P(Methods, SpotOverBlackFloor, ::testing::Values("hierarchical", "shooting"),
                         [](const auto& info) { return test::case_name(info.param); });

// The hierarchical oracle refines light links where the profile varies over the receiver: a
// hard-edged spot (beam = cut-off) on coarse roots leaves every element the cone's edge
// crosses at solver.min_area, like a shadow boundary, while elements away from it stay larger.
TEST(SpotHierarchical, HardConeEdgeIsRefinedToMinArea) {
    const double cutoff = 25, min_area = 0.004;
    const Vec3 position{0.3, 0.2, 2.0}, axis = normalize(Vec3(-0.2, 0.1, -1));
    Scene scene;
    auto black = add_material(scene, "black", Rgb(0), {}, false);
    add_rect(scene, "floor", black, {-3, -3, 0}, {6, 0, 0}, {0, 6, 0});
    scene.point_lights.push_back(make_spot(position, axis, cutoff, cutoff, 1000));
    scene.mesher.max_edge_length = 1.0;
    scene.solver.min_area = min_area;
    scene.solver.epsilon = 0.05; // I cos θ / d² alone would not refine the beam to min_area
    app::BakeResult r = bake_no_render(scene, 0, "hierarchical");
    const double cc = std::cos(cutoff * k_pi / 180);
    int crossed = 0;
    double widest_crossed = 0, widest_lit = 0;
    for (std::size_t e = 0; e < r.mesh.element_count(); ++e) {
        int inside = 0;
        for (std::uint32_t v : r.mesh.triangles[e])
            inside += dot(normalize(r.mesh.vertex(v) - position), axis) > cc ? 1 : 0;
        const double area = r.mesh.element_area[e];
        if (inside == 3)
            widest_lit = std::max(widest_lit, area);
        if (inside == 0 || inside == 3)
            continue;
        ++crossed;
        widest_crossed = std::max(widest_crossed, area);
    }
    std::printf("hard-edged spot: %zu elements, %d across the cone's edge, largest of those "
                "%.4f m2 (min_area %.4f), largest inside %.4f m2\n",
                r.mesh.element_count(), crossed, widest_crossed, min_area, widest_lit);
    EXPECT_GT(crossed, 20);
    EXPECT_LE(widest_crossed, min_area * (1 + 1e-9));
    EXPECT_GT(widest_lit, 4 * min_area);
    const double flux_lm = 1000 * spot_solid_angle_sr(cutoff, cutoff);
    double caught_lm = 0;
    for (std::size_t e = 0; e < r.mesh.element_count(); ++e)
        caught_lm += to_photometric(r.solution.irradiance_direct[e]) * r.mesh.element_area[e];
    EXPECT_NEAR(caught_lm, flux_lm, 1e-3 * flux_lm);
}

// A closed grey room (ρ = 0.5) lit by a smooth spot aimed into a corner and a hard-edged one
// (beam = cut-off) aimed at a wall: everything emitted is absorbed, absorbed + unshot = the
// spots' analytic power within the closed-room tolerances of Cie171Cube (shooting, 1e-3) and
// Cie171CubeHierarchical (5e-3), and nothing escapes.
struct SpotRoomCase {
    const char* method;
    double tolerance;
};

class SpotInClosedRoom : public ::testing::TestWithParam<SpotRoomCase> {};

TEST_P(SpotInClosedRoom, AbsorbedEqualsSpotPower) {
    const SpotRoomCase& c = GetParam();
    Scene scene;
    auto grey = add_material(scene, "grey", Rgb(0.5f), {}, false);
    test::add_room(scene, {0, 0, 0}, {4, 3, 2.5}, grey);
    scene.point_lights.push_back(make_spot({1.2, 1.0, 2.3}, {1, 0.4, -0.7}, 25, 50, 800));
    scene.point_lights.push_back(make_spot({3.0, 2.2, 1.5}, {-0.2, -1, 0.3}, 30, 30, 500));
    scene.mesher.max_edge_length = 0.5;
    scene.solver.residual = 1e-4;
    scene.solver.epsilon = 1e-2; // hierarchical: as Cie171CubeHierarchical, a few seconds
    scene.solver.min_area = 0.02;
    app::BakeResult r = bake_no_render(scene, 0, c.method);
    const double power_lm = 800 * spot_solid_angle_sr(25, 50) + 500 * spot_solid_angle_sr(30, 30);
    const solver::PowerBalance& pb = r.stats.power;
    const double absorbed = to_photometric(pb.absorbed), residual = to_photometric(pb.residual);
    const double error = std::abs(absorbed + residual - power_lm) / power_lm;
    std::printf("spots in a closed room (%s): power %.3f lm, absorbed %.3f lm, unshot %.3f lm, "
                "rel. error %.2e\n",
                c.method, power_lm, absorbed, residual, error);
    EXPECT_NEAR(to_photometric(pb.emitted), power_lm, 1e-6 * power_lm);
    EXPECT_LT(error, c.tolerance);
    EXPECT_NEAR(to_photometric(pb.escaped), 0.0, 1e-9 * power_lm);
}

INSTANTIATE_TEST_SUITE_P(Methods, SpotInClosedRoom,
                         ::testing::Values(SpotRoomCase{"shooting", 1e-3},
                                           SpotRoomCase{"hierarchical", 5e-3}),
                         [](const auto& info) { return test::case_name(info.param.method); });

// ---- The sun: direct illuminance E_n cos θ V and its power ----

Sun make_sun(double altitude_deg, double azimuth_deg, double illuminance_lx) {
    const double alt = altitude_deg * k_pi / 180, az = azimuth_deg * k_pi / 180;
    return Sun{{std::cos(alt) * std::cos(az), std::cos(alt) * std::sin(az), std::sin(alt)},
               from_photometric(illuminance_lx, Rgb(1.0f)),
               0.533};
}

// The visible fraction of the sun's disc from x past a straight blocker edge through p along
// e (the blocker on the side of the plane through x and the edge that `hidden` is on): the
// disc cut by that plane, a circular segment of the disc at the centre's angular distance δ
// from it (the disc taken as flat: 0.27° wide, its curvature changes the area by ~1e-5).
double visible_past_edge(const Sun& sun, const Vec3& x, const Vec3& p, const Vec3& e,
                         const Vec3& hidden) {
    Vec3 n = normalize(cross(p - x, e));
    if (dot(n, hidden - x) > 0)
        n = -n;
    const double r = sun.angular_diameter_deg * k_pi / 360;
    const double d = std::asin(dot(n, sun.direction)) / r; // > 0: the centre is visible
    const auto segment = [](double t) { return (std::acos(t) - t * std::sqrt(1 - t * t)) / k_pi; };
    if (d >= 1)
        return 1;
    if (d <= -1)
        return 0;
    return d >= 0 ? 1 - segment(d) : segment(-d);
}

// A black 10 m floor under a 2 × 3 m black plate 2 m up, the sun at 50° altitude from +x
// (100 klx normal): sensors in the open read E_n cos θ (1e-4 relative: the gathering is exact
// where every probe ray is open), in the plate's umbra 0, across the penumbra of its edge
// x = 1 (15.9 mm either side of its shadow line x = −0.678) between, near the disc's circular
// segment (0.04 of E_n cos θ: 144 stratified rays). The sun's power is what lands: E_n cos θ
// times the 100 m² of floor (the plate's top catches what its shadow misses), all absorbed.
class SunOverBlackFloor : public ::testing::TestWithParam<const char*> {};

TEST_P(SunOverBlackFloor, DirectIlluminanceIsEnCosThetaTimesVisibleDisc) {
    const double lx = 1e5, altitude = 50;
    const Sun sun = make_sun(altitude, 0, lx);
    Scene scene;
    auto black = add_material(scene, "black", Rgb(0), {}, false);
    add_rect(scene, "floor", black, {-5, -5, 0}, {10, 0, 0}, {0, 10, 0});
    add_rect(scene, "plate", black, {-1, -1.5, 2}, {2, 0, 0}, {0, 3, 0});
    scene.sun = sun;
    const double open_lx = lx * std::sin(altitude * k_pi / 180);
    const double shadow_x = 1 - 2 / std::tan(altitude * k_pi / 180); // of the edge x = 1
    const double half_width = 2 / std::sin(altitude * k_pi / 180) * sun.angular_radius() /
                              std::sin(altitude * k_pi / 180);
    for (double x : {-4.5, 1.0, 2.5, 4.0})
        for (double y : {-3.0, 0.0, 2.0})
            scene.sensors.push_back({"open", {x, y, 0}, {0, 0, 1}});
    for (const Vec3& p : {Vec3(-1.7, 0, 0), Vec3(-1.2, 0.5, 0), Vec3(-2.2, -0.8, 0)})
        scene.sensors.push_back({"umbra", p, {0, 0, 1}});
    for (double t : {-0.8, -0.5, -0.2, 0.0, 0.2, 0.5, 0.8})
        scene.sensors.push_back({"penumbra", {shadow_x + t * half_width, 0.3, 0}, {0, 0, 1}});
    scene.mesher.max_edge_length = 0.5;
    app::BakeResult r = bake_no_render(scene, 0, GetParam());
    ASSERT_EQ(r.sensors.size(), scene.sensors.size());
    double worst_open = 0, worst_penumbra = 0;
    for (std::size_t i = 0; i < r.sensors.size(); ++i) {
        const Sensor& s = scene.sensors[i];
        const double got = r.sensors[i].illuminance_direct_lx;
        if (s.name == "open") {
            worst_open = std::max(worst_open, std::abs(got - open_lx) / open_lx);
            EXPECT_NEAR(got, open_lx, 1e-4 * open_lx) << "sensor " << i;
        } else if (s.name == "umbra") {
            EXPECT_EQ(got, 0.0) << "sensor " << i;
        } else {
            const double v = visible_past_edge(sun, s.position, {1, 0, 2}, {0, 1, 0}, {0, 0, 2});
            worst_penumbra = std::max(worst_penumbra, std::abs(got / open_lx - v));
            EXPECT_GT(got, 0.0) << "sensor " << i;
            EXPECT_LT(got, open_lx) << "sensor " << i;
            EXPECT_NEAR(got / open_lx, v, 0.04) << "sensor " << i << ", x " << s.position.x;
        }
        EXPECT_EQ(r.sensors[i].illuminance_total_lx, got) << "black surfaces";
    }
    const double power_lm = open_lx * 100;
    const solver::PowerBalance& pb = r.stats.power;
    double direct_lm = 0;
    for (std::size_t e = 0; e < r.mesh.element_count(); ++e)
        direct_lm += to_photometric(r.solution.irradiance_direct[e]) * r.mesh.element_area[e];
    std::printf("sun over a black floor (%s): open sensors rel. error %.1e, penumbra |V - "
                "segment| %.3f; power %.6g lm (expected %.6g), balance %.1e\n",
                GetParam(), worst_open, worst_penumbra, to_photometric(pb.emitted), power_lm,
                pb.relative_imbalance());
    EXPECT_NEAR(to_photometric(pb.emitted), power_lm, 1e-3 * power_lm);
    EXPECT_NEAR(direct_lm, to_photometric(pb.emitted), 1e-5 * power_lm);
    EXPECT_NEAR(to_photometric(pb.escaped), 0.0, 1e-9 * power_lm);
    EXPECT_LT(std::abs(pb.relative_imbalance()), 1e-5);
}

INSTANTIATE_TEST_SUITE_P(Methods, SunOverBlackFloor, ::testing::Values("hierarchical", "shooting"),
                         [](const auto& info) { return test::case_name(info.param); });

// A closed grey room (ρ = 0.5, walls two-sided) with a 1 × 1 m window in the wall x = 0, the
// sun at 35° altitude from −x: the power entering through the window, E_n A cos(window
// normal, sun), lands on the inside (5e-3); absorbed + escaped (out of the window, and off
// the outside walls and roof) + unshot = the sun's delivered power Σ E_direct,sun A within the
// usual 0.5 %.
class SunThroughWindow : public ::testing::TestWithParam<const char*> {};

TEST_P(SunThroughWindow, PowerBalances) {
    const double lx = 8e4;
    Scene scene;
    scene.sun = make_sun(35, 180, lx);
    auto grey = add_material(scene, "grey", Rgb(0.5f));
    add_rect(scene, "floor", grey, {0, 0, 0}, {4, 0, 0}, {0, 3, 0});
    add_rect(scene, "ceiling", grey, {0, 0, 2.5}, {0, 3, 0}, {4, 0, 0});
    add_rect(scene, "wall_y0", grey, {0, 0, 0}, {0, 0, 2.5}, {4, 0, 0});
    add_rect(scene, "wall_y3", grey, {0, 3, 0}, {4, 0, 0}, {0, 0, 2.5});
    add_rect(scene, "wall_x4", grey, {4, 0, 0}, {0, 0, 2.5}, {0, 3, 0});
    add_rect(scene, "sill", grey, {0, 0, 0}, {0, 3, 0}, {0, 0, 0.8}); // the wall x = 0
    add_rect(scene, "lintel", grey, {0, 0, 1.8}, {0, 3, 0}, {0, 0, 0.7});
    add_rect(scene, "jamb_left", grey, {0, 0, 0.8}, {0, 1, 0}, {0, 0, 1});
    add_rect(scene, "jamb_right", grey, {0, 2, 0.8}, {0, 1, 0}, {0, 0, 1});
    scene.mesher.max_edge_length = 0.5;
    scene.solver.residual = 1e-4;
    scene.solver.epsilon = 1e-2; // hierarchical: as SpotInClosedRoom
    scene.solver.min_area = 0.01;
    app::BakeResult r = bake_no_render(scene, 0, GetParam());
    const Vec3& s = scene.sun->direction;
    const double through_window_lm = lx * 1.0 * std::abs(s.x);
    double inside_lm = 0, direct_lm = 0;
    for (std::size_t e = 0; e < r.mesh.element_count(); ++e) {
        const double lm = to_photometric(r.solution.irradiance_direct[e]) * r.mesh.element_area[e];
        direct_lm += lm;
        const Vec3 c =
            r.mesh.centroid(std::uint32_t(e)) + r.mesh.patch_of(std::uint32_t(e)).normal * 0.01;
        if (c.x > 0 && c.x < 4 && c.y > 0 && c.y < 3 && c.z > 0 && c.z < 2.5)
            inside_lm += lm;
    }
    const solver::PowerBalance& pb = r.stats.power;
    const double emitted = to_photometric(pb.emitted);
    // Outside: the roof's top and the window wall's outer face, whole but for the window.
    const double outside_lm = lx * (12 * s.z + 6.5 * std::abs(s.x));
    std::printf("sun through a window (%s): inside %.6g lm (window %.6g, rel. %.1e), delivered "
                "%.6g lm (expected %.6g), absorbed %.6g, escaped %.6g, unshot %.6g, balance "
                "%.2e\n",
                GetParam(), inside_lm, through_window_lm,
                std::abs(inside_lm - through_window_lm) / through_window_lm, emitted,
                outside_lm + through_window_lm, to_photometric(pb.absorbed),
                to_photometric(pb.escaped), to_photometric(pb.residual), pb.relative_imbalance());
    EXPECT_NEAR(inside_lm, through_window_lm, 5e-3 * through_window_lm);
    EXPECT_NEAR(emitted, direct_lm, 1e-5 * emitted);
    EXPECT_NEAR(emitted, outside_lm + through_window_lm, 5e-3 * emitted);
    EXPECT_GT(to_photometric(pb.escaped), 0.2 * emitted); // the outside reflects to the sky
    EXPECT_LT(std::abs(pb.relative_imbalance()), 5e-3);
}

INSTANTIATE_TEST_SUITE_P(Methods, SunThroughWindow, ::testing::Values("hierarchical", "shooting"),
                         [](const auto& info) { return test::case_name(info.param); });

} // namespace
} // namespace penumbra
