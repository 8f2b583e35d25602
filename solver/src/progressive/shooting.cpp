// Progressive refinement radiosity (Cohen, Chen, Wallace & Greenberg 1988): the element with
// the most unshot power shoots it to all others through a row of form factors (Southwell
// iteration). Point lights shoot once first. Rows are cached within a memory budget, so that
// an element shooting again costs no new rays. Deterministic: shooters are chosen serially
// (ties to the lowest id) and each receiver is updated by exactly one task.

#include "solver/solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "core/parallel.h"
#include "kernels/element_rows.h"
#include "output/vertex_values.h"
#include "progressive/shooting_state.h"
#include "sources/point_lights.h"
#include "sources/sky_light.h"
#include "sources/sun_light.h"

namespace penumbra::solver {

RgbD ShootingState::receive_from_afar(const std::vector<Rgb>& direct,
                                      const std::vector<double>& area) {
    RgbD delivered;
    for (std::size_t j = 0; j < direct.size(); ++j) {
        if (direct[j].is_black())
            continue;
        receive(j, direct[j], Rgb{});
        delivered += RgbD(direct[j]) * area[j];
    }
    emitted += delivered;
    return delivered;
}

ShootingState::ShootingState(const RadiosityMesh& mesh) {
    const std::size_t n = mesh.element_count();
    emission.resize(n);
    reflectance.resize(n);
    transmittance.resize(n);
    twin = mesh.element_twin;
    for (std::size_t e = 0; e < n; ++e) {
        const Patch& patch = mesh.patch_of(std::uint32_t(e));
        emission[e] = patch.emission;
        reflectance[e] = patch.reflectance;
        transmittance[e] = patch.diffuse_transmittance;
        emitted += RgbD(patch.emission) * mesh.element_area[e];
    }
    radiosity = emission;
    unshot_emitted = emission;
    h_direct.assign(n, Rgb{});
    h_indirect.assign(n, Rgb{});
    unshot_reflected.assign(n, Rgb{});
}

namespace {

double power_of(const ShootingState& s, const ElementGeometry& geo, std::size_t e) {
    return double((s.unshot_emitted[e] + s.unshot_reflected[e]).sum()) * geo.area[e];
}

double total_unshot(const ShootingState& s, const ElementGeometry& geo) {
    double total = 0;
    for (std::size_t e = 0; e < geo.size(); ++e)
        total += power_of(s, geo, e);
    return total;
}

class RowCache {
public:
    RowCache(std::size_t n, double budget_mb) : rows_(n), budget_(budget_mb * 1024.0 * 1024.0) {}

