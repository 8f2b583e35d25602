// Issue #4: hierarchical radiosity and the fixed-element methods, end to end through the
// pipeline. Reference values: docs/validation.md (sections given per test).

#include <algorithm>
#include <cmath>
#include <cstring>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "app/pipeline.h"
#include "common/bake_util.h"
#include "common/test_util.h"
#include "core/scene_io.h"

namespace penumbra {
namespace {

using test::add_material;

using test::bake;
using test::relative_l1;

Scene cornell(double max_edge) {
    return test::cornell_box(max_edge);
}

// Σ A |B − B_ref| / Σ A B_ref over elements and channels (the same mesh).
double relative_l1(const app::BakeResult& r, const app::BakeResult& ref) {
    return relative_l1(r.solution.radiosity, ref.solution.radiosity, ref.mesh.element_area);
}

TEST(FixedElementMethods, ShootingJacobiGaussSeidelAndMatrixAgree) {
    Scene scene = cornell(0.15);
    scene.solver.residual = 1e-8;
    scene.solver.method = SolverMethod::matrix;
    const app::BakeResult reference = bake(scene);
    ASSERT_GT(reference.mesh.element_count(), 300u);
    for (const char* method : {"shooting", "jacobi", "gauss_seidel"}) {
        scene.solver.method = *parse_enum<SolverMethod>(method);
        const app::BakeResult r = bake(scene);
        ASSERT_EQ(r.mesh.element_count(), reference.mesh.element_count());
        EXPECT_LT(relative_l1(r, reference), 1e-4) << method;
    }
}

// Radiosity of the hierarchical leaf containing each reference element's centroid, compared
// area-weighted with the reference.
double hierarchical_error(const app::BakeResult& hr, const app::BakeResult& ref) {
    double diff = 0, norm = 0;
    for (std::size_t e = 0; e < ref.mesh.element_count(); ++e) {
        const Patch& patch = ref.mesh.patch_of(std::uint32_t(e));
        const Vec3 c = ref.mesh.centroid(std::uint32_t(e));
        std::vector<Rgb> leaf_values(hr.mesh.vertex_count());
        for (std::size_t k = 0; k < hr.mesh.element_count(); ++k) {
            if (hr.mesh.element_patch[k] != ref.mesh.element_patch[e])
                continue;
            const auto& t = hr.mesh.triangles[k];
            Vec3 a = hr.mesh.vertex(t[0]), b = hr.mesh.vertex(t[1]), d = hr.mesh.vertex(t[2]);
            Vec3 n = cross(b - a, d - a);
            double w1 = dot(cross(c - a, d - a), n) / dot(n, n);
            double w2 = dot(cross(b - a, c - a), n) / dot(n, n);
            if (w1 < -1e-9 || w2 < -1e-9 || w1 + w2 > 1 + 1e-9)
                continue;
            const double area = ref.mesh.element_area[e];
            diff += area *
                    std::abs(double((hr.solution.radiosity[k] - ref.solution.radiosity[e]).sum()));
            norm += area * double(ref.solution.radiosity[e].sum());
            break;
        }
        (void)patch;
    }
    return diff / norm;
}

TEST(Hierarchical, ErrorAgainstMatrixSolveFallsAsEpsilonShrinks) {
    Scene fine = cornell(0.06);
    fine.solver.method = SolverMethod::matrix;
    const app::BakeResult reference = bake(fine);
    double previous = 1e30;
    for (double eps : {1e-2, 3e-3, 1e-3}) {
        Scene scene = cornell(0.25);
        scene.solver.epsilon = eps;
        scene.solver.min_area = 0.06 * 0.06 / 2; // the reference's element size
        scene.solver.residual = 1e-5;
        const app::BakeResult hr = bake(scene);
        const double error = hierarchical_error(hr, reference);
        std::printf("epsilon %.0e: %zu leaves, %llu links, error %.4f\n", eps,
                    hr.mesh.element_count(), (unsigned long long)hr.stats.links, error);
        EXPECT_LT(error, previous) << "epsilon " << eps;
        previous = error;
    }
}

class HierarchicalFurnace : public ::testing::TestWithParam<double> {};

TEST_P(HierarchicalFurnace, UniformEmissionAndReflectance) {
    Scene scene;
    scene.solver.epsilon = GetParam();
    const float rho = 0.5f, E = 1.0f;
    auto m = add_material(scene, "furnace", Rgb(rho), Rgb(float(E / k_pi)));
    test::add_room(scene, {0, 0, 0}, {1, 1.5, 0.8}, m);
    scene.mesher.max_edge_length = 0.3;
    scene.solver.min_area = 0.01; // two levels below the roots (0.02–0.05 m²): fast enough
    scene.solver.residual = 1e-6;
    const app::BakeResult r = bake(scene);
    const std::int32_t levels =
        *std::max_element(r.mesh.element_level.begin(), r.mesh.element_level.end());
    EXPECT_EQ(levels, GetParam() < 1 ? 2 : 0);
    const double expected = E / (1 - rho);
    double worst = 0;
    std::size_t worst_e = 0;
    for (std::size_t e = 0; e < r.mesh.element_count(); ++e) {
        if (r.mesh.patch_of(std::uint32_t(e)).back)
            continue;
        const double err = std::abs(r.solution.radiosity[e].g - expected) / expected;
        if (err > worst) {
            worst = err;
            worst_e = e;
        }
    }
    EXPECT_LT(worst, 0.005) << "element " << worst_e << " level " << r.mesh.element_level[worst_e];
}

// ε = 1 never refines: links between the roots, gathering, push-pull and the leaf mesh. With
// refinement, leaves next to edges and corners inherit links whose form factors their
// ancestors average over (each far surface is seen flatter from there): spread evenly, the
// form factors such a leaf gathered summed to up to 1.5 and B was 9 % (ε = 1e-2) and 2.4 %
// (ε = 1e-3) off; the leaf weights (hierarchy/leaf_weights.h) spread them by the leaf's own.
INSTANTIATE_TEST_SUITE_P(Epsilon, HierarchicalFurnace, ::testing::Values(1.0, 1e-2, 1e-3),
                         [](const auto& info) {
                             return test::case_name(fmt::format("{}", info.param));
                         });

// §3, CIE 171 5.6: a uniformly lit 4 × 4 m reflector (ρ = 0.3); the illuminance it causes at
// points 3 m away, over its own illuminance × ρ, is the configuration factor.
TEST(Hierarchical, Cie171ConfigurationFactors) {
    Scene scene;
    auto m = add_material(scene, "reflector", Rgb(0.3f), {}, false);
    test::add_rect(scene, "reflector", m, {0, 0, 0}, {4, 0, 0}, {0, 4, 0}); // faces +z
    PointLight sun_like; // far above: uniform to 1e-5 over the reflector
    sun_like.position = {2, 2, 1000};
    sun_like.intensity = from_photometric(1e10, Rgb(1.0f));
    scene.point_lights.push_back(sun_like);
    const double ys[] = {0.25, 0.75, 1.25, 1.75};
    const double expected[] = {0.2680, 0.3094, 0.3398, 0.3557};
    for (double y : ys)
        scene.sensors.push_back({"p", {2, y, 3}, {0, 0, -1}});
    scene.mesher.max_edge_length = 1.0;
    const app::BakeResult r = bake(scene);
    double lit = 0, area = 0;
    for (std::size_t e = 0; e < r.mesh.element_count(); ++e) {
        lit += to_photometric(r.solution.irradiance_direct[e]) * r.mesh.element_area[e];
        area += r.mesh.element_area[e];
    }
    lit /= area;
    for (std::size_t i = 0; i < 4; ++i) {
        const double factor = r.sensors[i].illuminance_total_lx / (lit * 0.3);
        EXPECT_NEAR(factor, expected[i], 0.01 * expected[i]) << "y = " << ys[i];
    }
}

TEST(Hierarchical, IdenticalFor1And2And4Threads) {
    Scene scene = cornell(0.2);
    scene.solver.epsilon = 1e-2;
    std::vector<app::BakeResult> results;
    for (int threads : {1, 2, 4})
        results.push_back(bake(scene, threads));
    for (std::size_t i = 1; i < results.size(); ++i) {
        const auto& a = results[0].solution.radiosity;
        const auto& b = results[i].solution.radiosity;
        ASSERT_EQ(a.size(), b.size());
        EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(Rgb)), 0);
        EXPECT_EQ(results[i].stats.links, results[0].stats.links);
        EXPECT_EQ(results[i].mesh.element_count(), results[0].mesh.element_count());
    }
}

