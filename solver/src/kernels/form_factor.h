#pragma once
// Analytic form-factor kernels: point-to-polygon (Lambert's contour integral; Baum, Rushmeier
// & Winget 1989) with clipping to the receiver's hemisphere, and the solid angle of a
// triangle (Van Oosterom & Strackee 1983).

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "core/rng.h"
#include "core/vec.h"

namespace penumbra::solver {

/// \brief Form factor from a differential area at \p x with unit normal \p n to the planar
///        polygon \p poly (any winding). The part of the polygon below x's tangent plane is
///        clipped away. The caller checks that the polygon's emitting side faces x.
double form_factor_point_polygon(const Vec3& x, const Vec3& n, const Vec3* poly, std::size_t count);

/// \brief atan(t) for t in [0, 1], within 6.1e-11 of it relatively: a polynomial in t²
///        (least squares at Chebyshev nodes, degree 11) in Estrin's scheme, with no branch and
///        no division.
inline double atan_unit(double t) {
    constexpr double c0 = 0.99999999993907696, c1 = -0.3333333151817387, c2 = 0.19999909955996786,
                     c3 = -0.14283948404175323, c4 = 0.11092984641754024,
                     c5 = -0.089790503253429688, c6 = 0.072422819112294701,
                     c7 = -0.054215264419245006, c8 = 0.034133367440394913,
                     c9 = -0.016055117215345222, c10 = 0.0048272086315059946,
                     c11 = -0.00068049363598211409;
    const double s = t * t, s2 = s * s, s4 = s2 * s2, s8 = s4 * s4;
    const double low = (c0 + c1 * s) + (c2 + c3 * s) * s2;
    const double mid = (c4 + c5 * s) + (c6 + c7 * s) * s2;
    const double high = (c8 + c9 * s) + (c10 + c11 * s) * s2;
    return (low + mid * s4 + high * s8) * t;
}

/// \brief The angle atan2(y, x) in [0, π] for y ≥ 0 from atan of \p ratio = min(y, |x|) /
///        max(y, |x|), folded back by the octant (steep where y > |x|, obtuse where x < 0)
///        with signs rather than branches, which the octants of a contour's edges mispredict.
inline double fold_angle(double ratio, double y, double x) {
    const double a = atan_unit(ratio);
    const double steep = std::copysign(1.0, std::abs(x) - y); // −1 where steep
    const double b = (1.0 - steep) * (0.25 * k_pi) + steep * a;
    const double side = std::copysign(1.0, x); // −1 where obtuse
    return (1.0 - side) * (0.5 * k_pi) + side * b;
}

/// \brief One edge's term of the contour sum, γ n·Γ, for edge vectors \p r0 and \p r1 from
///        the point (as components): F = |Σ over a polygon's edges| / 2π where the whole
///        polygon lies in front of the point's tangent plane. Branch-free, for the loops over
///        points of add_contour_terms.
inline double contour_term(double r0x, double r0y, double r0z, double r1x, double r1y, double r1z,
                           const Vec3& n) {
    const double cx = r0y * r1z - r0z * r1y, cy = r0z * r1x - r0x * r1z, cz = r0x * r1y - r0y * r1x;
    const double c_len = std::sqrt(cx * cx + cy * cy + cz * cz);
    const double d = r0x * r1x + r0y * r1y + r0z * r1z;
    // One division gives both the angle's ratio and n·c / |c|.
    const double ad = std::abs(d), hi = std::max(c_len, ad);
    const double inv = 1.0 / (c_len * hi);
    const double term = fold_angle(std::min(c_len, ad) * c_len * inv, c_len, d) *
                        (n.x * cx + n.y * cy + n.z * cz) * hi * inv;
    // Below this the edge passes through the point (and c_len × hi would underflow).
    return c_len > 1e-150 ? term : 0.0;
}

inline double contour_term(const Vec3& x, const Vec3& n, const Vec3& a, const Vec3& b) {
    return contour_term(a.x - x.x, a.y - x.y, a.z - x.z, b.x - x.x, b.y - x.y, b.z - x.z, n);
}

/// \brief Points that share a tangent plane's normal, as columns, each with its index in
///        the caller's list and a contour sum.
struct ContourPoints {
    std::vector<double> x, y, z, sum;
    std::vector<std::size_t> index;
    void clear() {
        x.clear();
        y.clear();
        z.clear();
        sum.clear();
        index.clear();
    }
    void push_back(const Vec3& p, std::size_t i) {
        x.push_back(p.x);
        y.push_back(p.y);
        z.push_back(p.z);
        sum.push_back(0.0);
        index.push_back(i);
    }
    std::size_t size() const { return x.size(); }
    bool empty() const { return x.empty(); }
    /// Writes each point's form factor, |sum| / 2π, to out[its index].
    void write_form_factors(double* out) const {
        for (std::size_t j = 0; j < size(); ++j)
            out[index[j]] = std::abs(sum[j]) / (2.0 * k_pi);
    }
};

/// \brief Adds edge (a, b)'s contour term at each of \p points (of tangent-plane normal
///        \p n) to its sum: a loop the compiler vectorizes over the points.
void add_contour_terms(const Vec3& a, const Vec3& b, const Vec3& n, ContourPoints& points);

inline double form_factor_point_triangle(const Vec3& x, const Vec3& n,
                                         const std::array<Vec3, 3>& tri) {
    return form_factor_point_polygon(x, n, tri.data(), 3);
}

/// \brief Form factors from points \p x[0, count) sharing the tangent-plane normal \p n to
///        triangle \p tri, into \p out: each as form_factor_point_triangle gives it, with the
///        points that see all of the triangle summed over its edges at once
///        (add_contour_terms).
void form_factors_point_triangle(const Vec3* x, std::size_t count, const Vec3& n,
                                 const std::array<Vec3, 3>& tri, double* out);

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
