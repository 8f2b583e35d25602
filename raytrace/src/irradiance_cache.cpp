// Ward's irradiance cache (irradiance_cache.h). A record gathers M × N rays stratified in
// sin²θ and φ (uniform in projected solid angle: E = π/(MN) Σ L), and from the same rays Ward &
// Heckbert's (1992) gradients: the rotational one from each ray's tan θ, the translational one
// from the radiance steps between neighbouring cells, each boundary moving as the nearer of its
// two hits would. A lookup sums the valid records of its grid cell in record order, so the
// cache reads the same bits from any thread.

#include "irradiance_cache.h"

#include "core/parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra::raytrace {

namespace {

/// The pixel grids records are placed on, coarse to fine (pixels between grid points).
constexpr int k_coarsest_grid_px = 32;
constexpr int k_finest_grid_px = 2;

/// A record's reach a·R in pixels' footprints at its point (Tabellion & Lamorlette 2004 clamp R
/// to the screen likewise): at least a finest grid's diagonal half-step, so the finest grid
/// leaves few gaps; at most a few coarse grid steps, so flat walls still get records near
/// what changes their light.
constexpr double k_min_reach_px = 1.5;
constexpr double k_max_reach_px = 20.0;

/// At most this many cells in the lookup grid: past it, its cells grow.
constexpr double k_max_grid_cells = double(1 << 22);

/// Ward's ε of record \p r at (p, n); infinite where the record does not apply: it lies in
/// front of the point (the point is behind its plane: in a corner or under what the record
/// sees) or faces away.
double ward_error(const IrradianceRecord& r, const Vec3& p, const Vec3& n) {
    const double facing = dot(n, r.n);
    if (!(facing > 0))
        return std::numeric_limits<double>::infinity();
    const Vec3 d = p - r.p;
    // Ward's test: a point more than a hundredth of R behind the record's plane (the mean of
    // both normals) may be shadowed by what the record's rays met.
    if (dot(d, n + r.n) * 0.5 < -0.01 * r.radius_m)
        return std::numeric_limits<double>::infinity();
    return length(d) / r.radius_m + std::sqrt(std::max(0.0, 1.0 - facing));
}

/// The record's irradiance carried to (p, n) by its gradients, never below 0.
Rgb extrapolated(const IrradianceRecord& r, const Vec3& p, const Vec3& n) {
    const Vec3 turn = cross(r.n, n), shift = p - r.p;
    Rgb e = r.irradiance;
    for (int c = 0; c < 3; ++c)
        e[c] = std::max(0.0f, e[c] + float(dot(turn, r.rotation_gradient[std::size_t(c)]) +
                                           dot(shift, r.translation_gradient[std::size_t(c)])));
    return e;
}

} // namespace

IrradianceCache::IrradianceCache(std::vector<IrradianceRecord> records, double error)
    : records_(std::move(records)), error_(error), grid_(make_grid(records_, error)) {}

IrradianceCache::Grid IrradianceCache::sized_grid(const std::vector<IrradianceRecord>& records,
                                                  const std::vector<double>& reach) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    Vec3 lo{inf, inf, inf}, hi{-inf, -inf, -inf};
    for (std::size_t i = 0; i < records.size(); ++i) {
        const Vec3 d{reach[i], reach[i], reach[i]};
        lo = min(lo, records[i].p - d);
        hi = max(hi, records[i].p + d);
    }
    // Cells of the median reach: a typical record spans a few cells, a lookup sees few.
    std::vector<double> sorted = reach;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2),
                     sorted.end());
    Grid grid;
    grid.cell_m = sorted[sorted.size() / 2];
    const Vec3 extent = hi - lo;
    const auto cells_along = [&](double e) { return std::max(1.0, std::ceil(e / grid.cell_m)); };
    while (cells_along(extent.x) * cells_along(extent.y) * cells_along(extent.z) > k_max_grid_cells)
        grid.cell_m *= 1.25;
    grid.origin = lo;
    grid.cells = {int(cells_along(extent.x)), int(cells_along(extent.y)),
                  int(cells_along(extent.z))};
    return grid;
}

