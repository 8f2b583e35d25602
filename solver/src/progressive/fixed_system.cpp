// Gathering (Jacobi, Gauss–Seidel) and a dense direct solve of the fixed-element system.

#include "progressive/fixed_system.h"

#include <chrono>
#include <cmath>

#include <Eigen/Dense>

#include "core/error.h"
#include "core/parallel.h"
#include "progressive/shooting_state.h"
#include "sources/point_lights.h"
#include "sources/sky_light.h"
#include "sources/sun_light.h"

namespace penumbra::solver {

namespace {

bool can_radiate(const FixedSystem& s, std::size_t e) {
    return !s.emission[e].is_black() || !s.reflectance[e].is_black() ||
           !s.transmittance[e].is_black();
}

// B_j from the irradiances of j and of its twin (what j's other side passes on).
Rgb radiosity_of(const FixedSystem& s, const ElementResult& r, std::size_t j) {
    Rgb b = s.emission[j] + s.reflectance[j] * (r.h_direct[j] + r.h_indirect[j]);
    const std::int32_t t = s.twin[j];
    if (t >= 0 && !s.transmittance[j].is_black())
        b += s.transmittance[j] * (r.h_direct[std::size_t(t)] + r.h_indirect[std::size_t(t)]);
    return b;
}

double emitted_power_sum(const FixedSystem& s, const ElementGeometry& geo) {
    double total = s.light_emitted.sum();
    for (std::size_t e = 0; e < s.size(); ++e)
        total += double(s.emission[e].sum()) * geo.area[e];
    return std::max(total, 1e-300);
}

// One gathering update of receiver j from the radiosities \p b.
void gather_one(const FixedSystem& s, const std::vector<Rgb>& b, std::size_t j, Rgb& h_direct,
                Rgb& h_indirect) {
    RgbD direct(s.light_direct[j]), indirect;
    for (std::uint32_t k = s.offset[j]; k < s.offset[j + 1]; ++k) {
        const std::uint32_t i = s.source[k];
        direct += RgbD(s.emission[i]) * s.k[k];
        indirect += RgbD(b[i] - s.emission[i]) * s.k[k];
    }
    h_direct = Rgb(float(direct.r), float(direct.g), float(direct.b));
    h_indirect = Rgb(float(indirect.r), float(indirect.g), float(indirect.b));
}

} // namespace

FixedSystem build_fixed_system(const Scene& scene, const RadiosityMesh& mesh,
                               const ElementGeometry& geo, const VisibilityQuery& visibility,
                               const RowSettings& settings, const Context& ctx) {
    FixedSystem s;
    s.mesh = &mesh;
    const std::size_t n = geo.size();
    ShootingState lights(mesh);
    s.emission = lights.emission;
    s.reflectance = lights.reflectance;
    s.transmittance = lights.transmittance;
    s.twin = lights.twin;
    shoot_point_lights(lights, geo, scene.point_lights, visibility, settings, ctx);
    for (const PointLight& l : scene.point_lights)
        s.light_emitted += l.power();
    if (scene.sun) // the sun's power is what its direct light delivers
        s.light_emitted += shoot_sun(lights, geo, *scene.sun, visibility, settings, ctx);
    if (scene.sky) // and the sky's
        s.light_emitted += shoot_sky(lights, geo, *scene.sky, visibility, settings, ctx);
    s.light_direct = lights.h_direct;
    s.light_escaped = lights.escaped;
    std::vector<Row> rows(n);
    s.escape.assign(n, 0.0);
    ProgressStage progress(ctx, "form factors");
    for (std::size_t i = 0; i < n; ++i) {
        if (can_radiate(s, i)) {
            rows[i] = compute_row(geo, visibility, std::uint32_t(i), settings);
            s.escape[i] = rows[i].escape;
        }
        progress.update(double(i + 1) / double(n));
    }
    // Transpose the rows (by source) into CSR by receiver, sources in increasing order.
    s.offset.assign(n + 1, 0);
    for (const Row& row : rows)
        for (std::uint32_t j : row.receiver)
            ++s.offset[j + 1];
    for (std::size_t j = 0; j < n; ++j)
        s.offset[j + 1] += s.offset[j];
    s.source.resize(s.offset[n]);
    s.k.resize(s.offset[n]);
    std::vector<std::uint32_t> fill(s.offset.begin(), s.offset.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t m = 0; m < rows[i].receiver.size(); ++m) {
            const std::uint32_t j = rows[i].receiver[m];
            s.source[fill[j]] = std::uint32_t(i);
            s.k[fill[j]++] = float(double(rows[i].form_factor[m]) * geo.area[i] / geo.area[j]);
        }
    }
    return s;
}

