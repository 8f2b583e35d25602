// Analytic kernels against closed forms (shared/validation/README.md §1).

#include "form_factor.h"

#include <cmath>

#include <gtest/gtest.h>

namespace penumbra::solver {
namespace {

// Howell C-? : differential area at the corner below a parallel a × b rectangle at height c.
double corner_rectangle(double a, double b, double c) {
    double A = a / c, B = b / c;
    return (1 / (2 * k_pi)) * (A / std::sqrt(1 + A * A) * std::atan(B / std::sqrt(1 + A * A)) +
                               B / std::sqrt(1 + B * B) * std::atan(A / std::sqrt(1 + B * B)));
}

TEST(FormFactor, PointBelowRectangleCorner) {
    const double a = 1.3, b = 0.7, c = 0.9;
    Vec3 rect[4] = {{0, 0, c}, {a, 0, c}, {a, b, c}, {0, b, c}};
    double f = form_factor_point_polygon({0, 0, 0}, {0, 0, 1}, rect, 4);
    EXPECT_NEAR(f, corner_rectangle(a, b, c), 1e-12);
}

TEST(FormFactor, PointBelowCoaxialDisc) {
    const double R = 0.8, h = 1.5;
    constexpr int n = 2048; // a fine regular polygon approximates the disc
    std::vector<Vec3> disc;
    for (int i = 0; i < n; ++i)
        disc.emplace_back(R * std::cos(2 * k_pi * i / n), R * std::sin(2 * k_pi * i / n), h);
    // The polygon's inscribed area is smaller than the disc's by a factor sin(2π/n)/(2π/n).
    double f = 0;
    // Sum over a fan of triangles so that the 16-vertex limit of the kernel is not hit.
    for (int i = 0; i < n; ++i) {
        std::array<Vec3, 3> tri{Vec3(0, 0, h), disc[std::size_t(i)], disc[std::size_t((i + 1) % n)]};
        f += form_factor_point_triangle({0, 0, 0}, {0, 0, 1}, tri);
    }
    double r_eff2 = R * R * std::sin(2 * k_pi / n) / (2 * k_pi / n);
    EXPECT_NEAR(f, r_eff2 / (r_eff2 + h * h), 1e-6);
}

TEST(FormFactor, ClipsPartBelowTangentPlane) {
    // A vertical unit square crossing the receiver's tangent plane: only the upper half counts.
    Vec3 full[4] = {{-0.5, 1, -0.5}, {0.5, 1, -0.5}, {0.5, 1, 0.5}, {-0.5, 1, 0.5}};
    Vec3 upper[4] = {{-0.5, 1, 0}, {0.5, 1, 0}, {0.5, 1, 0.5}, {-0.5, 1, 0.5}};
    Vec3 n(0, 0, 1);
    EXPECT_NEAR(form_factor_point_polygon({0, 0, 0}, n, full, 4),
                form_factor_point_polygon({0, 0, 0}, n, upper, 4), 1e-14);
    EXPECT_GT(form_factor_point_polygon({0, 0, 0}, n, upper, 4), 0.0);
}

TEST(FormFactor, ClosedCubeSumsToOne) {
    // From the centre of the floor of a unit cube the five other faces fill the hemisphere.
    Vec3 x(0.5, 0.5, 0), n(0, 0, 1);
    Vec3 faces[5][4] = {
        {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}, {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}},
        {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}}, {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}},
        {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}};
    double sum = 0;
    for (auto& f : faces)
        sum += form_factor_point_polygon(x, n, f, 4);
    EXPECT_NEAR(sum, 1.0, 1e-12);
    // A point on the edge between floor and wall sees the wall edge-on.
    Vec3 on_edge(0.5, 0, 0);
    EXPECT_NEAR(form_factor_point_polygon(on_edge, n, faces[1], 4), 0.0, 1e-12);
}

TEST(SolidAngle, OctantTriangle) {
    EXPECT_NEAR(solid_angle_triangle({0, 0, 0}, {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}),
                k_pi / 2, 1e-12);
}

TEST(SolidAngle, CubeFacesSumToFourPi) {
    Vec3 c(0.3, 0.6, 0.45); // off-centre inside the unit cube
    double sum = 0;
    Vec3 corners[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                       {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    int quads[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                       {3, 2, 6, 7}, {0, 3, 7, 4}, {1, 2, 6, 5}};
    for (auto& q : quads) {
        sum += solid_angle_triangle(c, {corners[q[0]], corners[q[1]], corners[q[2]]});
        sum += solid_angle_triangle(c, {corners[q[0]], corners[q[2]], corners[q[3]]});
    }
    EXPECT_NEAR(sum, 4 * k_pi, 1e-12);
}

TEST(Quadrature, EqualWeightRuleIntegratesLinearFunctionsExactly) {
    for (int level = 0; level <= 3; ++level) {
        std::array<std::array<double, 2>, k_max_quadrature_points> pts{};
        std::size_t count = 0;
        quadrature_barycentrics(level, pts.data(), &count);
        EXPECT_EQ(count, std::size_t(1) << (2 * level));
        double mean1 = 0, mean2 = 0;
        for (std::size_t k = 0; k < count; ++k) {
            mean1 += pts[k][0] / double(count);
            mean2 += pts[k][1] / double(count);
            EXPECT_LE(pts[k][0] + pts[k][1], 1.0);
        }
        EXPECT_NEAR(mean1, 1.0 / 3.0, 1e-14);
        EXPECT_NEAR(mean2, 1.0 / 3.0, 1e-14);
    }
}

} // namespace
} // namespace penumbra::solver