IrradianceCache::Grid IrradianceCache::make_grid(const std::vector<IrradianceRecord>& records,
                                                 double error) {
    if (records.empty())
        return {};
    std::vector<double> reach;
    for (const IrradianceRecord& r : records)
        reach.push_back(error * r.radius_m);
    Grid grid = sized_grid(records, reach);
    const auto index = [&](double x, double o, int n) {
        return std::clamp(int(std::floor((x - o) / grid.cell_m)), 0, n - 1);
    };
    // Counting sort: each record's cells counted, then filled in record order.
    const auto each_cell = [&](std::size_t i, auto&& fn) {
        const Vec3& p = records[i].p;
        const double d = reach[i];
        const Vec3& o = grid.origin;
        const auto& n = grid.cells;
        for (int z = index(p.z - d, o.z, n[2]); z <= index(p.z + d, o.z, n[2]); ++z)
            for (int y = index(p.y - d, o.y, n[1]); y <= index(p.y + d, o.y, n[1]); ++y)
                for (int x = index(p.x - d, o.x, n[0]); x <= index(p.x + d, o.x, n[0]); ++x)
                    fn((std::size_t(z) * std::size_t(n[1]) + std::size_t(y)) * std::size_t(n[0]) +
                       std::size_t(x));
    };
    grid.first.assign(
        std::size_t(grid.cells[0]) * std::size_t(grid.cells[1]) * std::size_t(grid.cells[2]) + 1,
        0);
    for (std::size_t i = 0; i < records.size(); ++i)
        each_cell(i, [&](std::size_t c) { ++grid.first[c + 1]; });
    for (std::size_t c = 1; c < grid.first.size(); ++c)
        grid.first[c] += grid.first[c - 1];
    grid.items.resize(grid.first.back());
    std::vector<std::uint32_t> cursor(grid.first.begin(), grid.first.end() - 1);
    for (std::size_t i = 0; i < records.size(); ++i)
        each_cell(i, [&](std::size_t c) { grid.items[cursor[c]++] = std::uint32_t(i); });
    return grid;
}

template <typename Visit>
void IrradianceCache::visit_valid(const Vec3& p, const Vec3& n, Visit&& visit) const {
    if (grid_.items.empty())
        return;
    std::size_t cell = 0;
    const double coords[3] = {p.x - grid_.origin.x, p.y - grid_.origin.y, p.z - grid_.origin.z};
    for (int axis = 2; axis >= 0; --axis) {
        const double i = std::floor(coords[axis] / grid_.cell_m);
        if (!(i >= 0 && i < grid_.cells[std::size_t(axis)]))
            return; // beyond every record's reach
        cell = cell * std::size_t(grid_.cells[std::size_t(axis)]) + std::size_t(i);
    }
    for (std::uint32_t k = grid_.first[cell]; k < grid_.first[cell + 1]; ++k) {
        const IrradianceRecord& r = records_[grid_.items[k]];
        const double e = ward_error(r, p, n);
        if (e < error_)
            visit(r, e);
    }
}

std::optional<Rgb> IrradianceCache::irradiance(const Vec3& p, const Vec3& n) const {
    RgbD sum;
    double weights = 0;
    visit_valid(p, n, [&](const IrradianceRecord& r, double e) {
        // Ward's weight 1/ε less its value at the edge of validity: continuous across the edge.
        const double w = 1.0 / std::max(e, 1e-9) - 1.0 / error_;
        sum += RgbD(extrapolated(r, p, n)) * w;
        weights += w;
    });
    if (!(weights > 0))
        return std::nullopt;
    return Rgb{float(sum.r / weights), float(sum.g / weights), float(sum.b / weights)};
}

bool IrradianceCache::covers(const Vec3& p, const Vec3& n) const {
    bool found = false;
    visit_valid(p, n, [&](const IrradianceRecord&, double) { found = true; });
    return found;
}

