// Rows of element-to-element form factors by shooter-side quadrature (see element_rows.h).

#include "element_rows.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "core/rng.h"
#include "form_factor.h"

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
    }
    diagonal = mesh.scene_diagonal;
    offset = 1e-5 * std::max(diagonal, 1e-3);
}

bool ElementGeometry::in_front_of(std::uint32_t e, std::uint32_t f) const {
    const double eps = 1e-9 * diagonal;
    for (const Vec3& v : triangle[e])
        if (dot(v - triangle[f][0], normal[f]) > eps)
            return true;
    return false;
}

namespace {

struct Quadrature {
    std::array<Vec3, k_max_quadrature_points> point;
    std::size_t count = 0;
};

Quadrature make_quadrature(const std::array<Vec3, 3>& t, int level) {
    std::array<std::array<double, 2>, k_max_quadrature_points> bary{};
    Quadrature q;
    quadrature_barycentrics(level, bary.data(), &q.count);
    for (std::size_t k = 0; k < q.count; ++k)
        q.point[k] = t[0] + (t[1] - t[0]) * bary[k][0] + (t[2] - t[0]) * bary[k][1];
    return q;
}

Segment segment_between(const Vec3& from, const Vec3& to) {
    return {Vec3f(from), Vec3f(to - from), 0.0f, 1.0f};
}

// Casts \p per_point rays from each active quadrature point to random points of j; adds the
// open ones to open[q].
void cast_pair_rays(const ElementGeometry& geo, const VisibilityQuery& visibility,
                    const Quadrature& quad, const std::array<double, k_max_quadrature_points>& f,
                    std::uint32_t i, std::uint32_t j, int per_point, Pcg32& rng,
                    std::array<int, k_max_quadrature_points>& open) {
    std::vector<Segment> segments;
    segments.reserve(quad.count * std::size_t(per_point));
    for (std::size_t q = 0; q < quad.count; ++q) {
        if (f[q] <= 0)
            continue;
        Vec3 from = quad.point[q] + geo.normal[i] * geo.offset;
        for (int r = 0; r < per_point; ++r) {
            Vec3 to = sample_triangle(geo.triangle[j], rng.next_double(), rng.next_double()) +
                      geo.normal[j] * geo.offset;
            segments.push_back(segment_between(from, to));
        }
    }
    std::vector<std::uint8_t> blocked(segments.size());
    visibility.occluded(segments, blocked);
    std::size_t s = 0;
    for (std::size_t q = 0; q < quad.count; ++q) {
        if (f[q] <= 0)
            continue;
        for (int r = 0; r < per_point; ++r)
            open[q] += blocked[s++] ? 0 : 1;
    }
}

// Unoccluded point-to-triangle form factors of the quadrature points toward j (0 where a
// point lies behind j's plane); returns their mean, F_ij without occlusion.
double unoccluded_form_factor(const ElementGeometry& geo, const Quadrature& quad,
                              std::uint32_t i, std::uint32_t j,
                              std::array<double, k_max_quadrature_points>& f_point) {
    const auto& tj = geo.triangle[j];
    double sum = 0;
    for (std::size_t q = 0; q < quad.count; ++q) {
        f_point[q] = 0;
        if (dot(quad.point[q] - tj[0], geo.normal[j]) <= 0)
            continue; // this part of the shooter lies behind the receiver's plane
        f_point[q] = form_factor_point_triangle(quad.point[q], geo.normal[i], tj);
        sum += f_point[q];
    }
    return sum / double(quad.count);
}

struct PairFormFactor {
    double f = 0;             ///< with visibility
    double f_unoccluded = 0;  ///< without
};

// F_ij for one receiver: quadrature over the shooter, visibility per quadrature point. One
// probe ray per point first; only where the probes disagree (a penumbra) are the remaining
// rays cast, so that fully visible and fully hidden pairs cost one ray per point.
PairFormFactor pair_form_factor(const ElementGeometry& geo, const VisibilityQuery& visibility,
                                const Quadrature& quad, std::uint32_t i, std::uint32_t j,
                                const RowSettings& settings) {
    std::array<double, k_max_quadrature_points> f_point{};
    PairFormFactor result;
    result.f_unoccluded = unoccluded_form_factor(geo, quad, i, j, f_point);
    if (result.f_unoccluded <= 0)
        return result;
    std::size_t active = 0;
    for (std::size_t q = 0; q < quad.count; ++q)
        active += f_point[q] > 0 ? 1 : 0;
    Pcg32 rng = Pcg32::for_stream(RngPurpose::form_factor_visibility, i, j, 0, settings.seed);
    std::array<int, k_max_quadrature_points> open{};
    cast_pair_rays(geo, visibility, quad, f_point, i, j, 1, rng, open);
    int open_probes = 0;
    for (std::size_t q = 0; q < quad.count; ++q)
        open_probes += open[q];
    if (open_probes == int(active)) {
        result.f = result.f_unoccluded;
        return result;
    }
    if (open_probes == 0)
        return result;
    const int per_point =
        std::max(1, int(std::ceil(double(settings.visibility_rays) / double(quad.count))));
    if (per_point > 1)
        cast_pair_rays(geo, visibility, quad, f_point, i, j, per_point - 1, rng, open);
    for (std::size_t q = 0; q < quad.count; ++q)
        result.f += f_point[q] * double(open[q]) / per_point;
    result.f /= double(quad.count);
    return result;
}

double escape_fraction(const ElementGeometry& geo, const VisibilityQuery& visibility,
                       const Quadrature& quad, std::uint32_t i, const RowSettings& settings) {
    if (settings.escape_rays <= 0)
        return 0;
    Pcg32 rng = Pcg32::for_stream(RngPurpose::escape_estimate, i, 0, 0, settings.seed);
    std::vector<Segment> segments(std::size_t(settings.escape_rays));
    const float reach = float(4.0 * geo.diagonal + 1.0);
    for (std::size_t r = 0; r < segments.size(); ++r) {
        Vec3 from = quad.point[r % quad.count] + geo.normal[i] * geo.offset;
        Vec3 dir = sample_cosine_hemisphere(geo.normal[i], rng.next_double(), rng.next_double());
        segments[r] = {Vec3f(from), Vec3f(dir), 0.0f, reach};
    }
    std::vector<std::uint8_t> blocked(segments.size());
    visibility.occluded(segments, blocked);
    auto misses = std::count(blocked.begin(), blocked.end(), std::uint8_t(0));
    return double(misses) / double(segments.size());
}



double longest_edge(const std::array<Vec3, 3>& t) {
    return std::max({length(t[1] - t[0]), length(t[2] - t[1]), length(t[0] - t[2])});
}

// Pairs closer than this many element sizes use the fine rule: there F(x → j) varies fast
// over the shooter (log-singular next to a shared edge) and the coarse rule would break
// reciprocity A_i F_ij = A_j F_ji. Far pairs keep the coarse rule, whose error falls as
// (size / distance)².
constexpr double k_near_factor = 2.0;


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
    const Quadrature coarse = make_quadrature(geo.triangle[i], settings.quadrature_level);
    const Quadrature fine = make_quadrature(geo.triangle[i], settings.near_quadrature_level);
    const Vec3 centroid_i = (geo.triangle[i][0] + geo.triangle[i][1] + geo.triangle[i][2]) / 3.0;
    const double size_i = longest_edge(geo.triangle[i]);
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
        const auto& tj = geo.triangle[j];
        const double distance = length((tj[0] + tj[1] + tj[2]) / 3.0 - centroid_i);
        near[j] = distance < k_near_factor * (size_i + longest_edge(tj));
        PairFormFactor pf = pair_form_factor(geo, visibility, near[j] ? fine : coarse, i, jj,
                                             settings);
        dense[j] = float(pf.f);
        if (near[j] && pf.f_unoccluded > 0) {
            std::array<double, k_max_quadrature_points> scratch{};
            near_coarse[j] = unoccluded_form_factor(geo, coarse, i, jj, scratch) *
                             (pf.f / pf.f_unoccluded);
        }
    });
    rescale_far_pairs(dense, near, near_coarse);
    Row row;
    for (std::size_t j = 0; j < n; ++j) {
        if (dense[j] > 0) {
            row.receiver.push_back(std::uint32_t(j));
            row.form_factor.push_back(dense[j]);
        }
    }
    row.escape = escape_fraction(geo, visibility, coarse, i, settings);
    return row;
}

} // namespace penumbra::solver