ElementResult solve_gathering(const FixedSystem& s, const ElementGeometry& geo,
                              const SolverSettings& settings, bool gauss_seidel, const Context& ctx,
                              SolveStats* stats) {
    const std::size_t n = s.size();
    ElementResult r{s.emission, std::vector<Rgb>(n), std::vector<Rgb>(n)};
    const double emitted = emitted_power_sum(s, geo);
    std::vector<Rgb> next(n);
    std::vector<double> change(n);
    ProgressStage progress(ctx, gauss_seidel ? "gauss-seidel" : "jacobi");
    double relative = 1;
    int sweep = 0;
    for (; sweep < settings.max_sweeps && relative > settings.residual; ++sweep) {
        if (gauss_seidel) {
            for (std::size_t j = 0; j < n; ++j) {
                const Rgb old = r.radiosity[j];
                gather_one(s, r.radiosity, j, r.h_direct[j], r.h_indirect[j]);
                r.radiosity[j] = radiosity_of(s, r, j);
                change[j] = double((r.radiosity[j] - old).sum());
            }
        } else {
            // All irradiances first: B_j reads its twin's.
            parallel_for_index(n, 256, [&](std::size_t j) {
                gather_one(s, r.radiosity, j, r.h_direct[j], r.h_indirect[j]);
            });
            parallel_for_index(n, 256, [&](std::size_t j) {
                next[j] = radiosity_of(s, r, j);
                change[j] = double((next[j] - r.radiosity[j]).sum());
            });
            r.radiosity.swap(next);
        }
        double changed = 0;
        for (std::size_t j = 0; j < n; ++j)
            changed += std::abs(change[j]) * geo.area[j];
        relative = changed / emitted;
        if (stats)
            stats->residual_history.push_back(relative);
        progress.update(std::log(std::max(relative, 1e-300)) / std::log(settings.residual));
    }
    if (relative > settings.residual)
        ctx.warn("solve: {} sweeps (solver.max_sweeps) left {:.3g} of the power changing", sweep,
                 relative);
    if (stats) {
        stats->shots = sweep;
        stats->power = fixed_balance(s, geo, r, relative);
    }
    return r;
}

ElementResult solve_matrix(const FixedSystem& s, const ElementGeometry& geo, const Context& ctx,
                           SolveStats* stats) {
    const std::size_t n = s.size();
    if (n > 6000)
        throw ConfigError(fmt::format("solver.method 'matrix' is for small scenes: {} elements "
                                      "(limit 6000); use 'hierarchical' or a larger max edge",
                                      n));
    ProgressStage progress(ctx, "matrix solve");
    ElementResult r{std::vector<Rgb>(n), std::vector<Rgb>(n), std::vector<Rgb>(n)};
    for (int c = 0; c < 3; ++c) {
        Eigen::MatrixXd a = Eigen::MatrixXd::Identity(Eigen::Index(n), Eigen::Index(n));
        Eigen::VectorXd rhs = Eigen::VectorXd::Zero(Eigen::Index(n));
        // Row j: B_j − ρ_j (L + K B)_j − τ_j (L + K B)_twin(j) = E_j.
        auto add_irradiance = [&](std::size_t j, std::size_t from, double weight) {
            rhs[Eigen::Index(j)] += weight * s.light_direct[from][c];
            for (std::uint32_t k = s.offset[from]; k < s.offset[from + 1]; ++k)
                a(Eigen::Index(j), Eigen::Index(s.source[k])) -= weight * double(s.k[k]);
        };
        for (std::size_t j = 0; j < n; ++j) {
            rhs[Eigen::Index(j)] = s.emission[j][c];
            add_irradiance(j, j, s.reflectance[j][c]);
            if (s.twin[j] >= 0 && s.transmittance[j][c] > 0)
                add_irradiance(j, std::size_t(s.twin[j]), s.transmittance[j][c]);
        }
        Eigen::VectorXd b = a.partialPivLu().solve(rhs);
        for (std::size_t j = 0; j < n; ++j)
            r.radiosity[j][c] = float(b[Eigen::Index(j)]);
        progress.update((c + 1) / 3.0);
    }
    for (std::size_t j = 0; j < n; ++j)
        gather_one(s, r.radiosity, j, r.h_direct[j], r.h_indirect[j]);
    if (stats)
        stats->power = fixed_balance(s, geo, r, 0.0);
    return r;
}

PowerBalance fixed_balance(const FixedSystem& s, const ElementGeometry& geo, const ElementResult& r,
                           double unconverged_power_fraction) {
    PowerBalance pb;
    pb.emitted = s.light_emitted;
    pb.escaped = s.light_escaped;
    for (std::size_t e = 0; e < s.size(); ++e) {
        pb.emitted += RgbD(s.emission[e]) * geo.area[e];
        pb.escaped += RgbD(r.radiosity[e]) * (geo.area[e] * s.escape[e]);
        pb.receive(s.patch(e), RgbD(r.h_direct[e]) + RgbD(r.h_indirect[e]), geo.area[e]);
    }
    pb.residual = pb.emitted * unconverged_power_fraction;
    return pb;
}

} // namespace penumbra::solver
