// Diffuse transmission (Radiance's `trans`, issue #30) through the whole pipeline and every
// solver: a side's radiosity gains τ times the other side's irradiance. Checked against two
// closed forms: a furnace whose translucent partition keeps the enclosure uniform, and a
// translucent sheet under a uniform sky seen from a point below it.

#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "app/pipeline.h"
#include "common/bake_util.h"
#include "common/test_util.h"
#include "core/enum_names.h"
#include "core/scene.h"

namespace penumbra {
namespace {

using test::add_material;
using test::add_rect;

// The solver configurations that must all transport τ: the hierarchical solver with each of
// its iterations, and the methods on the mesh's elements.
struct Method {
    const char* name;
    SolverMethod method;
    SolverIteration iteration = SolverIteration::jacobi;
};

const Method k_methods[] = {
    {"hierarchical_jacobi", SolverMethod::hierarchical, SolverIteration::jacobi},
    {"hierarchical_gauss_seidel", SolverMethod::hierarchical, SolverIteration::gauss_seidel},
    {"hierarchical_shooting", SolverMethod::hierarchical, SolverIteration::shooting},
    {"shooting", SolverMethod::shooting},
    {"jacobi", SolverMethod::jacobi},
    {"gauss_seidel", SolverMethod::gauss_seidel},
    {"matrix", SolverMethod::matrix},
};

app::BakeResult bake_with(Scene scene, const Method& m) {
    scene.solver.method = m.method;
    scene.solver.iteration = m.iteration;
    return test::bake(scene);
}

std::uint32_t add_translucent(Scene& scene, const std::string& name, float rho, float tau,
                              Rgb emission = {}) {
    const auto id = add_material(scene, name, Rgb(rho), emission, true);
    scene.materials[id].diffuse_transmittance = Rgb(tau);
    scene.materials[id].emission_two_sided = !emission.is_black();
    return id;
}

class DiffuseTransmission : public ::testing::TestWithParam<Method> {};

// A closed room of reflectance ρ emitting E everywhere has B = E / (1 − ρ) on every wall
// (docs/validation.md §2). A partition inside it emitting E on both sides with ρ_p + τ_p = ρ
// keeps that: each side's B = E + ρ_p H + τ_p H_other = E + ρ B. Without τ it would read
// E + ρ_p B (1.4 E here instead of 2 E). The balance closes with (1 − ρ − τ) absorbed.
TEST_P(DiffuseTransmission, FurnaceWithTranslucentPartitionStaysUniform) {
    Scene scene;
    const float rho = 0.5f, emitted = 1.0f; // W/m²
    const Rgb radiance(float(emitted / k_pi));
    const auto walls = add_material(scene, "walls", Rgb(rho), radiance);
    const auto partition = add_translucent(scene, "partition", 0.2f, 0.3f, radiance);
    test::add_room(scene, {0, 0, 0}, {1, 1.5, 0.8}, walls);
    add_rect(scene, "partition", partition, {0.5, 0.2, 0.1}, {0, 1.1, 0}, {0, 0, 0.6});
    scene.mesher.max_edge_length = 0.25;
    scene.mesher.discontinuity.enabled = false; // every wall emits: no shadow lines to follow
    scene.solver.min_area = 0.01;
    scene.solver.epsilon = 1e-2;
    scene.solver.residual = 1e-6;
    const app::BakeResult r = bake_with(scene, GetParam());
    const double expected = emitted / (1 - rho);
    double worst_partition = 0, wall_error = 0, wall_area = 0;
    std::size_t partition_elements = 0;
    for (std::size_t e = 0; e < r.mesh.element_count(); ++e) {
        const Patch& p = r.mesh.patch_of(std::uint32_t(e));
        const double error = std::abs(r.solution.radiosity[e].g - expected) / expected;
        if (p.material == partition) {
            ++partition_elements;
            worst_partition = std::max(worst_partition, error);
        } else if (!p.back) { // the room's outside sees nothing
            wall_error += error * r.mesh.element_area[e];
            wall_area += r.mesh.element_area[e];
        }
    }
    EXPECT_GT(partition_elements, 8u);
    // Both sides of the partition, each element: 1 %. The walls in the area mean: 1 %
    // (measured 0.66 % hierarchical, less on the elements); their elements right under the
    // partition's edge see it edge-on at 0.1 m, where form factors err by a few % with or
    // without τ.
    EXPECT_LT(worst_partition, 0.01) << GetParam().name;
    EXPECT_LT(wall_error / wall_area, 0.01) << GetParam().name;
    EXPECT_LT(std::abs(r.stats.power.relative_imbalance()), 0.01) << GetParam().name;
}

// Irradiance at a point below the centre from a parallel a × b rectangle whose corner lies
// above the point at height d (Howell's catalogue, C-11): the view factor of one quarter.
double corner_view_factor(double a, double b, double d) {
    const double x = a / d, y = b / d;
    const double sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
    return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2 * k_pi);
}

// A translucent sheet (ρ 0.3, τ 0.5) under a uniform sky of radiance L, nothing below it: its
// top receives π L, its underside sends τ π L. A point below it facing up receives the sky
// beside the sheet and the underside: E = π L (1 − F) + τ π L F, F its view factor of the
// sheet. The underside's vertices carry B = τ π L.
TEST_P(DiffuseTransmission, SheetUnderUniformSky) {
    const double radiance = 10.0, tau = 0.5, half = 1.0, height = 0.5;
    Scene scene;
    const auto sheet = add_translucent(scene, "sheet", 0.3f, float(tau));
    add_rect(scene, "sheet", sheet, {-half, -half, height}, {2 * half, 0, 0}, {0, 2 * half, 0});
    scene.sky = Sky{};
    scene.sky->model = UniformSky{};
    scene.sky->zenith_radiance = radiance;
    scene.sensors.push_back({"below", {0, 0, 0}, {0, 0, 1}});
    scene.mesher.max_edge_length = 0.5;
    const app::BakeResult r = bake_with(scene, GetParam());
    ASSERT_EQ(r.sensors.size(), 1u);
    const double f = 4 * corner_view_factor(half, half, height);
    const double expected = k_pi * radiance * (1 - f + tau * f);
    // The sensors' sky quadrature: 0.5 % (docs/daylight.md); without τ this reads 0.29 of it.
    EXPECT_NEAR(r.sensors[0].irradiance_total.g / expected, 1.0, 5e-3) << GetParam().name;
    double worst = 0;
    for (std::size_t v = 0; v < r.mesh.vertex_count(); ++v)
        if (r.mesh.patches[r.mesh.vertex_patch[v]].back)
            worst = std::max(
                worst, std::abs(r.solution.vertex_radiosity[v].g / (tau * k_pi * radiance) - 1.0));
    EXPECT_LT(worst, 5e-3) << GetParam().name;
}

INSTANTIATE_TEST_SUITE_P(Methods, DiffuseTransmission, ::testing::ValuesIn(k_methods),
                         [](const auto& info) { return test::case_name(info.param.name); });

} // namespace
} // namespace penumbra
