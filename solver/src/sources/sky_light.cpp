// The sky: its irradiance at points and on triangles by adaptive cells over the hemisphere.

#include "sources/sky_light.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <unordered_map>
#include <vector>

#include "core/parallel.h"

namespace penumbra::solver {

namespace {

/// Samples of a cell whose transmittances differ by more than this (relative) see an edge:
/// a pane's own T(θ) varies less across a cell.
constexpr double k_edge_contrast = 0.1;
/// Samples whose sky luminance differs by more than this ratio split the cell (the horizon,
/// the circumsolar peak), down to k_luminance_depth only: jittered samples average a smooth
/// sky without bias, and a sharp horizon split to the finest cells cost every vertical
/// surface outdoors thousands of rays.
constexpr double k_luminance_ratio = 1.5;
constexpr int k_luminance_depth = 2;

/// A cell of the hemisphere: cell (i, j) of the (side << depth)² grid over the unit square,
/// which Shirley & Chiu's concentric map takes to the unit disc, area for area, and the disc
/// lifts to the hemisphere (Malley's method): every cell has projected solid angle
/// π / (side << depth)², and cells stay nearly square, also at the normal.
struct Cell {
    std::int64_t i = 0, j = 0;
};

/// What a cell's four samples saw.
enum class CellSight : std::uint8_t { hidden, open, varies };

/// The direction of the point (a, b) of the unit square around \p frame's normal.
Vec3 cell_direction(const Frame& frame, double a, double b) {
    const double x = 2 * a - 1, y = 2 * b - 1;
    double r = 0, phi = 0;
    if (x != 0 || y != 0) {
        const bool wide = std::abs(x) > std::abs(y);
        r = wide ? x : y;
        phi = wide ? (k_pi / 4) * (y / x) : (k_pi / 2) - (k_pi / 4) * (x / y);
    }
    const double dx = r * std::cos(phi), dy = r * std::sin(phi);
    return frame.to_world(Vec3(dx, dy, std::sqrt(std::max(0.0, 1.0 - dx * dx - dy * dy))));
}

/// Whether the four samples of a cell (transmittances \p t, sky radiances \p l) call for
/// finer cells: some blocked and some not, panes and open sky mixed, or a steep sky (at
/// \p depth below k_luminance_depth).
CellSight sight_of(std::span<const float> t, std::span<const Rgb> l, int depth) {
    const auto [t_lo, t_hi] = std::minmax_element(t.begin(), t.end());
    if (*t_hi <= 0.0f)
        return CellSight::hidden;
    if (*t_lo <= 0.0f || *t_hi - *t_lo > k_edge_contrast * *t_hi)
        return CellSight::varies;
    if (depth >= k_luminance_depth)
        return CellSight::open;
    double lo = 1e300, hi = 0;
    for (const Rgb& c : l) {
        const double y = to_photometric(c);
        lo = std::min(lo, y);
        hi = std::max(hi, y);
    }
    return hi > k_luminance_ratio * lo ? CellSight::varies : CellSight::open;
}

/// The cells of one level with what each saw, to find the neighbours of an edge.
class LevelSights {
public:
    LevelSights(const std::vector<Cell>& cells, const std::vector<CellSight>& sights,
                std::int64_t side)
        : side_(side) {
        for (std::size_t k = 0; k < cells.size(); ++k)
            sight_.emplace(key(cells[k].i, cells[k].j), sights[k]);
    }
    /// Whether an edge-adjacent cell of this level saw otherwise than \p sight: an edge the
    /// samples of \p c missed may run through it.
    bool beside_an_edge(const Cell& c, CellSight sight) const {
        const std::int64_t di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
        for (int k = 0; k < 4; ++k) {
            const std::int64_t i = c.i + di[k], j = c.j + dj[k];
            if (i < 0 || j < 0 || i >= side_ || j >= side_)
                continue;
            const auto it = sight_.find(key(i, j));
            if (it != sight_.end() && it->second != sight)
                return true;
        }
        return false;
    }

private:
    std::int64_t key(std::int64_t i, std::int64_t j) const { return i * side_ + j; }
    std::int64_t side_;
    std::unordered_map<std::int64_t, CellSight> sight_;
};

// Calls \p settle(dirs, radiance, t, k, weight) for each final cell k: its four samples are
// dirs[4k..4k+3] with the sky's radiance and the transmittance to it, and weight the
// projected solid angle of each sample's share of the cell.
template <typename Settle>
void integrate_cells(const Sky& sky, const Vec3& from, const Vec3& n, double diagonal,
                     const VisibilityQuery& visibility, const SkyQuadrature& quadrature, Pcg32& rng,
                     Settle&& settle) {
    const Frame frame = Frame::from_normal(n);
    const float reach = distant_reach(diagonal);
    const Vec3f origin(from);
    std::vector<Cell> cells, finer;
    for (int i = 0; i < quadrature.side; ++i)
        for (int j = 0; j < quadrature.side; ++j)
            cells.push_back({i, j});
    std::vector<Segment> rays;
    std::vector<Vec3> dirs;
    std::vector<Rgb> radiance;
    std::vector<float> t;
    std::vector<CellSight> sights;
    for (int depth = 0; !cells.empty(); ++depth) {
        const std::int64_t side = std::int64_t(quadrature.side) << depth;
        const double d = 1.0 / double(side);
        rays.clear();
        dirs.clear();
        for (const Cell& c : cells)
            for (int s = 0; s < 4; ++s) {
                const double a = d * (double(c.i) + ((s / 2) + rng.next_double()) / 2);
                const double b = d * (double(c.j) + ((s % 2) + rng.next_double()) / 2);
                dirs.push_back(cell_direction(frame, a, b));
                rays.push_back({origin, Vec3f(dirs.back()), 0.0f, reach});
            }
        // One call per level: the sky's own constants (Perez's coefficients, the CIE
        // normalisation) are computed once rather than per ray.
        radiance.resize(dirs.size());
        sky.radiance(dirs, radiance);
        t.resize(rays.size());
        visibility.transmittance(rays, t);
        sights.clear();
        for (std::size_t k = 0; k < cells.size(); ++k)
            sights.push_back(sight_of({t.data() + 4 * k, 4}, {radiance.data() + 4 * k, 4}, depth));
        const LevelSights level(cells, sights, side);
        finer.clear();
        for (std::size_t k = 0; k < cells.size(); ++k) {
            const Cell& c = cells[k];
            if (depth < quadrature.max_depth &&
                (sights[k] == CellSight::varies || level.beside_an_edge(c, sights[k]))) {
                for (int a = 0; a < 2; ++a)
                    for (int b = 0; b < 2; ++b)
                        finer.push_back({2 * c.i + a, 2 * c.j + b});
                continue;
            }
            settle(dirs, radiance, t, k, k_pi * d * d / 4.0);
        }
        cells.swap(finer);
    }
}

} // namespace

RgbD sky_point_irradiance(const Sky& sky, const Vec3& from, const Vec3& n, double diagonal,
                          const VisibilityQuery& visibility, const SkyQuadrature& quadrature,
                          Pcg32& rng) {
    RgbD sum;
    integrate_cells(sky, from, n, diagonal, visibility, quadrature, rng,
                    [&](const std::vector<Vec3>&, const std::vector<Rgb>& radiance,
                        const std::vector<float>& t, std::size_t k, double weight) {
                        RgbD cell;
                        for (std::size_t s = 4 * k; s < 4 * k + 4; ++s)
                            cell += RgbD(radiance[s]) * double(t[s]);
                        sum += cell * weight;
                    });
    return sum;
}

void sky_point_samples(const Sky& sky, const Vec3& from, const Vec3& n, double diagonal,
                       const VisibilityQuery& visibility, const SkyQuadrature& quadrature,
                       Pcg32& rng, std::vector<SkySample>& out) {
    out.clear();
    integrate_cells(sky, from, n, diagonal, visibility, quadrature, rng,
                    [&](const std::vector<Vec3>& dirs, const std::vector<Rgb>& radiance,
                        const std::vector<float>& t, std::size_t k, double weight) {
                        for (std::size_t s = 4 * k; s < 4 * k + 4; ++s)
                            if (t[s] > 0)
                                out.push_back({dirs[s], radiance[s], double(t[s]) * weight});
                    });
}

Rgb sky_triangle_irradiance(const Sky& sky, const OrientedTriangle& target, double offset,
                            double diagonal, std::uint64_t key, const VisibilityQuery& visibility,
                            std::uint64_t seed) {
    const Vec3 centroid = (target.v[0] + target.v[1] + target.v[2]) / 3.0;
    Pcg32 rng = Pcg32::for_stream(RngPurpose::sky_visibility, key, 0, 0, seed);
    const RgbD e = sky_point_irradiance(sky, centroid + target.n * offset, target.n, diagonal,
                                        visibility, k_sky_element_quadrature, rng);
    return Rgb(float(e.r), float(e.g), float(e.b));
}

RgbD shoot_sky(ShootingState& state, const ElementGeometry& geo, const Sky& sky,
               const VisibilityQuery& visibility, const RowSettings& settings, const Context& ctx) {
    std::vector<Rgb> received(geo.size());
    parallel_for_index(geo.size(), 16, [&](std::size_t j) {
        received[j] = sky_triangle_irradiance(sky, geo.oriented(std::uint32_t(j)), geo.offset,
                                              geo.diagonal, j, visibility, settings.seed);
    });
    const RgbD delivered = state.receive_from_afar(received, geo.area);
    ctx.debug("sky shot: {:.6g} lm delivered", to_photometric(delivered));
    return delivered;
}

} // namespace penumbra::solver