namespace {

/// The M × N strata of a record's rays: N ≈ π M (Ward & Heckbert), M N ≥ rays.
struct Strata {
    int m = 1, n = 1;
    explicit Strata(int rays)
        : m(std::max(2, int(std::lround(std::sqrt(rays / k_pi))))),
          n(std::max(3, (rays + m - 1) / m)) {}
};

/// The rays of one record, cell (j, k) at [j n + k]: sin²θ in [j, j + 1)/M, φ in
/// 2π [k, k + 1)/N.
struct RecordRays {
    std::vector<RecordRay> cells;
    Strata strata;
};

RecordRays trace_record_rays(const SurfaceHit& s, const Strata& strata, const Pcg32& stream,
                             const RecordTracer& trace) {
    const Frame frame = Frame::from_normal(s.shading);
    RecordRays out{{}, strata};
    out.cells.reserve(std::size_t(strata.m * strata.n));
    for (int j = 0; j < strata.m; ++j)
        for (int k = 0; k < strata.n; ++k) {
            Pcg32 rng = stream;
            rng.advance(std::int64_t(j * strata.n + k) << 16);
            const double sin2 = (j + rng.next_double()) / strata.m;
            const double phi = 2.0 * k_pi * (k + rng.next_double()) / strata.n;
            const double sin_theta = std::sqrt(sin2);
            const Vec3 wi = frame.to_world({sin_theta * std::cos(phi), sin_theta * std::sin(phi),
                                            std::sqrt(std::max(0.0, 1.0 - sin2))});
            // Below the geometric surface (a shading normal tilted off it): no light, no hit.
            if (!SurfaceGeometry::geometric_side_agrees(s, s.shading, wi, false)) {
                out.cells.push_back({Rgb{}, std::numeric_limits<double>::infinity()});
                continue;
            }
            out.cells.push_back(trace(s, wi, rng));
        }
    return out;
}

/// Ward & Heckbert's gradients of the rays' irradiance (irradiance_cache.h), per channel.
void add_gradients(const RecordRays& rays, const Frame& frame, IrradianceRecord& r) {
    const int m = rays.strata.m, n = rays.strata.n;
    const auto cell = [&](int j, int k) -> const RecordRay& {
        return rays.cells[std::size_t(j * n + (k + n) % n)];
    };
    const auto plane = [&](double phi) {
        return frame.to_world({std::cos(phi), std::sin(phi), 0.0});
    };
    for (int k = 0; k < n; ++k) {
        const double phi_centre = 2.0 * k_pi * (k + 0.5) / n, phi_start = 2.0 * k_pi * k / n;
        const Vec3 u = plane(phi_centre), v = plane(phi_centre + 0.5 * k_pi);
        const Vec3 v_start = plane(phi_start + 0.5 * k_pi);
        for (int j = 0; j < m; ++j) {
            const double sin_lo = std::sqrt(double(j) / m), sin_hi = std::sqrt(double(j + 1) / m);
            const double sin_c = std::sqrt((j + 0.5) / m), cos_c = std::sqrt(1.0 - sin_c * sin_c);
            const Rgb& l = cell(j, k).radiance;
            // Tilting the normal by α about v brings tan θ α of this cell's light.
            const Vec3 rotation = v * (k_pi / (m * n) * sin_c / cos_c);
            // The ring boundary at θ_lo moves by cos θ/r per metre along u; the azimuthal one
            // at φ_start by 1/(r sin θ) along v_start; each adds the step of radiance it passes.
            Vec3 ring{}, wedge{};
            if (j > 0) {
                const double dist = std::min(cell(j, k).distance, cell(j - 1, k).distance);
                const double cos_lo = std::sqrt(1.0 - sin_lo * sin_lo);
                ring = u * (2.0 * k_pi / n * sin_lo * cos_lo * cos_lo / dist);
            }
            const double dist = std::min(cell(j, k).distance, cell(j, k - 1).distance);
            wedge = v_start * ((sin_hi - sin_lo) / dist);
            for (int c = 0; c < 3; ++c) {
                const auto ch = std::size_t(c);
                r.rotation_gradient[ch] += rotation * double(l[c]);
                if (j > 0)
                    r.translation_gradient[ch] += ring * double(l[c] - cell(j - 1, k).radiance[c]);
                r.translation_gradient[ch] += wedge * double(l[c] - cell(j, k - 1).radiance[c]);
            }
        }
    }
}

/// Where the least reach (k_min_reach_px) overrides R ≤ E / |∇E|, the gradient is scaled down
/// to |∇E| R = E instead: a noisy gradient (one ray per cell, divided by short distances by a
/// corner) would extrapolate below zero within reach, and clamping that at zero biased the
/// furnace 1 % bright at 256 rays (the bias grows as the rays' noise).
void limit_translation_gradients(IrradianceRecord& r) {
    for (std::size_t c = 0; c < 3; ++c) {
        Vec3& g = r.translation_gradient[c];
        const double reach = length(g) * r.radius_m;
        if (reach > double(r.irradiance[c]))
            g = g * (double(r.irradiance[c]) / reach);
    }
}

/// The record at \p s: irradiance, gradients, and R from the harmonic mean distance, clamped
/// to [k_min_reach_px, k_max_reach_px] footprints of \p footprint_m (reach a·R) and to
/// E / |∇E| (Křivánek et al. 2008: no further than the gradient would take E to zero).
IrradianceRecord compute_record(const SurfaceHit& s, double footprint_m, double error,
                                const Strata& strata, const Pcg32& stream,
                                const RecordTracer& trace) {
    const RecordRays rays = trace_record_rays(s, strata, stream, trace);
    IrradianceRecord r;
    r.p = s.p;
    r.n = s.shading;
    RgbD sum;
    double inverse_distances = 0;
    for (const RecordRay& ray : rays.cells) {
        sum += RgbD(ray.radiance);
        inverse_distances += 1.0 / ray.distance; // 0 for a ray that leaves
    }
    const double count = double(rays.cells.size());
    r.irradiance =
        Rgb{float(k_pi * sum.r / count), float(k_pi * sum.g / count), float(k_pi * sum.b / count)};
    add_gradients(rays, Frame::from_normal(s.shading), r);
    const double lo = k_min_reach_px * footprint_m / error;
    const double hi = k_max_reach_px * footprint_m / error;
    double radius = inverse_distances > 0 ? count / inverse_distances : hi;
    for (int c = 0; c < 3; ++c) {
        const double slope = length(r.translation_gradient[std::size_t(c)]);
        if (slope > 0)
            radius = std::min(radius, double(r.irradiance[c]) / slope);
    }
    r.radius_m = std::clamp(radius, lo, hi);
    limit_translation_gradients(r);
    return r;
}

/// A grid point's primary hit on a cacheable surface, and the footprint of a pixel there.
struct Candidate {
    SurfaceHit s;
    double footprint_m = 0;
};

std::optional<Candidate> candidate_at(const EmbreeScene& rt, const SurfaceGeometry& surfaces,
                                      const PinholeCamera& camera, int x, int y) {
    const Vec3 dir = normalize(camera.image_plane(x + 0.5, y + 0.5));
    const auto hit = rt.intersect(Vec3f(camera.eye), Vec3f(dir), 0.0f, k_infinity);
    if (hit.element < 0 || !cacheable(surfaces.material_of(std::uint32_t(hit.element))))
        return std::nullopt;
    const double pixel_angle = 2.0 * length(camera.right) / camera.width;
    return Candidate{surfaces.surface_of(hit, camera.eye, dir), double(hit.t) * pixel_angle};
}

} // namespace

