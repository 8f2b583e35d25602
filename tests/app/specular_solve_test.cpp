// Light that reaches a diffuse surface through a specular one is in the radiosity solution
// (issue #28): a point light between a diffuse floor and a mirror above it. The floor's
// indirect irradiance is then the mirror image source's, R I cos θ / d² (the floor sees
// nothing else the solver does not treat as black), whose mean over the floor is R I Ω / A
// with Ω the floor's solid angle from the image; the floor reflects 1 %, so that the light it
// sends itself through the mirror (D S D, about 0.8 × 0.01 × 24 W/m² × a view factor of 0.07
// to its image 2 m away: 0.4 % of the image's) stays well inside the tolerance.

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/bake_util.h"
#include "common/test_util.h"
#include "core/scene.h"

namespace penumbra {
namespace {

constexpr double k_light_height = 0.5, k_mirror_height = 1.0, k_floor_side = 1.0;
constexpr double k_intensity_w_sr = 10, k_mirror_reflectance = 0.8;

Scene point_light_under_mirror() {
    Scene scene;
    const auto floor = test::add_material(scene, "floor", Rgb(0.01f), {}, false);
    const auto mirror =
        test::add_lobe_material(scene, "mirror", Mirror{Rgb(float(k_mirror_reflectance))});
    const double h = k_floor_side / 2;
    test::add_rect(scene, "floor", floor, {-h, -h, 0}, {k_floor_side, 0, 0}, {0, k_floor_side, 0});
    // Three times the floor's side, facing down: every floor point sees the image through it.
    test::add_rect(scene, "mirror", mirror, {-3 * h, -3 * h, k_mirror_height},
                   {0, 3 * k_floor_side, 0}, {3 * k_floor_side, 0, 0});
    PointLight light;
    light.name = "lamp";
    light.position = {0, 0, k_light_height};
    light.intensity = Rgb(float(k_intensity_w_sr));
    scene.point_lights.push_back(light);
    scene.render.caustic_photons = 20000;
    return scene;
}

/// Σ H_indirect A / Σ A over the floor's elements, channel mean.
double floor_mean_indirect(const app::BakeResult& baked) {
    double flux = 0, area = 0;
    for (std::uint32_t e = 0; e < baked.mesh.element_count(); ++e) {
        if (baked.mesh.patch_of(e).material != 0)
            continue;
        const double a = baked.mesh.element_area[e];
        const Rgb h = baked.solution.irradiance_indirect[e];
        flux += (double(h.r) + h.g + h.b) / 3 * a;
        area += a;
    }
    return flux / area;
}

TEST(SpecularSolve, FloorIrradianceIsTheMirrorImageSource) {
    const app::BakeResult baked = test::bake(point_light_under_mirror());
    // A square of side a seen from height d above its centre: Ω = 4 asin(a² / (a² + 4d²)).
    const double d = 2 * k_mirror_height - k_light_height, a = k_floor_side;
    const double omega = 4 * std::asin(a * a / (a * a + 4 * d * d));
    const double expected = k_mirror_reflectance * k_intensity_w_sr * omega / (a * a);
    // 20000 photons of equal power land on the floor: 1/√20000 = 0.7 % of noise.
    EXPECT_NEAR(floor_mean_indirect(baked), expected, 0.03 * expected);
}

// A diffuse floor that emits E and reflects ρ, under a mirror ceiling of reflectance R, in
// walls of perfect mirrors: unfolded, an infinite floor under an infinite mirror, so that all
// the light leaving the floor comes back to it after one bounce off the ceiling. Its
// irradiance is then uniform and H = R (E + ρ H) = R E / (1 − ρ R): light that crosses the
// mirror any number of times (L S D, then D S D, D S D S D, ...). The sources' photons alone
// give R E (−40 % here), one D S D pass R E (1 + ρ R) (−16 %).
constexpr double k_floor_exitance_w_m2 = 1.0, k_floor_reflectance = 0.5;

Scene emitting_floor_in_mirrors() {
    Scene scene;
    const auto floor = test::add_material(scene, "floor", Rgb(float(k_floor_reflectance)),
                                          Rgb(float(k_floor_exitance_w_m2 / k_pi)), false);
    const auto mirror = [&](const std::string& name, float r) {
        return test::add_lobe_material(scene, name, Mirror{Rgb(r)});
    };
    const auto ceiling = mirror("ceiling", float(k_mirror_reflectance));
    const auto wall = mirror("wall", 1.0f);
    // Four times as wide as high: a photon meets the walls about tan θ / 2 times on its way
    // there and back, so that max_bounces (16) loses only those beyond 88° (0.1 %).
    const double a = 2.0, h = 0.5;
    test::add_rect(scene, "floor", floor, {0, 0, 0}, {a, 0, 0}, {0, a, 0});
    test::add_rect(scene, "ceiling", ceiling, {0, 0, h}, {0, a, 0}, {a, 0, 0});
    test::add_rect(scene, "wall_x0", wall, {0, 0, 0}, {0, a, 0}, {0, 0, h});
    test::add_rect(scene, "wall_x1", wall, {a, 0, 0}, {0, 0, h}, {0, a, 0});
    test::add_rect(scene, "wall_y0", wall, {0, 0, 0}, {0, 0, h}, {a, 0, 0});
    test::add_rect(scene, "wall_y1", wall, {0, a, 0}, {a, 0, 0}, {0, 0, h});
    scene.mesher.max_edge_length = 0.5;
    scene.render.caustic_photons = 20000;
    return scene;
}

class SpecularSolveIterations : public ::testing::TestWithParam<SolverIteration> {};

// Every iteration carries the transfers to convergence (shooting ends with sweeps for them).
TEST_P(SpecularSolveIterations, LightCrossingMirrorsAnyNumberOfTimesConverges) {
    Scene scene = emitting_floor_in_mirrors();
    scene.solver.iteration = GetParam();
    const app::BakeResult baked = test::bake(scene);
    const double rho_r = k_floor_reflectance * k_mirror_reflectance;
    const double expected = k_mirror_reflectance * k_floor_exitance_w_m2 / (1 - rho_r);
    // 20000 photons land on the floor in each of the two sets: under 1 % of noise.
    EXPECT_NEAR(floor_mean_indirect(baked), expected, 0.02 * expected);
}

INSTANTIATE_TEST_SUITE_P(SpecularSolve, SpecularSolveIterations,
                         ::testing::Values(SolverIteration::jacobi, SolverIteration::shooting),
                         [](const auto& info) { return std::string(enum_name(info.param)); });

// A re-solve (--reuse) traces the transfers from the saved radiosities, those of another
// floor reflectance, and still carries them to the changed scene's convergence.
TEST(SpecularSolve, ResolveAfterAReflectanceChangeConverges) {
    Scene before = emitting_floor_in_mirrors();
    before.materials[0].reflectance = Rgb(0.2f);
    const app::BakeResult first = test::bake(before);
    ASSERT_TRUE(first.solver_state);
    const app::BakeResult resolved =
        test::bake(emitting_floor_in_mirrors(), 0, first.solver_state.get());
    const double rho_r = k_floor_reflectance * k_mirror_reflectance;
    const double expected = k_mirror_reflectance * k_floor_exitance_w_m2 / (1 - rho_r);
    const double before_expected =
        k_mirror_reflectance * k_floor_exitance_w_m2 / (1 - 0.2 * k_mirror_reflectance);
    EXPECT_NEAR(floor_mean_indirect(first), before_expected, 0.02 * before_expected);
    EXPECT_NEAR(floor_mean_indirect(resolved), expected, 0.02 * expected);
}

TEST(SpecularSolve, SolutionDoesNotDependOnTheThreadCount) {
    const Scene scene = point_light_under_mirror();
    const app::BakeResult one = test::bake(scene, 1), two = test::bake(scene, 2);
    ASSERT_EQ(one.solution.vertex_radiosity.size(), two.solution.vertex_radiosity.size());
    for (std::size_t v = 0; v < one.solution.vertex_radiosity.size(); ++v) {
        EXPECT_EQ(one.solution.vertex_radiosity[v].r, two.solution.vertex_radiosity[v].r);
        EXPECT_EQ(one.solution.vertex_radiosity[v].g, two.solution.vertex_radiosity[v].g);
        EXPECT_EQ(one.solution.vertex_radiosity[v].b, two.solution.vertex_radiosity[v].b);
    }
    EXPECT_GT(floor_mean_indirect(one), 0.0);
}

} // namespace
} // namespace penumbra