    const Row& get(const ElementGeometry& geo, const VisibilityQuery& vis, std::uint32_t i,
                   const RowSettings& settings, Row& scratch) {
        if (rows_[i])
            return *rows_[i];
        scratch = compute_row(geo, vis, i, settings);
        if (used_ + double(scratch.bytes()) > budget_)
            return scratch;
        used_ += double(scratch.bytes());
        rows_[i] = std::move(scratch);
        return *rows_[i];
    }

private:
    std::vector<std::optional<Row>> rows_;
    double budget_;
    double used_ = 0;
};

// Shoots element i's unshot radiosity through its row; returns the power that receivers
// reflected (now unshot) so the caller can keep a running total.
double shoot_element(ShootingState& s, const ElementGeometry& geo, const Row& row,
                     std::uint32_t i) {
    const Rgb ue = s.unshot_emitted[i], ur = s.unshot_reflected[i];
    const double shot_power_rgb = double((ue + ur).sum()) * geo.area[i];
    s.escaped += (RgbD(ue) + RgbD(ur)) * (geo.area[i] * row.escape);
    s.unshot_emitted[i] = Rgb{};
    s.unshot_reflected[i] = Rgb{};
    const std::size_t m = row.receiver.size();
    std::vector<double> reflected(m);
    parallel_for_index(m, 512, [&](std::size_t k) {
        std::uint32_t j = row.receiver[k];
        float scale = float(double(row.form_factor[k]) * geo.area[i] / geo.area[j]);
        Rgb before = s.unshot_reflected[j];
        s.reflect(j, ue * scale, ur * scale);
        reflected[k] = double((s.unshot_reflected[j] - before).sum()) * geo.area[j];
    });
    // The receivers' twins in a second pass: a twin may be another receiver's slot.
    std::vector<double> passed(m, 0.0);
    parallel_for_index(m, 512, [&](std::size_t k) {
        const std::uint32_t j = row.receiver[k];
        const std::int32_t t = s.twin[j];
        if (t < 0 || s.transmittance[j].is_black())
            return;
        const float scale = float(double(row.form_factor[k]) * geo.area[i] / geo.area[j]);
        const Rgb before = s.unshot_reflected[std::size_t(t)];
        s.transmit(j, (ue + ur) * scale);
        passed[k] =
            double((s.unshot_reflected[std::size_t(t)] - before).sum()) * geo.area[std::size_t(t)];
    });
    double added = 0;
    for (std::size_t k = 0; k < m; ++k)
        added += reflected[k] + passed[k];
    return added - shot_power_rgb;
}

std::uint32_t pick_shooter(const ShootingState& s, const ElementGeometry& geo) {
    std::uint32_t best = 0;
    double best_power = -1;
    for (std::size_t e = 0; e < geo.size(); ++e) {
        double p = power_of(s, geo, e);
        if (p > best_power) {
            best_power = p;
            best = std::uint32_t(e);
        }
    }
    return best;
}

struct LoopResult {
    std::int64_t shots = 0;
    std::vector<double> history;
};

LoopResult shooting_loop(ShootingState& s, const RadiosityMesh& mesh, const ElementGeometry& geo,
                         const VisibilityQuery& vis, const SolverSettings& settings,
                         const RowSettings& row_settings, const SolveObserver* observer,
                         const Context& ctx) {
    const double emitted = s.emitted.sum();
    const std::int64_t max_shots =
        settings.max_shots > 0 ? settings.max_shots : 10000 * std::int64_t(geo.size()) + 100;
    RowCache cache(geo.size(), settings.row_cache_mb);
    ProgressStage progress(ctx, "solve");
    LoopResult result;
    Row scratch;
    double unshot = total_unshot(s, geo);
    const double start = std::max(unshot, 1e-300);
    const double target = settings.residual * emitted;
    while (unshot > target && result.shots < max_shots) {
        std::uint32_t i = pick_shooter(s, geo);
        const Row& row = cache.get(geo, vis, i, row_settings, scratch);
        unshot += shoot_element(s, geo, row, i);
        if (++result.shots % std::int64_t(geo.size()) == 0) {
            unshot = total_unshot(s, geo); // drop accumulated rounding
            result.history.push_back(unshot / std::max(emitted, 1e-300));
        }
        if (observer && observer->on_pass && observer->every_shots > 0 &&
            result.shots % observer->every_shots == 0)
            observer->on_pass(snapshot_solution(mesh, {s.radiosity, s.h_direct, s.h_indirect}),
                              result.shots, unshot / std::max(emitted, 1e-300), false);
        progress.update(std::log(start / std::max(unshot, 1e-300)) /
                        std::log(start / std::max(target, 1e-300)));
    }
    if (result.shots >= max_shots)
        ctx.warn("solve: stopped after {} shots (solver.max_shots) with {:.3g} of the emitted "
                 "power unshot",
                 result.shots, unshot / std::max(emitted, 1e-300));
    return result;
}

// Cohen et al. 1988's ambient term, for previews: the unshot power spread uniformly and
// reflected with the area-mean reflectance.
void add_ambient(ShootingState& s, const ElementGeometry& geo) {
    RgbD unshot, rho_area;
    double area = 0;
    for (std::size_t e = 0; e < geo.size(); ++e) {
        unshot += (RgbD(s.unshot_emitted[e]) + RgbD(s.unshot_reflected[e])) * geo.area[e];
        rho_area += RgbD(s.reflectance[e]) * geo.area[e];
        area += geo.area[e];
    }
    if (area <= 0)
        return;
    Rgb ambient;
    for (int c = 0; c < 3; ++c) {
        double rho = (c == 0 ? rho_area.r : c == 1 ? rho_area.g : rho_area.b) / area;
        double u = (c == 0 ? unshot.r : c == 1 ? unshot.g : unshot.b) / area;
        ambient[c] = float(u / std::max(1.0 - rho, 1e-3));
    }
    for (std::size_t e = 0; e < geo.size(); ++e) {
        s.h_indirect[e] += ambient;
        s.radiosity[e] += s.reflectance[e] * ambient;
    }
}

PowerBalance balance_of(const ShootingState& s, const RadiosityMesh& mesh,
                        const ElementGeometry& geo) {
    PowerBalance pb;
    pb.emitted = s.emitted;
    pb.escaped = s.escaped;
    for (std::size_t e = 0; e < geo.size(); ++e) {
        pb.receive(mesh.patch_of(std::uint32_t(e)), RgbD(s.h_direct[e]) + RgbD(s.h_indirect[e]),
                   geo.area[e]);
        pb.residual += (RgbD(s.unshot_emitted[e]) + RgbD(s.unshot_reflected[e])) * geo.area[e];
    }
    return pb;
}

} // namespace

double PowerBalance::relative_imbalance() const {
    double e = to_photometric(emitted);
    if (e <= 0)
        return 0;
    return (e - to_photometric(absorbed) - to_photometric(escaped) - to_photometric(glazing) -
            to_photometric(residual)) /
           e;
}

void PowerBalance::receive(const Patch& patch, const RgbD& h, double area) {
    if (patch.glazing) {
        const RgbD kept = RgbD(1, 1, 1) - RgbD(patch.glazing->hemispherical_transmittance());
        glazing += RgbD(h.r * kept.r, h.g * kept.g, h.b * kept.b) * area;
        return;
    }
    const RgbD a = RgbD(1, 1, 1) - RgbD(patch.reflectance) - RgbD(patch.diffuse_transmittance);
    absorbed += RgbD(h.r * a.r, h.g * a.g, h.b * a.b) * area;
}

Solution solve_shooting(const Scene& scene, const RadiosityMesh& mesh,
                        const VisibilityQuery& visibility, const Context& ctx, SolveStats* stats,
                        const SolveObserver* observer) {
    using clock = std::chrono::steady_clock;
    const auto t0 = clock::now();
    const std::uint64_t rays0 = visibility.rays_traced();
    return run_in_arena(ctx, [&] {
        ElementGeometry geo(mesh);
        ShootingState state(mesh);
        RowSettings row_settings;
        row_settings.visibility_rays = scene.solver.visibility_rays;
        row_settings.seed = ctx.seed;
        shoot_point_lights(state, geo, scene.point_lights, visibility, row_settings, ctx);
        if (scene.sun)
            shoot_sun(state, geo, *scene.sun, visibility, row_settings, ctx);
        if (scene.sky)
            shoot_sky(state, geo, *scene.sky, visibility, row_settings, ctx);
        LoopResult loop =
            shooting_loop(state, mesh, geo, visibility, scene.solver, row_settings, observer, ctx);
        PowerBalance balance = balance_of(state, mesh, geo);
        if (scene.solver.ambient)
            add_ambient(state, geo);
        Solution solution =
            make_solution(scene, mesh, geo, {state.radiosity, state.h_direct, state.h_indirect},
                          visibility, row_settings, ctx);
        if (observer && observer->on_pass)
            observer->on_pass(solution, loop.shots,
                              balance.residual.sum() / std::max(balance.emitted.sum(), 1e-300),
                              true);
        ctx.info("solve: {} shots, unshot {:.3g} of emitted, power imbalance {:.3g}", loop.shots,
                 balance.residual.sum() / std::max(balance.emitted.sum(), 1e-300),
                 balance.relative_imbalance());
        if (stats) {
            stats->shots = loop.shots;
            stats->residual_history = std::move(loop.history);
            stats->power = balance;
            stats->rays = visibility.rays_traced() - rays0;
            stats->seconds_total = std::chrono::duration<double>(clock::now() - t0).count();
        }
        return solution;
    });
}

} // namespace penumbra::solver