IrradianceCache build_irradiance_cache(const EmbreeScene& rt, const SurfaceGeometry& surfaces,
                                       const PinholeCamera& camera,
                                       const IrradianceCacheSettings& settings,
                                       const RecordTracer& trace, const Context& ctx) {
    ProgressStage stage(ctx, "irradiance cache");
    const Strata strata(settings.rays);
    std::vector<IrradianceRecord> records;
    IrradianceCache cache({}, settings.error);
    for (int grid = k_coarsest_grid_px; grid >= k_finest_grid_px; grid /= 2) {
        std::vector<std::pair<int, int>> points;
        for (int y = 0; y < camera.height; y += grid)
            for (int x = 0; x < camera.width; x += grid)
                points.emplace_back(x, y);
        std::vector<std::optional<IrradianceRecord>> made(points.size());
        run_in_arena(ctx, [&] {
            parallel_for_index(points.size(), 1, [&](std::size_t i) {
                const auto [x, y] = points[i];
                const auto c = candidate_at(rt, surfaces, camera, x, y);
                if (!c || cache.covers(c->s.p, c->s.shading))
                    return;
                const Pcg32 stream = Pcg32::for_stream(
                    RngPurpose::irradiance_record, std::uint64_t(x), std::uint64_t(y), 0, ctx.seed);
                made[i] =
                    compute_record(c->s, c->footprint_m, settings.error, strata, stream, trace);
            });
        });
        for (auto& r : made)
            if (r)
                records.push_back(std::move(*r));
        cache = IrradianceCache(records, settings.error);
        // A grid of half the step has four times the points.
        stage.update(double(k_finest_grid_px * k_finest_grid_px) / (grid * grid));
    }
    ctx.debug("irradiance cache: {} records of {} rays", records.size(), strata.m * strata.n);
    return cache;
}

} // namespace penumbra::raytrace
