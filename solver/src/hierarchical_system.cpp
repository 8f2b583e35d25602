// Building and solving a hierarchical radiosity system (see hierarchical_system.h).
// Reflectors have no radiosity before the first solve, so refinement and solving alternate
// until refinement changes nothing, or next to nothing.

#include "hierarchical_system.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.h"
#include "hierarchy/leaf_weights.h"
#include "state/solver_state.h"

namespace penumbra::solver {

namespace {

constexpr int k_max_cycles = 12;
/// Refine → solve cycles stop once a refinement grows the links and the nodes by less than
/// this fraction: later ones change the solution by next to nothing
/// (docs/calibration.md#k_settled_growth).
constexpr double k_settled_growth = 5e-3;

/// A cycle whose refinement is not the last sweeps to this many times solver.residual: the
/// next refinement asks its radiosities for no more than the oracle's error estimates
/// (docs/calibration.md#k_intermediate_residual).
constexpr double k_intermediate_residual = 4.0;

/// Rounds of weighing the leaves by the last radiosities and solving again after the last
/// cycle (settle_reflected_weights); one or two reach solver.residual on the test scenes.
constexpr int k_max_weight_rounds = 6;

bool settled(std::size_t before, std::size_t after) {
    return double(after) <= double(before) * (1.0 + k_settled_growth);
}

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}
/// A refinement running longer than this logs its progress at every pass this long after
/// the last.
constexpr double k_refine_report_s = 10.0;
/// solver.clustering "auto" clusters meshes with more elements than this.
constexpr std::size_t k_clustering_auto_roots = 3000;
/// Quadrature level of near element pairs that do not touch (16 points; touching ones, and
/// rows of the other methods, take 64). A hierarchical pair is computed once, from its
/// smaller end, and its other link follows by reciprocity, so the fine rule is not needed to
/// keep the two reciprocal as in rows; what it resolves is the steep part of the form factor
/// by a common edge. About as accurate as 64 points, and faster; touching pairs at 16 fail
/// the furnace (docs/calibration.md#k_apart_level).
constexpr int k_apart_level = 2;

double emitted_power_max(const Hierarchy& h, const std::vector<PointLight>& lights) {
    double total = 0;
    for (std::size_t n = 0; n < h.root_count; ++n)
        total += double(h.emission[n].max_component()) * h.area[n];
    for (const PointLight& l : lights)
        total += l.power().max_component();
    return total;
}

// The radiosity scale ε is relative to: the brightest emitter's exitance, or the brightest
// irradiance a point light brings to a root.
double radiosity_scale(const Hierarchy& h, const LinkStore& links) {
    double scale = 0;
    for (std::size_t n = 0; n < h.root_count; ++n)
        scale = std::max(scale, double(h.emission[n].max_component()));
    for (const LightLink& l : links.light_links())
        scale = std::max(scale, double(l.irradiance.max_component()));
    return scale;
}

// A re-solve: the saved hierarchy with the new scene's reflectances, emissions and opacity.
Hierarchy reused_hierarchy(const RadiosityMesh& mesh, const HierarchicalState& state) {
    check_reusable(mesh, state);
    Hierarchy h = state.hierarchy;
    for (std::size_t n = 0; n < h.size(); ++n) {
        const Patch& p = mesh.patches[h.patch[n]];
        h.emission[n] = p.emission;
        h.reflectance[n] = p.reflectance;
        h.transmittance[n] = p.diffuse_transmittance;
        h.opaque[n] = p.opaque() ? 1 : 0;
        h.specular_only[n] = p.specular_only ? 1 : 0;
    }
    return h;
}

/// A minimum area that lets the hierarchy grow past this many times the element budget in
/// leaves is refused: solver.min_area 1e-30 refined without bound.
constexpr double k_leaf_budget_factor = 100.0;

// Leaves are at least a quarter of min_area (a node is split while above it, in four).
void check_min_area(const Scene& scene, const RadiosityMesh& mesh, double min_area) {
    const std::int64_t budget = scene.mesher.element_budget;
    if (budget <= 0)
        return;
    double area = 0;
    for (const double a : mesh.element_area)
        area += a;
    const double most_leaves = 4.0 * area / min_area;
    if (most_leaves <= k_leaf_budget_factor * double(budget))
        return;
    throw ConfigError(fmt::format(
        "solver.min_area {:.3g} m² lets the hierarchy grow to about {:.3g} leaves, over {:g} "
        "times mesher.element_budget ({}): use --min-area {:.2g} or more",
        min_area, most_leaves, k_leaf_budget_factor, budget,
        4.0 * area / (k_leaf_budget_factor * double(budget))));
}

RefineSettings refine_settings(const Scene& scene, const RadiosityMesh& mesh, const Context& ctx) {
    RefineSettings rs;
    rs.oracle = scene.solver.oracle;
    rs.rows.visibility_rays = scene.solver.visibility_rays;
    rs.rows.seed = ctx.seed;
    rs.rows.apart_quadrature_level = k_apart_level;
    rs.offset = 1e-5 * std::max(mesh.scene_diagonal, 1e-3);
    rs.max_memory_bytes = ctx.max_memory_bytes;
    rs.min_area = scene.solver.min_area > 0 ? scene.solver.min_area
                                            : std::pow(mesh.scene_diagonal / 200.0, 2);
    check_min_area(scene, mesh, rs.min_area);
    return rs;
}

// With clustering (solver.clustering, or as the saved state was): the cluster tree, its
// values and the tables its links read.
void make_clusters(HierarchicalSystem& sys, const Scene& scene, const Context& ctx,
                   const HierarchicalState* reuse) {
    const Hierarchy& h = sys.h;
    Clusters& clusters = sys.clusters;
    clusters.enabled = reuse ? reuse->clustered
                             : scene.solver.clustering == Clustering::on ||
                                   (scene.solver.clustering == Clustering::automatic &&
                                    h.root_count > k_clustering_auto_roots);
    if (!clusters.enabled)
        return;
    clusters.tree = build_cluster_tree(h);
    init_cluster_values(clusters.tree, h, sys.values.b, clusters.values);
    const ClusterValues& cv = clusters.values;
    clusters.tables = std::make_unique<ClusterTables>(h, clusters.tree, cv.exitance,
                                                      cv.exitance_emitted, cv.peak, cv.departure);
    ctx.info("hierarchical: {} clusters over {} elements", clusters.tree.size(), h.root_count);
}

// The first links: the cluster tree's (with clustering) or every pair of roots', or the
// saved ones of a re-solve; and the oracle's thresholds.
void link_system(HierarchicalSystem& sys, LinkSet& refiner, const Scene& scene, const Context& ctx,
                 const HierarchicalState* reuse) {
    const Hierarchy& h = sys.h;
    const Clusters& clusters = sys.clusters;
    if (clusters.enabled && !reuse)
        refiner.link_clusters();
    if (reuse) {
        refiner.restore(reuse->links.span(), reuse->cluster_links.span());
        ctx.info("hierarchical: reusing {} nodes and {} links", h.size(), sys.links.link_count());
    } else if (!clusters.enabled) {
        refiner.link_roots();
    }
    refiner.set_threshold(scene.solver.epsilon * radiosity_scale(h, sys.links));
    sys.emitted += sys.distant_power().max_component(); // what the sun and sky deliver
    if (clusters.enabled)
        refiner.set_cluster_threshold(scene.solver.epsilon * sys.emitted / clusters.tree.area[0]);
}

// A re-solve starts from the saved weights (of the same links), their reflected part weighed by
// the saved radiosities, and solves once before refining: the oracle should see the new
// materials' radiosities, and the next weights are weighed by them.
void resolve_saved(HierarchicalSystem& sys, const Scene& scene, const HierarchicalState& reuse,
                   SweepLog& log) {
    NodeValues& v = sys.values;
    if (!reuse.weights.empty()) {
        v.weights = leaf_weights(sys.h, sys.links, v.b, true, reuse.weights);
        v.weights.reflected_solved = false; // weighed by the saved materials' light
        pull_emit(sys.h, v);
    }
    solve_links(sys.h, sys.links, v, sys.clusters, scene.solver, sys.iteration, sys.emitted, log);
    sys.solved = true;
}

const char* pass_name(Iteration iteration) {
    return iteration == Iteration::shooting ? "shots" : "sweeps";
}

// Seconds a cycle took to refine, weigh the leaves and solve.
struct CycleTimes {
    double refine = 0, weights = 0, solve = 0;
};

// Logs a cycle's solve: its times, a sweep limit hit, its nodes and links.
void report_cycle(const Context& ctx, const HierarchicalSystem& sys, int cycle, const Solved& s,
                  double residual, const CycleTimes& t) {
    const char* passes = pass_name(sys.iteration);
    ctx.debug("hierarchical: cycle {}: refine {:.2f} s, leaf weights {:.2f} s, {} {:.2f} s", cycle,
              t.refine, t.weights, passes, t.solve);
    if (s.limit_hit)
        ctx.warn("hierarchical: cycle {} stopped at {} {} (solver.{}) with a change of "
                 "{:.3g} of the emitted power, above its residual {:.3g}",
                 cycle, s.sweeps, passes,
                 sys.iteration == Iteration::shooting ? "max_shots" : "max_sweeps", s.relative,
                 residual);
    ctx.info("hierarchical: cycle {}: {} nodes, {} links ({} element, {} cluster, {} "
             "light), {} {}, change {:.2e}",
             cycle, sys.h.size(), sys.links.link_count(), sys.links.links().size(),
             sys.links.cluster_links().size(), sys.links.light_links().size(), s.sweeps, passes,
             s.relative);
}

// One refine → solve cycle; returns true if it was the last.
// Cycles before \p first_last are not the last, whatever their refinement did.
bool run_cycle(HierarchicalSystem& sys, LinkSet& refiner, const Scene& scene, const Context& ctx,
               ProgressStage& progress, SweepLog& log, int cycle, int first_last) {
    Hierarchy& h = sys.h;
    NodeValues& v = sys.values;
    auto t0 = Clock::now();
    const std::size_t links_before = sys.links.link_count(), nodes_before = h.size();
    // The number of cycles is not known ahead (refinement stops when the radiosities stop
    // asking for it, usually after 3–6): half the bar for the first, which links and
    // refines the most, and half of what is left for each one after it. Within a cycle,
    // the bar moves half way to the cycle's end per refinement pass (their number is not
    // known ahead either), and a long refinement says where it is every
    // k_refine_report_s.
    const double cycle_start = 1.0 - std::pow(0.5, cycle);
    const double cycle_share = std::pow(0.5, cycle + 1);
    auto last_report = t0;
    auto on_pass = [&](const RefinePass& p) {
        progress.update(cycle_start + cycle_share * (1.0 - std::pow(0.5, p.pass)));
        if (seconds_since(last_report) < k_refine_report_s)
            return;
        last_report = Clock::now();
        ctx.info("hierarchical: cycle {}: refining, pass {} ({} links): {} nodes, {} "
                 "element, {} cluster and {} light links after {:.0f} s",
                 cycle, p.pass, p.kind, p.nodes, p.element_links, p.cluster_links, p.light_links,
                 seconds_since(t0));
    };
    if (sys.clusters.enabled)
        weigh_departures(sys.clusters.tree, h, v.b, sys.clusters.values);
    const bool changed = refiner.refine(v.b, v.b_range, on_pass);
    const double refine_s = seconds_since(t0);
    t0 = Clock::now();
    // The first solve's radiosities weigh every leaf's reflected light afresh.
    if (changed || v.weights.empty() || (sys.solved && !v.weights.reflected_solved)) {
        v.weights = leaf_weights(h, sys.links, v.b, sys.solved, v.weights);
        pull_emit(h, v);
    }
    const double weights_s = seconds_since(t0);
    t0 = Clock::now();
    // A refinement that changed nothing, or added next to nothing, is the last: the
    // solution after it stays where the next one would leave it (k_settled_growth). The
    // cycles before it sweep to a looser residual.
    const bool last =
        cycle + 1 == k_max_cycles ||
        (cycle >= first_last && (!changed || (settled(links_before, sys.links.link_count()) &&
                                              settled(nodes_before, h.size()))));
    SolverSettings sweeps = scene.solver;
    if (!last)
        sweeps.residual *= k_intermediate_residual;
    const Solved s =
        solve_links(h, sys.links, v, sys.clusters, sweeps, sys.iteration, sys.emitted, log);
    sys.solved = true;
    report_cycle(ctx, sys, cycle, s, sweeps.residual, {refine_s, weights_s, seconds_since(t0)});
    progress.update(cycle_start + cycle_share);
    return last;
}

// A leaf's reflected weights are weighed by the radiosities of an earlier solve (those kept
// from an earlier cycle by the first solve's), and the solve's radiosities depend on them:
// weigh every leaf by the current radiosities and solve again until the radiosities change
// by less than solver.residual of the emitted power. Where the solution ends then depends on
// the links, not on the way to them: a re-solve from saved radiosities ends where the full
// solve of the changed scene does.
void settle_reflected_weights(HierarchicalSystem& sys, const Scene& scene, const Context& ctx,
                              SweepLog& log) {
    NodeValues& v = sys.values;
    for (int round = 0; round < k_max_weight_rounds; ++round) {
        const std::vector<Rgb> before = v.b;
        v.weights.reflected_solved = false; // every entry afresh
        v.weights = leaf_weights(sys.h, sys.links, v.b, true, v.weights);
        pull_emit(sys.h, v);
        solve_links(sys.h, sys.links, v, sys.clusters, scene.solver, sys.iteration, sys.emitted,
                    log);
        const double change = relative_leaf_change(sys.h, before, v.b, sys.emitted);
        ctx.debug("hierarchical: leaf weights settled by the last radiosities, round {}: change "
                  "{:.2e}",
                  round + 1, change);
        if (change < scene.solver.residual)
            return;
    }
    ctx.warn("hierarchical: the leaves' reflected weights still change the radiosities by more "
             "than solver.residual after {} rounds",
             k_max_weight_rounds);
}

void check_transfers(std::span<const SpecularLight::Transfer> transfers, std::size_t roots) {
    for (const SpecularLight::Transfer& t : transfers)
        if (t.from >= roots || t.to >= roots)
            throw InternalError("build_hierarchical: a specular transfer names no element");
}

// The sources' specular light as a fixed source (its power in the emitted total, as the sun's
// is) and the transfers between roots for the sweeps to apply (NodeValues::specular).
void take_specular_light(HierarchicalSystem& sys, const SpecularLight& specular) {
    const std::size_t roots = sys.h.root_count;
    if (!specular.irradiance.empty() && specular.irradiance.size() != roots)
        throw InternalError("build_hierarchical: one specular irradiance per element expected");
    check_transfers(specular.transfers, roots);
    NodeValues& v = sys.values;
    v.specular_fixed = specular.irradiance;
    v.specular_fixed.resize(roots);
    v.specular = v.specular_fixed;
    v.specular_transfers = specular.transfers;
    sys.emitted += sys.specular_power().max_component();
}

// The transfers traced for the roots' present reflected exitance, B − E (SpecularLight::
// trace_transfers): an estimate is all their photons need, since they are unbiased for any
// density of sources, and tracing them inside the solve saves a second one.
void trace_specular_transfers(HierarchicalSystem& sys, const SpecularLight& specular,
                              const Context& ctx) {
    const auto t0 = Clock::now();
    const Hierarchy& h = sys.h;
    NodeValues& v = sys.values;
    std::vector<Rgb> exitance(h.root_count);
    for (std::uint32_t r = 0; r < h.root_count; ++r)
        exitance[r] = reflected_exitance(h, v.b, r);
    sys.traced_transfers = specular.trace_transfers(exitance);
    check_transfers(sys.traced_transfers, h.root_count);
    v.specular_transfers = sys.traced_transfers;
    ctx.debug("hierarchical: {} specular transfers traced from the solve's exitance, {:.2f} s",
              sys.traced_transfers.size(), seconds_since(t0));
}

} // namespace

