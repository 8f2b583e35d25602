// Issue #26: a hierarchical system built once is solved for other source terms on its fixed
// links (solver/src/hierarchical_system.h). Radiosity is linear in the emission, so on the
// same links the solution for the sum of two emission sets is the sum of their solutions,
// up to where each solve stopped; and a solve depends on its sources alone.

#include <cmath>
#include <cstring>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "common/bake_util.h"
#include "common/test_util.h"
#include "hierarchical_system.h"
#include "mesher/mesher.h"
#include "raytrace/raytrace.h"

namespace penumbra {
namespace {

using solver::HierarchicalSystem;
using solver::SourceTerms;

/// Σ A |a + b − sum| / Σ A |sum| over the leaves (channels summed).
double linearity_error(const solver::Hierarchy& h, const std::vector<Rgb>& a,
                       const std::vector<Rgb>& b, const std::vector<Rgb>& sum) {
    double diff = 0, norm = 0;
    for (std::uint32_t n = 0; n < h.size(); ++n) {
        if (!h.is_leaf(n))
            continue;
        const Rgb d = a[n] + b[n] - sum[n];
        diff += h.area[n] * (double(std::abs(d.r)) + std::abs(d.g) + std::abs(d.b));
        norm += h.area[n] * double(sum[n].sum());
    }
    return diff / norm;
}

bool same_bits(const std::vector<Rgb>& a, const std::vector<Rgb>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Rgb)) == 0;
}

class HierarchicalSystemSources : public ::testing::TestWithParam<Clustering> {};

TEST_P(HierarchicalSystemSources, SolvesAreLinearAndRepeatable) {
    Scene scene = test::cornell_box(0.25);
    scene.solver.epsilon = 3e-3;
    scene.solver.clustering = GetParam();
    const Context ctx = test::quiet_context();
    const RadiosityMesh mesh = mesher::build_mesh(scene, ctx);
    const raytrace::EmbreeScene embree(mesh);
    ProgressStage progress(ctx, "hierarchical");
    solver::SweepLog log{mesh, nullptr, nullptr};
    const std::unique_ptr<HierarchicalSystem> system =
        solver::build_hierarchical(scene, mesh, embree, ctx, progress, log, nullptr);
    ASSERT_GT(system->h.size(), system->h.root_count); // refined
    EXPECT_EQ(system->clusters.enabled, GetParam() == Clustering::on);

    // The lamp, and a coloured glow from the surfaces of the first element's patch.
    const SourceTerms lamp = solver::current_sources(*system);
    SourceTerms glow = lamp;
    for (std::size_t r = 0; r < glow.emission.size(); ++r)
        glow.emission[r] =
            mesh.element_patch[r] == mesh.element_patch[0] ? Rgb(0.2f, 0.5f, 0.1f) : Rgb{};
    SourceTerms both = lamp;
    for (std::size_t r = 0; r < both.emission.size(); ++r)
        both.emission[r] += glow.emission[r];

    SolverSettings settings = scene.solver;
    settings.residual = 1e-6;
    const std::size_t links = system->links.link_count(), nodes = system->h.size();
    auto solve = [&](const SourceTerms& sources) {
        const solver::Solved s = solver::solve_sources(*system, sources, settings, log);
        EXPECT_FALSE(s.limit_hit);
        return system->values;
    };
    const solver::NodeValues first = solve(lamp);
    const solver::NodeValues second = solve(glow);
    const solver::NodeValues sum = solve(both);
    const solver::NodeValues again = solve(lamp);
    EXPECT_EQ(system->links.link_count(), links); // no refinement
    EXPECT_EQ(system->h.size(), nodes);

    // Each solve stops once a sweep changes the radiosities by less than the residual of
    // the emitted power, so the sum of two solutions is the solution of the sum within the
    // residual (measured: 7e-8 without clusters, 2.5e-7 with, at a residual of 1e-6).
    const double error = linearity_error(system->h, first.b, second.b, sum.b);
    std::printf("clustering %s: %zu nodes, %zu links, linearity error %.2e\n",
                std::string(enum_name(GetParam())).c_str(), nodes, links, error);
    EXPECT_LT(error, settings.residual);
    EXPECT_GT(linearity_error(system->h, first.b, first.b, sum.b), 0.1); // the test sees
    EXPECT_TRUE(same_bits(first.b, again.b));
    EXPECT_TRUE(same_bits(first.h_direct, again.h_direct));
    EXPECT_TRUE(same_bits(first.h_indirect, again.h_indirect));
}

INSTANTIATE_TEST_SUITE_P(Clustering, HierarchicalSystemSources,
                         ::testing::Values(Clustering::off, Clustering::on),
                         [](const ::testing::TestParamInfo<Clustering>& info) {
                             return std::string(enum_name(info.param));
                         });

} // namespace
} // namespace penumbra
