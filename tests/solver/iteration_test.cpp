// Issue #4: the three iterations of the hierarchical solver (solver.iteration): Jacobi sweeps,
// Gauss–Seidel sweeps by blocks of roots, and progressive shooting on the hierarchy. They
// solve the same linear system of the same links, so they must agree; shooting must show an
// early image that converges to the final one.

#include <algorithm>
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "app/pipeline.h"
#include "common/bake_util.h"
#include "common/test_util.h"
#include "core/scene_io.h"
#include "mesher/mesher.h"
#include "raytrace/raytrace.h"
#include "solver/solver.h"

namespace penumbra {
namespace {

using test::add_material;

using test::relative_l1;

// The hierarchical solver with \p iteration.
app::BakeResult bake(Scene scene, const char* iteration, int threads = 0) {
    scene.solver.method = SolverMethod::hierarchical;
    scene.solver.iteration = *parse_enum<SolverIteration>(iteration);
    return test::bake(scene, threads);
}

Scene cornell(double max_edge) {
    return test::cornell_box(max_edge);
}

// The Cornell box of 0.15 m elements whose links stay between the roots (ε = 1, no clusters),
// solved to \p residual.
Scene cornell_roots(double residual) {
    Scene scene = cornell(0.15);
    scene.solver.epsilon = 1.0;
    scene.solver.clustering = Clustering::off;
    scene.solver.residual = residual;
    return scene;
}

// ε = 1: the links between the roots are never refined, so every iteration solves exactly the
// same system; converged to 1e-8 they agree to 1e-4 (the tolerance for methods on the
// same elements), here far closer.
TEST(HierarchicalIterations, AgreeOnTheSameLinks) {
    const Scene scene = cornell_roots(1e-8);
    const app::BakeResult jacobi = bake(scene, "jacobi");
    ASSERT_GT(jacobi.mesh.element_count(), 300u);
    for (const char* iteration : {"gauss_seidel", "shooting"}) {
        const app::BakeResult r = bake(scene, iteration);
        ASSERT_EQ(r.mesh.element_count(), jacobi.mesh.element_count()) << iteration;
        EXPECT_EQ(r.stats.links, jacobi.stats.links) << iteration;
        const double e =
            relative_l1(r.solution.radiosity, jacobi.solution.radiosity, jacobi.mesh.element_area);
        EXPECT_LT(e, 1e-5) << iteration;
        const double d = relative_l1(r.solution.irradiance_direct,
                                     jacobi.solution.irradiance_direct, jacobi.mesh.element_area);
        EXPECT_LT(d, 1e-5) << iteration << " (direct irradiance)";
    }
}

// With refinement and with clustering: refinement reads the radiosities, which each iteration
// leaves within the residual of the solution, so the hierarchies could differ by a few links;
// the solutions, compared per input polygon and side (area means of their leaves), agree to
// 1e-4, the tolerance for methods on the same elements (measured: 1.4e-7).
TEST(HierarchicalIterations, AgreeWithRefinementAndClusters) {
    Scene scene = cornell(0.1);
    scene.solver.epsilon = 1e-2;
    scene.solver.clustering = Clustering::on;
    scene.solver.residual = 1e-6;
    auto root_means = [](const app::BakeResult& r) {
        std::vector<double> area(r.mesh.element_count());
        std::vector<Rgb> b;
        std::vector<double> sum_area;
        // Leaves carry the root mesh's polygon ids; compare per polygon and side.
        for (std::size_t e = 0; e < r.mesh.element_count(); ++e) {
            const Patch& p = r.mesh.patch_of(std::uint32_t(e));
            const std::size_t key = p.polygon * 2 + (p.back ? 1 : 0);
            if (key >= b.size()) {
                b.resize(key + 1);
                sum_area.resize(key + 1, 0.0);
            }
            b[key] += r.solution.radiosity[e] * float(r.mesh.element_area[e]);
            sum_area[key] += r.mesh.element_area[e];
        }
        for (std::size_t k = 0; k < b.size(); ++k)
            if (sum_area[k] > 0)
                b[k] = b[k] * float(1.0 / sum_area[k]);
        return std::make_pair(b, sum_area);
    };
    const app::BakeResult jacobi = bake(scene, "jacobi");
    const auto [ref, area] = root_means(jacobi);
    for (const char* iteration : {"gauss_seidel", "shooting"}) {
        const app::BakeResult r = bake(scene, iteration);
        const auto [b, a] = root_means(r);
        ASSERT_EQ(b.size(), ref.size());
        EXPECT_LT(relative_l1(b, ref, area), 1e-4) << iteration;
        EXPECT_NEAR(r.stats.power.relative_imbalance(), jacobi.stats.power.relative_imbalance(),
                    2e-3)
            << iteration;
    }
}

// Furnace (docs/validation.md §2): B = E / (1 − ρ) at every leaf, within 0.5 %.
class IterationFurnace : public ::testing::TestWithParam<const char*> {};

TEST_P(IterationFurnace, UniformEmissionAndReflectance) {
    Scene scene;
    scene.solver.epsilon = 1e-2;
    const float rho = 0.5f, E = 1.0f;
    auto m = add_material(scene, "furnace", Rgb(rho), Rgb(float(E / k_pi)));
    test::add_room(scene, {0, 0, 0}, {1, 1.5, 0.8}, m);
    scene.mesher.max_edge_length = 0.3;
    scene.solver.min_area = 0.01;
    scene.solver.residual = 1e-6;
    const app::BakeResult r = bake(scene, GetParam());
    const double expected = E / (1 - rho);
    double worst = 0;
    for (std::size_t e = 0; e < r.mesh.element_count(); ++e)
        if (!r.mesh.patch_of(std::uint32_t(e)).back)
            worst = std::max(worst, std::abs(r.solution.radiosity[e].g - expected) / expected);
    EXPECT_LT(worst, 0.005);
}

INSTANTIATE_TEST_SUITE_P(Iterations, IterationFurnace,
                         ::testing::Values("gauss_seidel", "shooting"),
                         [](const auto& info) { return test::case_name(info.param); });

// Gauss–Seidel blocks and the shots' order depend on the scene alone.
TEST(HierarchicalIterations, IdenticalFor1And2And4Threads) {
    Scene scene = cornell(0.2);
    scene.solver.epsilon = 1e-2;
    scene.solver.clustering = Clustering::on;
    for (const char* iteration : {"gauss_seidel", "shooting"}) {
        std::vector<app::BakeResult> results;
        for (int threads : {1, 2, 4})
            results.push_back(bake(scene, iteration, threads));
        for (std::size_t i = 1; i < results.size(); ++i) {
            const auto& a = results[0].solution.radiosity;
            const auto& b = results[i].solution.radiosity;
            ASSERT_EQ(a.size(), b.size()) << iteration;
            EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(Rgb)), 0) << iteration;
            EXPECT_EQ(results[i].stats.links, results[0].stats.links) << iteration;
            EXPECT_EQ(results[i].stats.shots, results[0].stats.shots) << iteration;
        }
    }
}