void check_reusable(const RadiosityMesh& mesh, const HierarchicalState& state) {
    if (state.mesh_hash != mesh_geometry_hash(mesh) ||
        state.hierarchy.root_count != mesh.element_count())
        throw ConfigError("the reused solver state is of another geometry (the mesh differs): "
                          "only reflectances and emissions may change; bake without --reuse");
}

HierarchicalSystem::HierarchicalSystem(const Scene& scene, const RadiosityMesh& mesh,
                                       const Context& ctx, const HierarchicalState* reuse)
    : h(reuse ? reused_hierarchy(mesh, *reuse) : Hierarchy(mesh)),
      settings(refine_settings(scene, mesh, ctx)) {
    emitted = emitted_power_max(h, scene.point_lights); // and the sun's and sky's, once linked
    values.b = reuse ? reuse->radiosity : h.emission;
    values.b_range.assign(h.size(), 0.0f);
}

RgbD HierarchicalSystem::specular_power() const {
    RgbD total;
    for (std::size_t r = 0; r < values.specular.size(); ++r)
        total += RgbD(values.specular[r]) * h.area[r];
    return total;
}

std::unique_ptr<HierarchicalSystem>
build_hierarchical(const Scene& scene, const RadiosityMesh& mesh, const VisibilityQuery& visibility,
                   const Context& ctx, ProgressStage& progress, SweepLog& log,
                   const HierarchicalState* reuse, const SpecularLight* specular) {
    auto sys = std::make_unique<HierarchicalSystem>(scene, mesh, ctx, reuse);
    if (specular && !specular->empty())
        take_specular_light(*sys, *specular);
    make_clusters(*sys, scene, ctx, reuse);
    // Lives as long as refinement: the system keeps the links and the cluster tables.
    LinkSet refiner(sys->h, sys->links, sys->clusters.tables.get(), visibility, scene.point_lights,
                    scene.sun ? &*scene.sun : nullptr, scene.sky ? &*scene.sky : nullptr,
                    sys->settings);
    link_system(*sys, refiner, scene, ctx, reuse);
    sys->iteration = scene.solver.iteration;
    // Transfers to trace from the solution's exitance: from a reused state's, or after the
    // first cycle. Refinement then sees their light at least once before it may settle.
    const bool trace = specular && specular->transfers.empty() && specular->trace_transfers;
    if (reuse && trace)
        trace_specular_transfers(*sys, *specular, ctx);
    if (reuse)
        resolve_saved(*sys, scene, *reuse, log);
    int first_last = 1;
    for (int cycle = 0; cycle < k_max_cycles; ++cycle) {
        if (run_cycle(*sys, refiner, scene, ctx, progress, log, cycle, first_last))
            break;
        if (cycle == 0 && trace && !reuse) {
            trace_specular_transfers(*sys, *specular, ctx);
            first_last = 2;
        }
    }
    settle_reflected_weights(*sys, scene, ctx, log);
    return sys;
}

