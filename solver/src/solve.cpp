// Method dispatch and the power balance of gathered solutions.

#include "solver/solver.h"

#include <algorithm>

#include "core/error.h"
#include "core/parallel.h"
#include "hierarchical.h"
#include "progressive/fixed_system.h"
#include "sources/point_lights.h"

namespace penumbra::solver {

namespace {

SolveResult solve_fixed(const Scene& scene, const RadiosityMesh& mesh,
                        const VisibilityQuery& visibility, const Context& ctx, SolveStats* stats,
                        const SolveObserver* observer) {
    const SolverMethod method = scene.solver.method;
    return run_in_arena(ctx, [&] {
        ElementGeometry geo(mesh);
        RowSettings rows;
        rows.visibility_rays = scene.solver.visibility_rays;
        rows.seed = ctx.seed;
        FixedSystem system = build_fixed_system(scene, mesh, geo, visibility, rows, ctx);
        ElementResult er = method == SolverMethod::matrix
                               ? solve_matrix(system, geo, ctx, stats)
                               : solve_gathering(system, geo, scene.solver,
                                                 method != SolverMethod::jacobi, ctx, stats);
        SolveResult result;
        result.solution = make_solution(scene, mesh, geo, std::move(er), visibility, rows, ctx);
        if (observer && observer->on_pass)
            observer->on_pass(result.solution, stats ? stats->shots : 0, 0.0, true);
        return result;
    });
}

// The escape rays of each leaf that is not an emitter (emitters take escape_rays_emitter):
// k_escape_budget in all, shared in proportion to the leaves' power A·B, 4 to 4096 a leaf, a
// multiple of 4 so that each of a leaf's 4 quadrature points starts as many. The balance sums
// A·B·escape: shares in proportion to the terms give that sum its least variance. 16 rays a
// leaf alike left the Cornell box's escaped power 0.3 % of the emitted power apart from seed to
// seed, its few big, bright ceiling leaves counting most (docs/calibration.md#k_escape_budget).
std::vector<int> escape_rays_by_power(const ElementGeometry& geo, const Solution& solution) {
    constexpr double k_escape_budget = double(std::size_t(1) << 20);
    constexpr int k_min_rays = 4, k_max_rays = 4096;
    std::vector<double> power(geo.size(), 0.0);
    double total = 0;
    for (std::size_t e = 0; e < geo.size(); ++e) { // in order: the same sum for every thread count
        if (!geo.emitter[e])
            power[e] = geo.area[e] * std::max(to_photometric(solution.radiosity[e]), 0.0);
        total += power[e];
    }
    std::vector<int> rays(geo.size(), k_min_rays);
    for (std::size_t e = 0; total > 0 && e < geo.size(); ++e) {
        const double share = std::min(k_escape_budget * power[e] / total, double(k_max_rays));
        rays[e] = std::max(k_min_rays, int(share) / 4 * 4);
    }
    return rays;
}

} // namespace

PowerBalance hierarchical_balance(const Scene& scene, const RadiosityMesh& mesh,
                                  const ElementGeometry& geo, const Solution& solution,
                                  const VisibilityQuery& visibility, const RowSettings& rows,
                                  double unconverged_fraction, const RgbD& distant_delivered) {
    PowerBalance pb;
    const std::vector<int> rays = escape_rays_by_power(geo, solution);
    std::vector<double> escape(mesh.element_count(), 0.0);
    parallel_for_index(mesh.element_count(), 64, [&](std::size_t e) {
        RowSettings escape_rows = rows;
        escape_rows.escape_rays = rays[e];
        if (!solution.radiosity[e].is_black())
            escape[e] = escape_fraction(geo, visibility, std::uint32_t(e), escape_rows);
    });
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
        const Patch& p = mesh.patch_of(std::uint32_t(e));
        pb.emitted += RgbD(p.emission) * geo.area[e];
        pb.escaped += RgbD(solution.radiosity[e]) * (geo.area[e] * escape[e]);
        pb.receive(p, RgbD(solution.irradiance_direct[e]) + RgbD(solution.irradiance_indirect[e]),
                   geo.area[e]);
    }
    for (std::uint32_t l = 0; l < scene.point_lights.size(); ++l) {
        const PointLight& light = scene.point_lights[l];
        const RgbD power = light.power();
        pb.emitted += power;
        pb.escaped +=
            power * light_escape_fraction(geo, visibility, light, PointSource{l}, rows.seed);
    }
    pb.emitted += distant_delivered; // the power of the sun and sky is what they deliver
    pb.residual = pb.emitted * unconverged_fraction;
    return pb;
}

SolveResult solve(const Scene& scene, const RadiosityMesh& mesh, const VisibilityQuery& visibility,
                  const Context& ctx, SolveStats* stats, const SolveObserver* observer,
                  const HierarchicalState* reuse, const SpecularLight* specular) {
    switch (scene.solver.method) {
    case SolverMethod::hierarchical:
        return run_in_arena(ctx, [&] {
            return solve_hierarchical(scene, mesh, visibility, ctx, stats, observer, reuse,
                                      specular);
        });
    case SolverMethod::shooting:
    case SolverMethod::jacobi:
    case SolverMethod::gauss_seidel:
    case SolverMethod::matrix:
        break;
    }
    if (reuse)
        throw ConfigError(fmt::format("a saved solver state is reused by the hierarchical "
                                      "method only, not '{}'",
                                      enum_name(scene.solver.method)));
    if (specular && !specular->empty())
        ctx.warn("solver.method '{}' leaves the light that reaches diffuse surfaces through "
                 "specular ones out of the solution (the hierarchical method has it)",
                 enum_name(scene.solver.method));
    if (scene.solver.method == SolverMethod::shooting) {
        SolveResult result;
        result.solution = solve_shooting(scene, mesh, visibility, ctx, stats, observer);
        return result;
    }
    return solve_fixed(scene, mesh, visibility, ctx, stats, observer);
}

} // namespace penumbra::solver
