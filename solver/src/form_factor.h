#pragma once
// Analytic form-factor kernels: point-to-polygon (Lambert's contour integral; Baum, Rushmeier
// & Winget 1989) with clipping to the receiver's hemisphere, and the solid angle of a
// triangle (Van Oosterom & Strackee 1983).

#include <array>
#include <cmath>
#include <cstddef>

#include "core/rng.h"
#include "core/vec.h"

namespace penumbra::solver {

/// \brief Form factor from a differential area at \p x with unit normal \p n to the planar
///        polygon \p poly (any winding). The part of the polygon below x's tangent plane is
///        clipped away. The caller checks that the polygon's emitting side faces x.
double form_factor_point_polygon(const Vec3& x, const Vec3& n, const Vec3* poly,
                                 std::size_t count);

/// \brief atan2(y, x) for y ≥ 0 (an angle in [0, π], between two vectors whose cross product
///        has length y and dot product x), within 3e-9 rad. The form factors' contour sums
///        spent a quarter of a large solve in libm's atan2, which rounds correctly: this
///        folds the ratio into [0, tan 15°] and sums atan's series there to the 11th power.
inline double vector_angle(double y, double x) {
    constexpr double k_tan15 = 0.26794919243112270, k_sqrt3 = 1.7320508075688772;
    const double ax = std::abs(x);
    const bool steep = y > ax;
    if (!(steep ? y > 0 : ax > 0))
        return 0.0;
    double t = steep ? ax / y : y / ax; // in [0, 1]
    double base = 0.0;
    if (t > k_tan15) { // atan t = 30° + atan((√3 t − 1) / (t + √3))
        t = (k_sqrt3 * t - 1.0) / (t + k_sqrt3);
        base = k_pi / 6.0;
    }
    const double t2 = t * t;
    double a = t * (1.0 + t2 * (-1.0 / 3.0 +
                                t2 * (1.0 / 5.0 +
                                      t2 * (-1.0 / 7.0 + t2 * (1.0 / 9.0 + t2 * (-1.0 / 11.0))))));
    a += base; // atan of the ratio, in [0, π/4]
    if (steep)
        a = 0.5 * k_pi - a;
    return x < 0 ? k_pi - a : a;
}

/// \brief One edge's term of the contour sum, γ n·Γ: F = |Σ over a polygon's edges| / 2π
///        where the whole polygon lies in front of x's tangent plane.
inline double contour_term(const Vec3& x, const Vec3& n, const Vec3& a, const Vec3& b) {
    const Vec3 r0 = a - x, r1 = b - x;
    const Vec3 c = cross(r0, r1);
    const double c_len = length(c);
    if (c_len <= 1e-300)
        return 0.0;
    return vector_angle(c_len, dot(r0, r1)) * dot(n, c) / c_len;
}

inline double form_factor_point_triangle(const Vec3& x, const Vec3& n,
                                         const std::array<Vec3, 3>& tri) {
    return form_factor_point_polygon(x, n, tri.data(), 3);
}

/// \brief Sutherland–Hodgman: the part of polygon \p poly where dot(p − x, n) ≥ 0, written to
///        \p out (count + 1 points suffice for a convex polygon); returns its point count.
std::size_t clip_to_half_space(const Vec3& x, const Vec3& n, const Vec3* poly, std::size_t count,
                               Vec3* out);

/// \brief Solid angle (sr) subtended by triangle \p tri seen from \p p.
double solid_angle_triangle(const Vec3& p, const std::array<Vec3, 3>& tri);

/// \brief Points of the equal-weight rule of \p level: the centroids of the 4^level congruent
///        sub-triangles. Exact for linear integrands; returns barycentrics (b1, b2).
void quadrature_barycentrics(int level, std::array<double, 2>* out, std::size_t* count);
inline constexpr std::size_t k_max_quadrature_points = 64; ///< level 3

/// A uniformly distributed point on a triangle from two uniform numbers in [0, 1).
inline Vec3 sample_triangle(const std::array<Vec3, 3>& t, double u1, double u2) {
    double su = std::sqrt(u1);
    double b0 = 1.0 - su, b1 = u2 * su;
    return t[0] * b0 + t[1] * b1 + t[2] * (1.0 - b0 - b1);
}

/// A cosine-distributed direction around \p n (Malley's method).
Vec3 sample_cosine_hemisphere(const Vec3& n, double u1, double u2);

/// A uniformly distributed direction on the unit sphere.
Vec3 sample_sphere(double u1, double u2);

} // namespace penumbra::solver