SourceTerms current_sources(const HierarchicalSystem& system) {
    const Hierarchy& h = system.h;
    SourceTerms s;
    s.emission.assign(h.emission.begin(), h.emission.begin() + std::ptrdiff_t(h.root_count));
    s.light_links = system.links.light_links();
    return s;
}

Solved solve_sources(HierarchicalSystem& system, const SourceTerms& sources,
                     const SolverSettings& settings, SweepLog& log) {
    Hierarchy& h = system.h;
    if (sources.emission.size() != h.root_count)
        throw ConfigError("source terms: one emission per root expected");
    const std::vector<std::uint32_t> root_of = h.root_of_nodes();
    for (std::size_t n = 0; n < h.size(); ++n)
        h.emission[n] = sources.emission[root_of[n]];
    system.links.set_light_links(sources.light_links);
    double emitted = 0;
    for (std::size_t n = 0; n < h.root_count; ++n)
        emitted += double(h.emission[n].max_component()) * h.area[n];
    for (const LightLink& l : sources.light_links)
        emitted += double(l.irradiance.max_component()) * h.area[l.receiver];
    system.emitted = emitted;
    NodeValues& v = system.values;
    v.b = h.emission;
    if (system.clusters.enabled)
        init_cluster_values(system.clusters.tree, h, v.b, system.clusters.values);
    pull_emit(h, v);
    return solve_links(h, system.links, v, system.clusters, settings, system.iteration, emitted,
                       log);
}

} // namespace penumbra::solver
