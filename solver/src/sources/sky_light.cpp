// The sky: its irradiance at points and on triangles by adaptive cells over the hemisphere.

#include "sources/sky_light.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/parallel.h"

namespace penumbra::solver {

namespace {

/// Samples of a cell whose transmittances differ by more than this (relative) see an edge:
/// a pane's own T(θ) varies less across a cell.
constexpr double k_edge_contrast = 0.1;
/// Samples whose sky luminance differs by more than this ratio split the cell (the horizon,
/// the circumsolar peak).
constexpr double k_luminance_ratio = 1.5;

/// A cell of the hemisphere in (u, v) = (sin²θ, φ / 2π): its projected solid angle is
/// π · du · dv.
struct Cell {
    double u0 = 0, v0 = 0, du = 0, dv = 0;
    int depth = 0;
};

/// The direction of (u, v) around \p frame's normal.
Vec3 cell_direction(const Frame& frame, double u, double v) {
    const double sin_theta = std::sqrt(u), cos_theta = std::sqrt(std::max(0.0, 1.0 - u));
    const double phi = 2.0 * k_pi * v;
    return frame.to_world(Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta));
}

/// Rays toward the sky end this far away: out of the scene from any point in it.
float sky_reach(double diagonal) {
    return float(2.0 * diagonal + 1.0);
}

std::vector<Cell> starting_cells(const SkyQuadrature& q) {
    std::vector<Cell> cells;
    cells.reserve(std::size_t(q.rows * q.columns));
    for (int i = 0; i < q.rows; ++i)
        for (int j = 0; j < q.columns; ++j)
            cells.push_back(
                {double(i) / q.rows, double(j) / q.columns, 1.0 / q.rows, 1.0 / q.columns, 0});
    return cells;
}

/// Whether the four samples of a cell (transmittances \p t, sky radiances \p l) call for
/// finer cells: some blocked and some not, panes and open sky mixed, or a steep sky.
bool cell_varies(std::span<const float> t, std::span<const Rgb> l) {
    const auto [t_lo, t_hi] = std::minmax_element(t.begin(), t.end());
    if (*t_hi <= 0.0f)
        return false; // all hidden
    if (*t_lo <= 0.0f || *t_hi - *t_lo > k_edge_contrast * *t_hi)
        return true;
    double lo = 1e300, hi = 0;
    for (const Rgb& c : l) {
        const double y = to_photometric(c);
        lo = std::min(lo, y);
        hi = std::max(hi, y);
    }
    return hi > k_luminance_ratio * lo;
}

/// The four children of \p c.
void split(const Cell& c, std::vector<Cell>& out) {
    const double du = c.du / 2, dv = c.dv / 2;
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
            out.push_back({c.u0 + i * du, c.v0 + j * dv, du, dv, c.depth + 1});
}

} // namespace

RgbD sky_point_irradiance(const Sky& sky, const Vec3& from, const Vec3& n, double diagonal,
                          const VisibilityQuery& visibility, const SkyQuadrature& quadrature,
                          Pcg32& rng) {
    const Frame frame = Frame::from_normal(n);
    const float reach = sky_reach(diagonal);
    const Vec3f origin(from);
    std::vector<Cell> cells = starting_cells(quadrature), finer;
    std::vector<Segment> rays;
    std::vector<Rgb> radiance;
    std::vector<float> t;
    RgbD sum;
    while (!cells.empty()) {
        rays.clear();
        radiance.clear();
        for (const Cell& c : cells)
            for (int s = 0; s < 4; ++s) {
                const double u = c.u0 + c.du * ((s / 2) + rng.next_double()) / 2;
                const double v = c.v0 + c.dv * ((s % 2) + rng.next_double()) / 2;
                const Vec3 dir = cell_direction(frame, u, v);
                rays.push_back({origin, Vec3f(dir), 0.0f, reach});
                radiance.push_back(sky.radiance(dir));
            }
        t.resize(rays.size());
        visibility.transmittance(rays, t);
        finer.clear();
        for (std::size_t k = 0; k < cells.size(); ++k) {
            const std::span<const float> tk(t.data() + 4 * k, 4);
            const std::span<const Rgb> lk(radiance.data() + 4 * k, 4);
            if (cells[k].depth < quadrature.max_depth && cell_varies(tk, lk)) {
                split(cells[k], finer);
                continue;
            }
            RgbD cell;
            for (int s = 0; s < 4; ++s)
                cell += RgbD(lk[std::size_t(s)]) * double(tk[std::size_t(s)]);
            sum += cell * (k_pi * cells[k].du * cells[k].dv / 4.0);
        }
        cells.swap(finer);
    }
    return sum;
}

SkyIrradiance sky_triangle_irradiance(const Sky& sky, const OrientedTriangle& target, double offset,
                                      double diagonal, std::uint64_t key,
                                      const VisibilityQuery& visibility, std::uint64_t seed) {
    constexpr double k_near = 2.0 / 3.0, k_far = 1.0 / 6.0;
    RgbD sum;
    double lo = 1e300, hi = 0;
    for (int i = 0; i < 3; ++i) {
        const Vec3 p = target.v[std::size_t(i)] * k_near +
                       target.v[std::size_t((i + 1) % 3)] * k_far +
                       target.v[std::size_t((i + 2) % 3)] * k_far + target.n * offset;
        Pcg32 rng = Pcg32::for_stream(RngPurpose::sky_visibility, key, std::uint64_t(i), 0, seed);
        const RgbD e = sky_point_irradiance(sky, p, target.n, diagonal, visibility,
                                            k_sky_element_quadrature, rng);
        sum += e;
        lo = std::min(lo, e.max_component());
        hi = std::max(hi, e.max_component());
    }
    const RgbD mean = sum * (1.0 / 3.0);
    return {Rgb(float(mean.r), float(mean.g), float(mean.b)), float(hi - lo)};
}

RgbD shoot_sky(ShootingState& state, const ElementGeometry& geo, const Sky& sky,
               const VisibilityQuery& visibility, const RowSettings& settings, const Context& ctx) {
    std::vector<Rgb> received(geo.size());
    parallel_for_index(geo.size(), 16, [&](std::size_t j) {
        received[j] = sky_triangle_irradiance(sky, geo.oriented(std::uint32_t(j)), geo.offset,
                                              geo.diagonal, j, visibility, settings.seed)
                          .irradiance;
    });
    RgbD delivered;
    for (std::size_t j = 0; j < geo.size(); ++j) {
        if (received[j].is_black())
            continue;
        state.receive(j, received[j], Rgb{});
        delivered += RgbD(received[j]) * geo.area[j];
    }
    state.emitted += delivered;
    ctx.debug("sky shot: {:.6g} lm delivered", to_photometric(delivered));
    return delivered;
}

} // namespace penumbra::solver
