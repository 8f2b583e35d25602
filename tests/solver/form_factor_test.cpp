// Analytic kernels against closed forms (docs/validation.md §1).

#include "kernels/form_factor.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "core/rng.h"
#include "core/visibility.h"
#include "kernels/element_rows.h"

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
    // Each edge's angle is within 6e-11 rad (fold_angle): F within 4 × 6e-11 / 2π.
    EXPECT_NEAR(f, corner_rectangle(a, b, c), 4e-11);
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
        std::array<Vec3, 3> tri{Vec3(0, 0, h), disc[std::size_t(i)],
                                disc[std::size_t((i + 1) % n)]};
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
    Vec3 faces[5][4] = {{{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},
                        {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}},
                        {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}},
                        {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}},
                        {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}};
    double sum = 0;
    for (auto& f : faces)
        sum += form_factor_point_polygon(x, n, f, 4);
    EXPECT_NEAR(sum, 1.0, 1e-12);
    // A point on the edge between floor and wall sees the wall edge-on.
    Vec3 on_edge(0.5, 0, 0);
    EXPECT_NEAR(form_factor_point_polygon(on_edge, n, faces[1], 4), 0.0, 1e-12);
}

// The contour sums' fast angle against libm's atan2 over every octant's ratios, scales from
// 1e-12 to 1e12, and the axes: within its stated 6e-11 rad, and 6.1e-11 relatively below
// π/4, where a distant source's small angles lie.
TEST(FormFactor, FoldedAngleMatchesAtan2) {
    Pcg32 rng(7, 11);
    double worst = 0, worst_relative = 0;
    auto check = [&](double y, double x) {
        const double ax = std::abs(x), hi = std::max(y, ax);
        if (!(hi > 0))
            return; // no angle: contour_term drops such an edge
        const double angle = fold_angle(std::min(y, ax) / hi, y, x);
        const double exact = std::atan2(y, x), error = std::abs(angle - exact);
        worst = std::max(worst, error);
        if (exact > 0 && exact < k_pi / 4)
            worst_relative = std::max(worst_relative, error / exact);
    };
    for (int k = 0; k < 1000000; ++k) {
        const double scale = std::pow(10.0, 24.0 * rng.next_double() - 12.0);
        const double angle = k_pi * rng.next_double();
        check(scale * std::sin(angle), scale * std::cos(angle));
    }
    for (double y : {0.0, 1.0, 1e-300})
        for (double x : {-1.0, 0.0, 1.0, 1e-300, -1e-300})
            check(y, x);
    for (int k = 0; k < 100000; ++k) { // small angles, down to 1e-12 rad
        const double angle = std::pow(10.0, -12.0 * rng.next_double());
        check(std::sin(angle), std::cos(angle));
    }
    EXPECT_LT(worst, 6e-11);
    EXPECT_LT(worst_relative, 6.1e-11);
}