// The bar moves and a cancel is honoured within a refinement, not only after each refine →
// solve cycle (on a 1 M-triangle floor, the first cycle runs for more than half an hour).
TEST(Hierarchical, ReportsProgressWithinRefinementAndHonoursCancel) {
    Scene scene = cornell(0.2);
    scene.solver.epsilon = 1e-2;
    app::BakeOptions options;
    options.render = false;
    Context ctx = test::quiet_context(2);
    auto progress = std::make_shared<test::RecordingProgress>();
    ctx.progress = progress;
    app::bake(scene, options, ctx);
    const auto stage = std::find(progress->stages.begin(), progress->stages.end(), "hierarchical");
    ASSERT_NE(stage, progress->stages.end());
    const auto index = std::size_t(stage - progress->stages.begin());
    // The update number of the hierarchical stage's first, and that stage's fractions.
    const auto first =
        std::size_t(std::find(progress->stage_of.begin(), progress->stage_of.end(), index) -
                    progress->stage_of.begin());
    std::vector<double> f;
    for (std::size_t k = first; k < progress->fractions.size(); ++k)
        if (progress->stage_of[k] == index)
            f.push_back(progress->fractions[k]);
    EXPECT_TRUE(std::is_sorted(f.begin(), f.end()));
    // The first cycle's share is [0, 0.5]: its refinement passes report inside it (before, the
    // first update came at 0.5, after the cycle's solve).
    ASSERT_GE(std::count_if(f.begin(), f.end(), [](double x) { return x > 0 && x < 0.5; }), 2);
    ASSERT_LT(f.front(), 0.5);

    // Cancelled at the hierarchical stage's first update, a refinement pass of the first
    // cycle: the bake stops there.
    auto cancelling = std::make_shared<test::RecordingProgress>();
    cancelling->cancel_after = first + 1;
    ctx.progress = cancelling;
    EXPECT_THROW(app::bake(scene, options, ctx), Cancelled);
    EXPECT_EQ(cancelling->stages.back(), "hierarchical");
    EXPECT_LT(cancelling->fractions.back(), 0.5);
}

} // namespace
} // namespace penumbra
