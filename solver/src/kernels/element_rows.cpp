// Element-to-element form factors (see kernels/element_rows.h): quadrature on one triangle of the
// analytic point-to-triangle form factor toward the other, times visibility from rays.

#include "kernels/element_rows.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "core/rng.h"
#include "kernels/form_factor.h"

namespace penumbra::solver {

ElementGeometry::ElementGeometry(const RadiosityMesh& mesh) {
    const std::size_t n = mesh.element_count();
    triangle.resize(n);
    normal.resize(n);
    area.resize(n);
    twin = mesh.element_twin;
    for (std::size_t e = 0; e < n; ++e) {
        const auto& t = mesh.triangles[e];
        triangle[e] = {mesh.vertex(t[0]), mesh.vertex(t[1]), mesh.vertex(t[2])};
        normal[e] = mesh.patch_of(std::uint32_t(e)).normal;
        area[e] = mesh.element_area[e];
        emitter.push_back(mesh.patch_of(std::uint32_t(e)).emission.is_black() ? 0 : 1);
    }
    diagonal = mesh.scene_diagonal;
    offset = 1e-5 * std::max(diagonal, 1e-3);
}

bool ElementGeometry::in_front_of(std::uint32_t e, std::uint32_t f) const {
    return in_front(oriented(e), oriented(f), 1e-9 * diagonal);
}

bool in_front(const OrientedTriangle& a, const OrientedTriangle& b, double eps) {
    for (const Vec3& v : a.v)
        if (dot(v - b.v[0], b.n) > eps)
            return true;
    return false;
}

namespace {

struct Quadrature {
    std::array<Vec3, k_max_quadrature_points> point;
    std::size_t count = 0;
    /// The points are the centroids of congruent sub-triangles, each the triangle's corner
    /// one (t0, t0 + e1, t0 + e2) moved, or turned half round (the rule's "downward" ones).
    Vec3 e1, e2;
    std::array<std::int8_t, k_max_quadrature_points> turned{};
    /// A uniform point of point k's sub-triangle from two uniform numbers.
    Vec3 jittered(std::size_t k, double u1, double u2) const {
        if (u1 + u2 > 1) { // the unit square's upper half folded onto the lower
            u1 = 1 - u1;
            u2 = 1 - u2;
        }
        const double sign = turned[k] ? -1.0 : 1.0;
        return point[k] + (e1 * (u1 - 1.0 / 3.0) + e2 * (u2 - 1.0 / 3.0)) * sign;
    }
};

Quadrature make_quadrature(const std::array<Vec3, 3>& t, int level) {
    std::array<std::array<double, 2>, k_max_quadrature_points> bary{};
    Quadrature q;
    quadrature_barycentrics(level, bary.data(), &q.count);
    const double k = double(1 << level);
    q.e1 = (t[1] - t[0]) / k;
    q.e2 = (t[2] - t[0]) / k;
    for (std::size_t i = 0; i < q.count; ++i) {
        q.point[i] = t[0] + (t[1] - t[0]) * bary[i][0] + (t[2] - t[0]) * bary[i][1];
        // An upward centroid sits at a third of its cell, a turned one at two thirds.
        const double cell = bary[i][0] * k - std::floor(bary[i][0] * k + 1e-9);
        q.turned[i] = cell > 0.5 ? 1 : 0;
    }
    return q;
}

double longest_edge(const std::array<Vec3, 3>& t) {
    return std::max({length(t[1] - t[0]), length(t[2] - t[1]), length(t[0] - t[2])});
}

using PointValues = std::array<double, k_max_quadrature_points>;

// Point form factors toward b of the quadrature points (0 where a point lies behind b's
// plane); returns their mean.
double point_form_factors(const Quadrature& quad, const OrientedTriangle& a,
                          const OrientedTriangle& b, PointValues& f_point) {
    std::array<Vec3, k_max_quadrature_points> front;
    std::array<std::size_t, k_max_quadrature_points> index;
    std::size_t m = 0;
    for (std::size_t q = 0; q < quad.count; ++q) {
        f_point[q] = 0;
        if (dot(quad.point[q] - b.v[0], b.n) <= 0)
            continue; // this part of a lies behind b's plane
        front[m] = quad.point[q];
        index[m++] = q;
    }
    PointValues f;
    form_factors_point_triangle(front.data(), m, a.n, b.v, f.data());
    for (std::size_t i = 0; i < m; ++i)
        f_point[index[i]] = f[i];
    double sum = 0;
    for (std::size_t q = 0; q < quad.count; ++q)
        sum += f_point[q];
    return sum / double(quad.count);
}

/// Rays that probe a pair's visibility before more are cast (pair_visibility): a pair all of
/// whose probes are open counts as unoccluded, which overestimates a pair with a small
/// occluded part (by up to about 8 % of its transfer with 4 probes, 2 % with 16), so fine
/// rules, whose pairs are near and large relative to their distance, get more.
constexpr int k_min_probe_rays = 4;
constexpr int k_max_probe_rays = 16;
/// Pairs whose far end subtends more than this (sr) from the near end's centroid draw their
/// rays' directions in its solid angle; others draw points of it by area (whose kernel then
/// varies little over it).
constexpr double k_solid_angle_sampling = 0.05;

struct PairVisibility {
    double fraction = 0;  ///< of the rays, weighed as the transfer
    bool partial = false; ///< the rays disagreed
};

/// A direction drawn uniformly in the spherical triangle of unit vectors a, b, c, and its
/// solid angle (Arvo 1995, "Stratified sampling of spherical triangles").
struct SphericalSample {
    Vec3 direction;
    double solid_angle = 0;
};

SphericalSample sample_spherical_triangle(const Vec3& a, const Vec3& b, const Vec3& c, double u1,
                                          double u2) {
    const Vec3 n_ab = normalize(cross(a, b)), n_bc = normalize(cross(b, c)),
               n_ca = normalize(cross(c, a));
    const double alpha = std::acos(std::clamp(-dot(n_ab, n_ca), -1.0, 1.0));
    const double beta = std::acos(std::clamp(-dot(n_bc, n_ab), -1.0, 1.0));
    const double gamma = std::acos(std::clamp(-dot(n_ca, n_bc), -1.0, 1.0));
    SphericalSample out;
    out.solid_angle = alpha + beta + gamma - k_pi;
    // The sub-triangle a, b, ĉ of area u1 × the whole: ĉ on the arc from a to c.
    const double area = u1 * out.solid_angle;
    const double s = std::sin(area - alpha), t = std::cos(area - alpha);
    const double u = t - std::cos(alpha), v = s + std::sin(alpha) * dot(a, b);
    const double denominator = (v * s + u * t) * std::sin(alpha);
    const double q =
        denominator != 0
            ? std::clamp(((v * t - u * s) * std::cos(alpha) - v) / denominator, -1.0, 1.0)
            : 1.0;
    const Vec3 c_hat = a * q + normalize(c - a * dot(c, a)) * std::sqrt(1 - q * q);
    // Then a point on the arc from b to ĉ.
    const double z = std::clamp(1 - u2 * (1 - dot(c_hat, b)), -1.0, 1.0);
    const Vec3 w = c_hat - b * dot(c_hat, b);
    const double w_len = length(w);
    out.direction = w_len > 0 ? b * z + w * (std::sqrt(1 - z * z) / w_len) : b;
    return out;
}

// The visible fraction of the transfer from a's quadrature points (whose shares of it are
// \p f) to b, ∫∫ K V / ∫∫ K with K = cos cos / r²: rays leave uniform points of the points'
// sub-triangles, drawn in proportion to the points' shares (stratified), toward b, and each
// counts K over the density it was drawn with (self-normalised). Toward a b that subtends
// much, directions are drawn uniformly in its solid angle from the ray's origin (the weight
// is then the cosine there: steady where K peaks, by a common edge); toward others, points
// by area (weight K). As many probes as points (4 to 16) first; \p rays more unless all were
// open.
PairVisibility pair_visibility(const Quadrature& quad, const PointValues& f,
                               const OrientedTriangle& a, const OrientedTriangle& b, double offset,
                               int rays, const VisibilityQuery& visibility, Pcg32& rng) {
    PairVisibility out;
    std::array<double, k_max_quadrature_points + 1> running{};
    for (std::size_t i = 0; i < quad.count; ++i)
        running[i + 1] = running[i] + std::max(0.0, f[i]);
    const double total = running[quad.count];
    if (total <= 0)
        return out;
    // Endpoints leave their own surface along its normal and, where the two planes meet at an
    // angle, the other surface's plane too: a target on a wall next to the floor would
    // otherwise end within float precision of the floor and count as blocked.
    const double cross_weight = offset * (1.0 - std::abs(dot(a.n, b.n)));
    const Vec3 lift_a = a.n * offset + b.n * cross_weight;
    const Vec3 lift_b = b.n * offset + a.n * cross_weight;
    const Vec3 centroid_a = (a.v[0] + a.v[1] + a.v[2]) / 3.0;
    auto directions = [&](const Vec3& x, std::array<Vec3, 3>& d) {
        for (std::size_t k = 0; k < 3; ++k)
            d[k] = normalize(b.v[k] - x);
    };
    const bool by_angle = solid_angle_triangle(centroid_a, b.v) > k_solid_angle_sampling;
    // Called for every element pair: no allocation per call (visibility queries start no
    // parallel work that could run another pair on this thread).
    thread_local std::vector<Segment> segments;
    thread_local std::vector<std::uint8_t> blocked;
    thread_local std::vector<double> weight;
    int open = 0, cast_rays = 0;
    double w_open = 0, w_all = 0;
    auto cast = [&](int n) {
        segments.clear();
        weight.clear();
        for (int j = 0; j < n; ++j) {
            const double u = (double(j) + rng.next_double()) / double(n) * total;
            const auto it = std::upper_bound(running.begin() + 1,
                                             running.begin() + std::ptrdiff_t(quad.count) + 1, u);
            const auto i = std::size_t(std::clamp<std::ptrdiff_t>(it - running.begin() - 1, 0,
                                                                  std::ptrdiff_t(quad.count) - 1));
            const Vec3 x = quad.jittered(i, rng.next_double(), rng.next_double());
            const double u1 = rng.next_double(), u2 = rng.next_double();
            Vec3 y;
            double w = 0;
            if (by_angle) {
                std::array<Vec3, 3> d;
                directions(x, d);
                const SphericalSample sample = sample_spherical_triangle(d[0], d[1], d[2], u1, u2);
                const double along = dot(sample.direction, b.n);
                const double cos_x = dot(sample.direction, a.n);
                if (along < 0 && cos_x > 0) {
                    y = x + sample.direction * (dot(b.v[0] - x, b.n) / along);
                    w = cos_x * sample.solid_angle / f[i];
                } else {
                    y = sample_triangle(b.v, u1, u2); // a ray of no weight
                }
            } else {
                y = sample_triangle(b.v, u1, u2);
                const Vec3 d = y - x;
                const double r2 = dot(d, d);
                if (r2 > 0)
                    w = std::max(0.0, dot(a.n, d)) * std::max(0.0, -dot(b.n, d)) / (r2 * r2 * f[i]);
            }
            const Vec3 from = x + lift_a, to = y + lift_b;
            segments.push_back({Vec3f(from), Vec3f(to - from), 0.0f, 1.0f});
            weight.push_back(std::isfinite(w) ? w : 0.0);
        }
        blocked.assign(segments.size(), 0);
        visibility.occluded(segments, blocked);
        for (std::size_t j = 0; j < blocked.size(); ++j) {
            open += blocked[j] ? 0 : 1;
            w_all += weight[j];
            w_open += blocked[j] ? 0.0 : weight[j];
        }
        cast_rays += n;
    };
    // A few blocked probes do not prove a pair dark (a pair seen through a door would be
    // dropped for good): those get the full rays too.
    const int probes = std::clamp(int(quad.count), k_min_probe_rays, k_max_probe_rays);
    cast(probes);
    if (open < probes)
        cast(std::max(rays, 1));
    out.partial = open > 0 && open < cast_rays;
    out.fraction = w_all > 0 ? w_open / w_all : double(open) / double(cast_rays);
    return out;
}

} // namespace

bool is_near(const OrientedTriangle& a, const OrientedTriangle& b) {
    const Vec3 ca = (a.v[0] + a.v[1] + a.v[2]) / 3.0, cb = (b.v[0] + b.v[1] + b.v[2]) / 3.0;
    return length(cb - ca) < k_near_factor * (longest_edge(a.v) + longest_edge(b.v));
}

int quadrature_level_for(const OrientedTriangle& a, const OrientedTriangle& b,
                         const RowSettings& settings) {
    if (is_near(a, b)) {
        if (settings.apart_quadrature_level >= settings.near_quadrature_level)
            return settings.near_quadrature_level;
        // Only a pair that touches (a shared vertex) has the steep part by a common edge that
        // the fine rule is for.
        const double tol = 1e-6 * (longest_edge(a.v) + longest_edge(b.v));
        for (const Vec3& p : a.v)
            for (const Vec3& q : b.v)
                if (length(p - q) <= tol)
                    return settings.near_quadrature_level;
        return settings.apart_quadrature_level;
    }
    // F(x → b) is convex over a, so a coarse centroid rule underestimates its integral
    // (Jensen): resolve a finely enough relative to the distance, whatever b's size.
    const Vec3 ca = (a.v[0] + a.v[1] + a.v[2]) / 3.0, cb = (b.v[0] + b.v[1] + b.v[2]) / 3.0;
    const double ratio = longest_edge(a.v) / std::max(length(cb - ca), 1e-300);
    const int level =
        ratio < 0.1 ? settings.quadrature_level
                    : (ratio < 0.4 ? settings.quadrature_level + 1 : settings.quadrature_level + 2);
    return std::min(level, settings.near_quadrature_level);
}

namespace {

/// The unoccluded form factor and its spread; \p quad and \p f_point keep the points'.
PairFormFactor unoccluded(const OrientedTriangle& a, const OrientedTriangle& b,
                          const Quadrature& quad, PointValues& f_point) {
    PairFormFactor result;
    result.f_unoccluded = point_form_factors(quad, a, b, f_point);
    if (result.f_unoccluded > 0) {
        const auto [lo, hi] = std::minmax_element(f_point.begin(), f_point.begin() + quad.count);
        result.f_spread = *hi - *lo;
    }
    return result;
}

} // namespace

PairFormFactor triangle_form_factor_visible(const OrientedTriangle& a, const OrientedTriangle& b,
                                            int level) {
    PointValues f_point{};
    PairFormFactor result = unoccluded(a, b, make_quadrature(a.v, level), f_point);
    result.f = result.f_unoccluded;
    return result;
}

PairFormFactor triangle_form_factor(const OrientedTriangle& a, const OrientedTriangle& b, int level,
                                    const VisibilityQuery& visibility, double offset,
                                    std::uint64_t key_a, std::uint64_t key_b,
                                    const RowSettings& settings) {
    const Quadrature quad = make_quadrature(a.v, level);
    PointValues f_point{};
    PairFormFactor result = unoccluded(a, b, quad, f_point);
    if (result.f_unoccluded <= 0)
        return result;
    Pcg32 rng =
        Pcg32::for_stream(RngPurpose::form_factor_visibility, key_a, key_b, 0, settings.seed);
    const PairVisibility v =
        pair_visibility(quad, f_point, a, b, offset, settings.visibility_rays, visibility, rng);
    result.f = result.f_unoccluded * v.fraction;
    result.partial = v.partial;
    return result;
}

namespace {

// A rows × cols grid of n strata (rows the largest divisor of n up to √n): a point's rays each
// take one cell of the unit square of the cosine sampling.
struct StratumGrid {
    std::size_t rows = 1, cols = 1;
};

StratumGrid stratum_grid(std::size_t n) {
    StratumGrid g;
    for (std::size_t a = 1; a * a <= n; ++a)
        if (n % a == 0)
            g.rows = a;
    g.cols = std::max<std::size_t>(n / g.rows, 1);
    return g;
}

} // namespace

double escape_fraction(const ElementGeometry& geo, const VisibilityQuery& visibility,
                       std::uint32_t i, const RowSettings& settings) {
    const int rays = geo.emitter[i] ? settings.escape_rays_emitter : settings.escape_rays;
    if (rays <= 0)
        return 0;
    const Quadrature quad = make_quadrature(geo.triangle[i], settings.quadrature_level);
    Pcg32 rng = Pcg32::for_stream(RngPurpose::escape_estimate, i, 0, 0, settings.seed);
    auto segments = std::vector<Segment>(std::size_t(rays));
    const float reach = float(4.0 * geo.diagonal + 1.0);
    // Each point's rays are jittered over a grid of its own on the cosine hemisphere: with 16
    // rays a leaf, independent directions left the Cornell box's escaped power 0.3 % of the
    // emitted power apart from seed to seed, more than the balance it is checked against.
    const std::size_t points = std::size_t(quad.count);
    const std::size_t per_point = (segments.size() + points - 1) / points;
    const StratumGrid grid = stratum_grid(per_point);
    for (std::size_t r = 0; r < segments.size(); ++r) {
        const Vec3 from = quad.point[r % points] + geo.normal[i] * geo.offset;
        const std::size_t k = r / points; // the ray's stratum among its point's
        const double u1 = (double(k / grid.cols) + rng.next_double()) / double(grid.rows);
        const double u2 = (double(k % grid.cols) + rng.next_double()) / double(grid.cols);
        const Vec3 dir = sample_cosine_hemisphere(geo.normal[i], u1, u2);
        segments[r] = {Vec3f(from), Vec3f(dir), 0.0f, reach};
    }
    // Through panes of glazing their T(θ) escapes (PowerBalance::escaped).
    std::vector<float> t(segments.size());
    visibility.transmittance(segments, t);
    double open = 0;
    for (float x : t)
        open += double(x);
    return open / double(segments.size());
}

namespace {

// Both rules satisfy Σ_j F(x → j) = 1 at each of their points in a closed unoccluded scene,
// so the far receivers' true sum is the coarse total minus the near receivers' fine values.
// Rescaling the far pairs to it keeps the row's sum that of the coarse rule (energy exact)
// while the near pairs get the accurate values (reciprocity).
void rescale_far_pairs(std::vector<float>& dense, const std::vector<std::uint8_t>& near,
                       const std::vector<double>& near_coarse) {
    double near_fine = 0, near_coarse_sum = 0, far = 0;
    for (std::size_t j = 0; j < dense.size(); ++j) {
        if (near[j]) {
            near_fine += dense[j];
            near_coarse_sum += near_coarse[j];
        } else {
            far += dense[j];
        }
    }
    if (far <= 0)
        return;
    const double scale = std::max(0.0, 1.0 + (near_coarse_sum - near_fine) / far);
    for (std::size_t j = 0; j < dense.size(); ++j)
        if (!near[j])
            dense[j] = float(dense[j] * scale);
}

} // namespace

Row compute_row(const ElementGeometry& geo, const VisibilityQuery& visibility, std::uint32_t i,
                const RowSettings& settings) {
    const OrientedTriangle ti = geo.oriented(i);
    const std::size_t n = geo.size();
    std::vector<float> dense(n, 0.0f);
    std::vector<std::uint8_t> near(n, 0);
    std::vector<double> near_coarse(n, 0.0); // coarse-rule F of near pairs, same visibility
    parallel_for_index(n, 64, [&](std::size_t j) {
        auto jj = std::uint32_t(j);
        if (jj == i || geo.twin[i] == std::int32_t(jj))
            return;
        if (!geo.in_front_of(jj, i) || !geo.in_front_of(i, jj))
            return;
        const OrientedTriangle tj = geo.oriented(jj);
        near[j] = is_near(ti, tj);
        const int level = near[j] ? settings.near_quadrature_level : settings.quadrature_level;
        PairFormFactor pf =
            triangle_form_factor(ti, tj, level, visibility, geo.offset, i, jj, settings);
        dense[j] = float(pf.f);
        if (near[j] && pf.f_unoccluded > 0)
            near_coarse[j] = triangle_form_factor_visible(ti, tj, settings.quadrature_level).f *
                             (pf.f / pf.f_unoccluded);
    });
    rescale_far_pairs(dense, near, near_coarse);
    Row row;
    for (std::size_t j = 0; j < n; ++j) {
        if (dense[j] > 0) {
            row.receiver.push_back(std::uint32_t(j));
            row.form_factor.push_back(dense[j]);
        }
    }
    row.escape = escape_fraction(geo, visibility, i, settings);
    return row;
}

} // namespace penumbra::solver