// The columns' contour sums (the vectorized loop over points) against the polygon kernel at
// each point on its own, where every point sees all of a pentagon; and an edge through a
// point adds nothing but rounding (no NaN from its zero cross product).
TEST(FormFactor, ContourTermsOverPointsMatchThePolygonKernel) {
    const Vec3 pentagon[5] = {
        {0, 0, 2}, {1, 0, 2.2}, {1.4, 0.9, 2.3}, {0.5, 1.5, 2.1}, {-0.3, 0.8, 2}};
    const Vec3 n = normalize(Vec3(0.1, -0.2, 1));
    Pcg32 rng(3, 5);
    ContourPoints points;
    std::vector<Vec3> xs;
    for (int k = 0; k < 37; ++k) { // an odd count: the vector loop's remainder too
        xs.emplace_back(4 * rng.next_double() - 2, 4 * rng.next_double() - 2, rng.next_double());
        points.push_back(xs.back(), xs.size() - 1);
    }
    for (int i = 0; i < 5; ++i)
        add_contour_terms(pentagon[i], pentagon[(i + 1) % 5], n, points);
    for (std::size_t k = 0; k < xs.size(); ++k)
        EXPECT_NEAR(std::abs(points.sum[k]) / (2 * k_pi),
                    form_factor_point_polygon(xs[k], n, pentagon, 5), 1e-13);
    ContourPoints on_edge;
    on_edge.push_back(Vec3(0.5, 0, 2.1), 0); // on the pentagon's first edge
    on_edge.push_back(Vec3(-1, 0, 1.8), 1);  // on its line, outside the edge
    add_contour_terms(pentagon[0], pentagon[1], n, on_edge);
    EXPECT_NEAR(on_edge.sum[0], 0.0, 1e-12); // fails for a NaN too
    EXPECT_NEAR(on_edge.sum[1], 0.0, 1e-12);
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

// An axis-aligned box that blocks segments (slab test): an analytic visibility oracle.
class BoxOccluder final : public VisibilityQuery {
public:
    BoxOccluder(Vec3 lo, Vec3 hi) : lo_(lo), hi_(hi) {}
    bool blocks(const Vec3& o, const Vec3& d, double t0, double t1) const {
        for (std::size_t a = 0; a < 3; ++a) {
            if (std::abs(d[a]) < 1e-300) {
                if (o[a] < lo_[a] || o[a] > hi_[a])
                    return false;
                continue;
            }
            double ta = (lo_[a] - o[a]) / d[a], tb = (hi_[a] - o[a]) / d[a];
            if (ta > tb)
                std::swap(ta, tb);
            t0 = std::max(t0, ta);
            t1 = std::min(t1, tb);
        }
        return t0 <= t1;
    }
    void occluded(std::span<const Segment> segments, std::span<std::uint8_t> out) const override {
        for (std::size_t i = 0; i < segments.size(); ++i)
            out[i] = blocks(Vec3(segments[i].origin), Vec3(segments[i].direction),
                            segments[i].tnear, segments[i].tfar);
    }
    std::uint64_t rays_traced() const override { return 0; }

private:
    Vec3 lo_, hi_;
};

// The visible fraction of a pair's transfer, ∫_a ∫_b K V / ∫_a ∫_b K with K = cos cos / r²,
// from uniform points on both (a brute-force reference: the two sums share their points, so
// the kernel's peak by a common edge does not make their ratio noisy).
double brute_force_fraction(const OrientedTriangle& a, const OrientedTriangle& b,
                            const BoxOccluder& box, int samples) {
    Pcg32 rng = Pcg32::for_stream(RngPurpose::form_factor_visibility, 7, 7, 7, 7);
    double open = 0, all = 0;
    for (int k = 0; k < samples; ++k) {
        const Vec3 x = sample_triangle(a.v, rng.next_double(), rng.next_double());
        const Vec3 y = sample_triangle(b.v, rng.next_double(), rng.next_double());
        const Vec3 d = y - x;
        const double r2 = dot(d, d);
        const double k_xy = std::max(0.0, dot(a.n, d)) * std::max(0.0, -dot(b.n, d)) / (r2 * r2);
        all += k_xy;
        if (k_xy > 0 && !box.blocks(x, d, 0.0, 1.0))
            open += k_xy;
    }
    return open / all;
}

// A small wall triangle beside a large floor triangle, a ridge across the floor 1 m out: most
// of the pair's transfer is near their common edge, in front of the ridge, and the visible
// fraction must weigh the rays by it. Rays from the wall's quadrature points to area-drawn
// points of the floor found the ridge in the way of more than half of them (a mean visible
// fraction of 0.44 with the default rays; 0.81 with those rays weighed by the kernel, whose
// peak by the edge few of them drew). From the small end, as hierarchical links of such a
// pair are made (the other follows by reciprocity): the large end's quadrature points do not
// resolve where the transfer is.
TEST(PairFormFactor, VisibleFractionWeighsTheTransferNearACommonEdge) {
    const OrientedTriangle wall{{Vec3(0, -0.2, 0), Vec3(0, 0.2, 0), Vec3(0, 0, 0.3)},
                                Vec3(1, 0, 0)};
    const OrientedTriangle floor{{Vec3(0, -3, 0), Vec3(0, 3, 0), Vec3(4, 0, 0)}, Vec3(0, 0, 1)};
    const BoxOccluder ridge(Vec3(1.0, -4, -0.1), Vec3(1.2, 4, 0.6));
    const double reference = brute_force_fraction(wall, floor, ridge, 4000000);
    EXPECT_NEAR(reference, 0.943, 0.003); // the reference's own check
    RowSettings settings;
    settings.visibility_rays = 4096;
    const PairFormFactor many = triangle_form_factor(wall, floor, 3, ridge, 1e-6, 1, 2, settings);
    // 16 rays a pair (the default), over 500 seeds: the mean is what a scene's many such
    // pairs add up to. Both within 2 % (16 probes all open count as fully visible: a little
    // high).
    settings.visibility_rays = RowSettings{}.visibility_rays;
    double mean = 0;
    for (std::uint64_t seed = 0; seed < 500; ++seed) {
        settings.seed = seed;
        const PairFormFactor pf = triangle_form_factor(wall, floor, 3, ridge, 1e-6, 1, 2, settings);
        mean += pf.f / pf.f_unoccluded / 500.0;
    }
    EXPECT_NEAR(many.f / many.f_unoccluded, reference, 0.02);
    EXPECT_NEAR(mean, reference, 0.02);
}

} // namespace
} // namespace penumbra::solver
