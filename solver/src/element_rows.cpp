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

// F_ij for one receiver: quadrature over the shooter, visibility per quadrature point.
double pair_form_factor(const ElementGeometry& geo, const VisibilityQuery& visibility,
                        const Quadrature& quad, std::uint32_t i, std::uint32_t j,
                        const RowSettings& settings) {
    const auto& tj = geo.triangle[j];
    std::array<double, k_max_quadrature_points> f_point{};
    double f_unoccluded = 0;
    for (std::size_t q = 0; q < quad.count; ++q) {
        if (dot(quad.point[q] - tj[0], geo.normal[j]) <= 0)
            continue; // this part of the shooter lies behind the receiver's plane
        f_point[q] = form_factor_point_triangle(quad.point[q], geo.normal[i], tj);
        f_unoccluded += f_point[q];
    }
    if (f_unoccluded <= 0)
        return 0;
    const int per_point =
        std::max(1, int(std::ceil(double(settings.visibility_rays) / double(quad.count))));
    Pcg32 rng = Pcg32::for_stream(RngPurpose::form_factor_visibility, i, j, 0, settings.seed);
    std::vector<Segment> segments;
    segments.reserve(quad.count * std::size_t(per_point));
    for (std::size_t q = 0; q < quad.count; ++q) {
        if (f_point[q] <= 0)
            continue;
        Vec3 from = quad.point[q] + geo.normal[i] * geo.offset;
        for (int r = 0; r < per_point; ++r) {
            Vec3 to = sample_triangle(tj, rng.next_double(), rng.next_double()) +
                      geo.normal[j] * geo.offset;
            segments.push_back(segment_between(from, to));
        }
    }
    std::vector<std::uint8_t> blocked(segments.size());
    visibility.occluded(segments, blocked);
    double f = 0;
    std::size_t s = 0;
    for (std::size_t q = 0; q < quad.count; ++q) {
        if (f_point[q] <= 0)
            continue;
        int open = 0;
        for (int r = 0; r < per_point; ++r)
            open += blocked[s++] ? 0 : 1;
        f += f_point[q] * double(open) / per_point;
    }
    return f / double(quad.count);
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

} // namespace

Row compute_row(const ElementGeometry& geo, const VisibilityQuery& visibility, std::uint32_t i,
                const RowSettings& settings) {
    const Quadrature quad = make_quadrature(geo.triangle[i], settings.quadrature_level);
    const std::size_t n = geo.size();
    std::vector<float> dense(n, 0.0f);
    parallel_for_index(n, 64, [&](std::size_t j) {
        auto jj = std::uint32_t(j);
        if (jj == i || geo.twin[i] == std::int32_t(jj))
            return;
        if (!geo.in_front_of(jj, i) || !geo.in_front_of(i, jj))
            return;
        dense[j] = float(pair_form_factor(geo, visibility, quad, i, jj, settings));
    });
    Row row;
    for (std::size_t j = 0; j < n; ++j) {
        if (dense[j] > 0) {
            row.receiver.push_back(std::uint32_t(j));
            row.form_factor.push_back(dense[j]);
        }
    }
    row.escape = escape_fraction(geo, visibility, quad, i, settings);
    return row;
}

} // namespace penumbra::solver