// Gauss–Seidel takes fewer sweeps than Jacobi to the same residual (it uses this sweep's
// radiosities where they are ready): the reason to offer it.
TEST(HierarchicalIterations, GaussSeidelNeedsFewerSweeps) {
    const Scene scene = cornell_roots(1e-6);
    const app::BakeResult jacobi = bake(scene, "jacobi");
    const app::BakeResult gs = bake(scene, "gauss_seidel");
    EXPECT_LT(double(gs.stats.shots), 0.8 * double(jacobi.stats.shots))
        << "Gauss–Seidel " << gs.stats.shots << " sweeps, Jacobi " << jacobi.stats.shots;
}

// The early image: snapshots every K shots on the input elements. Their error against the
// final solution (area-weighted L1) falls from snapshot to snapshot, and the first already
// holds the direct light (error < 50 %).
TEST(HierarchicalIterations, ShootingShowsAnEarlyImage) {
    Scene scene = cornell_roots(1e-6); // the roots are the elements the snapshots are on
    scene.solver.iteration = SolverIteration::shooting;
    const Context ctx = test::quiet_context(0);
    const RadiosityMesh mesh = mesher::build_mesh(scene, ctx);
    raytrace::EmbreeScene rt(mesh);
    std::vector<std::vector<Rgb>> snapshots;
    std::vector<Rgb> last;
    solver::SolveObserver observer;
    observer.every_shots = std::int64_t(mesh.element_count() / 4);
    observer.on_pass = [&](const Solution& s, std::int64_t, double, bool final) {
        (final ? last : snapshots.emplace_back()) = s.radiosity;
    };
    solver::SolveStats stats;
    solver::solve(scene, mesh, rt, ctx, &stats, &observer, nullptr);
    ASSERT_EQ(last.size(), mesh.element_count()); // the final call, on the input elements
    ASSERT_GE(snapshots.size(), 3u);
    double previous = 1e30;
    for (std::size_t i = 0; i < snapshots.size(); ++i) {
        const double e = relative_l1(snapshots[i], last, mesh.element_area);
        if (i == 0) {
            EXPECT_LT(e, 0.5);
        }
        EXPECT_LT(e, previous) << "snapshot " << i;
        previous = e;
    }
    EXPECT_LT(previous, 0.02);
}

} // namespace
} // namespace penumbra
