// Analytic form factors. Point-to-polygon: F = (1/2π) Σ_i γ_i n·Γ_i over the polygon's edges,
// with γ_i the angle the edge subtends at x and Γ_i the unit normal of the plane through x and
// the edge (Lambert 1760; Baum, Rushmeier & Winget 1989). Terms whose edge passes through x
// (γ undefined) contribute nothing: such an edge lies in a plane through x and adds no
// projected solid angle.

#include "kernels/form_factor.h"

#include <cmath>

namespace penumbra::solver {

std::size_t clip_to_half_space(const Vec3& x, const Vec3& n, const Vec3* poly, std::size_t count,
                               Vec3* out) {
    std::size_t m = 0;
    for (std::size_t i = 0; i < count; ++i) {
        const Vec3& a = poly[i];
        const Vec3& b = poly[(i + 1) % count];
        double da = dot(a - x, n), db = dot(b - x, n);
        if (da >= 0)
            out[m++] = a;
        if ((da >= 0) != (db >= 0)) {
            double t = da / (da - db);
            out[m++] = a + (b - a) * t;
        }
    }
    return m;
}

double form_factor_point_polygon(const Vec3& x, const Vec3& n, const Vec3* poly,
                                 std::size_t count) {
    constexpr std::size_t k_max = 16;
    Vec3 clipped[k_max + 1];
    if (count > k_max)
        count = k_max;
    std::size_t m = clip_to_half_space(x, n, poly, count, clipped);
    if (m < 3)
        return 0.0;
    double sum = 0.0;
    for (std::size_t i = 0; i < m; ++i)
        sum += contour_term(x, n, clipped[i], clipped[(i + 1) % m]);
    return std::abs(sum) / (2.0 * k_pi);
}

// On x86-64 (with ifunc), cloned for AVX2 (four points a step), chosen at load time. Not
// FMA: the clones then round alike, and results do not depend on the machine.
#if defined(__x86_64__) && defined(__linux__)
#define PENUMBRA_CLONE_AVX2 __attribute__((target_clones("avx2", "default")))
#else
#define PENUMBRA_CLONE_AVX2
#endif
PENUMBRA_CLONE_AVX2 void add_contour_terms(const Vec3& a, const Vec3& b, const Vec3& n,
                                           ContourPoints& points) {
    const Vec3 a_ = a, b_ = b, n_ = n; // copies: nothing the loop writes aliases them
    const std::size_t m = points.size();
    const double* __restrict x = points.x.data();
    const double* __restrict y = points.y.data();
    const double* __restrict z = points.z.data();
    double* __restrict sum = points.sum.data();
    for (std::size_t i = 0; i < m; ++i)
        sum[i] += contour_term(a_.x - x[i], a_.y - y[i], a_.z - z[i], b_.x - x[i], b_.y - y[i],
                               b_.z - z[i], n_);
}

void form_factors_point_triangle(const Vec3* x, std::size_t count, const Vec3& n,
                                 const std::array<Vec3, 3>& tri, double* out) {
    thread_local ContourPoints whole;
    whole.clear();
    for (std::size_t k = 0; k < count; ++k) {
        // The clipping's own test: no vertex behind the tangent plane leaves the triangle
        // whole, and its contour the three edges in order.
        if (dot(tri[0] - x[k], n) >= 0 && dot(tri[1] - x[k], n) >= 0 && dot(tri[2] - x[k], n) >= 0)
            whole.push_back(x[k], k);
        else
            out[k] = form_factor_point_triangle(x[k], n, tri);
    }
    if (whole.empty())
        return;
    for (std::size_t i = 0; i < 3; ++i)
        add_contour_terms(tri[i], tri[(i + 1) % 3], n, whole);
    whole.write_form_factors(out);
}

double solid_angle_triangle(const Vec3& p, const std::array<Vec3, 3>& tri) {
    Vec3 a = tri[0] - p, b = tri[1] - p, c = tri[2] - p;
    double la = length(a), lb = length(b), lc = length(c);
    double numerator = std::abs(dot(a, cross(b, c)));
    double denominator = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
    return 2.0 * std::atan2(numerator, denominator);
}

void quadrature_barycentrics(int level, std::array<double, 2>* out, std::size_t* count) {
    // Sub-triangles of a k × k subdivision (k = 2^level) in barycentric grid coordinates.
    const int k = 1 << level;
    std::size_t m = 0;
    for (int j = 0; j < k; ++j) {
        for (int i = 0; i < k - j; ++i) {
            // Upward sub-triangle (i, j), (i+1, j), (i, j+1): centroid (i + 1/3, j + 1/3).
            out[m++] = {(i + 1.0 / 3.0) / k, (j + 1.0 / 3.0) / k};
            if (i + 1 < k - j) // downward (i+1, j), (i+1, j+1), (i, j+1)
                out[m++] = {(i + 2.0 / 3.0) / k, (j + 2.0 / 3.0) / k};
        }
    }
    *count = m;
}

Vec3 sample_cosine_hemisphere(const Vec3& n, double u1, double u2) {
    double r = std::sqrt(u1), phi = 2.0 * k_pi * u2;
    Frame f = Frame::from_normal(n);
    return f.to_world(Vec3(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - u1))));
}

Vec3 sample_sphere(double u1, double u2) {
    double z = 1.0 - 2.0 * u1, r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.0 * k_pi * u2;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

} // namespace penumbra::solver
