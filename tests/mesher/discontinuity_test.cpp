// Discontinuity meshing (issue #5): shadow boundaries on element edges, hidden boundaries
// left out, orders and sources.

#include "mesher/mesher.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "mesher/mesh_checks.h"

namespace penumbra {
namespace {

using test::add_material;
using test::add_rect;

struct Poly2 {
    std::vector<std::array<double, 2>> v; // counter-clockwise
};

double cross2(const std::array<double, 2>& o, const std::array<double, 2>& a,
              const std::array<double, 2>& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

Poly2 convex_hull(std::vector<std::array<double, 2>> p) {
    std::sort(p.begin(), p.end());
    std::vector<std::array<double, 2>> h(2 * p.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross2(h[k - 2], h[k - 1], p[i]) <= 0)
            --k;
        h[k++] = p[i];
    }
    for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && cross2(h[k - 2], h[k - 1], p[i]) <= 0)
            --k;
        h[k++] = p[i];
    }
    h.resize(k - 1);
    return {h};
}

// Signed distance inside (> 0) a convex counter-clockwise polygon.
double inside_depth(const Poly2& poly, const std::array<double, 2>& x) {
    double depth = 1e300;
    for (std::size_t i = 0; i < poly.v.size(); ++i) {
        const auto& a = poly.v[i];
        const auto& b = poly.v[(i + 1) % poly.v.size()];
        const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
        depth = std::min(depth, cross2(a, b, x) / len);
    }
    return depth;
}

// A square light (side 0.6, centre (2.2, 2.05), height 2.5, facing down) above a box
// [1.5, 2.4] × [1.6, 2.3] × [0, 0.8] standing on a 4 × 4 floor.
struct BoxScene {
    Scene scene;
    std::uint32_t light_polygon = 0;
    std::array<Vec3, 4> light;
    std::array<Vec3, 4> top;
    std::array<std::array<double, 2>, 4> footprint;
};

BoxScene box_scene() {
    BoxScene b;
    Scene& s = b.scene;
    auto white = add_material(s, "white", Rgb(0.5f));
    auto lamp = add_material(s, "lamp", Rgb(0.0f), Rgb(5.0f), false);
    add_rect(s, "floor", white, {0, 0, 0}, {4, 0, 0}, {0, 4, 0});
    const double x0 = 1.5, x1 = 2.4, y0 = 1.6, y1 = 2.3, h = 0.8;
    add_rect(s, "box_top", white, {x0, y0, h}, {x1 - x0, 0, 0}, {0, y1 - y0, 0});
    add_rect(s, "box_s0", white, {x0, y0, 0}, {x1 - x0, 0, 0}, {0, 0, h});
    add_rect(s, "box_s1", white, {x1, y0, 0}, {0, y1 - y0, 0}, {0, 0, h});
    add_rect(s, "box_s2", white, {x1, y1, 0}, {x0 - x1, 0, 0}, {0, 0, h});
    add_rect(s, "box_s3", white, {x0, y1, 0}, {0, y0 - y1, 0}, {0, 0, h});
    b.light_polygon = std::uint32_t(s.polygons.size());
    add_rect(s, "light", lamp, {1.9, 1.75, 2.5}, {0, 0.6, 0}, {0.6, 0, 0}); // faces down
    for (int k = 0; k < 4; ++k)
        b.light[std::size_t(k)] = s.polygons[b.light_polygon].vertices[std::size_t(k)];
    b.top = {Vec3(x0, y0, h), Vec3(x1, y0, h), Vec3(x1, y1, h), Vec3(x0, y1, h)};
    b.footprint = {{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}};
    s.mesher.max_edge_length = 0.25;
    return b;
}

// The shadow of the box on the floor as seen from one light vertex.
Poly2 point_shadow(const BoxScene& b, const Vec3& v) {
    std::vector<std::array<double, 2>> pts(b.footprint.begin(), b.footprint.end());
    for (const Vec3& c : b.top) {
        const Vec3 p = v + (c - v) * (v.z / (v.z - c.z));
        pts.push_back({p.x, p.y});
    }
    return convex_hull(pts);
}

// Checks the runs of points of one edge of shadows[k] that lie on the penumbra's outer
// boundary (inside no other point shadow) or on the umbra's boundary (inside all), outside
// the footprint; returns the number of runs checked.
int check_shadow_edge(const RadiosityMesh& mesh, std::uint32_t floor,
                      const std::array<Poly2, 4>& shadows, const Poly2& footprint, std::size_t k,
                      std::size_t i, double tol) {
    const Poly2& s = shadows[k];
    const auto a = s.v[i], c = s.v[(i + 1) % s.v.size()];
    const int n = 400;
    auto point = [&](int j) {
        const double t = double(j) / n;
        return Vec3(a[0] + (c[0] - a[0]) * t, a[1] + (c[1] - a[1]) * t, 0);
    };
    int checked = 0, run_start = -1;
    auto close_run = [&](int end) {
        if (run_start >= 0 && end - run_start >= 2) {
            EXPECT_TRUE(test::segment_on_element_edges(mesh, floor, point(run_start),
                                                       point(end - 1), tol))
                << "light vertex " << k << ", shadow edge " << i << ", samples " << run_start
                << "-" << end - 1;
            ++checked;
        }
        run_start = -1;
    };
    for (int j = 0; j <= n; ++j) {
        const std::array<double, 2> x{point(j).x, point(j).y};
        bool outer = true, umbra = true;
        for (std::size_t m = 0; m < 4; ++m) {
            if (m == k)
                continue;
            const double d = inside_depth(shadows[m], x);
            outer = outer && d < -1e-4;
            umbra = umbra && d > 1e-4;
        }
        const bool wanted = (outer || umbra) && inside_depth(footprint, x) < -1e-4;
        if (wanted && run_start < 0)
            run_start = j;
        if (!wanted)
            close_run(j);
    }
    close_run(n + 1);
    return checked;
}

TEST(Discontinuity, UmbraAndPenumbraBoundariesLieOnElementEdges) {
    const BoxScene b = box_scene();
    const RadiosityMesh mesh = mesher::build_mesh(b.scene, test::quiet_context());
    const auto floor = std::uint32_t(test::find_patch(mesh, 0));
    std::array<Poly2, 4> shadows;
    for (std::size_t k = 0; k < 4; ++k)
        shadows[k] = point_shadow(b, b.light[k]);
    const Poly2 footprint{{b.footprint.begin(), b.footprint.end()}};
    int checked = 0;
    for (std::size_t k = 0; k < 4; ++k)
        for (std::size_t i = 0; i < shadows[k].v.size(); ++i)
            checked += check_shadow_edge(mesh, floor, shadows, footprint, k, i,
                                         1e-6 * mesh.scene_diagonal);
    EXPECT_GE(checked, 8);
    std::array<int, 3> orders{0, 0, 0};
    for (const DiscontinuitySegment& d : mesh.discontinuities) {
        EXPECT_EQ(d.source, std::int32_t(b.light_polygon));
        ++orders[std::size_t(d.order)];
        if (d.surface == 0) {
            EXPECT_NEAR(d.a.z, 0.0, 1e-9);
            EXPECT_NEAR(d.b.z, 0.0, 1e-9);
        }
    }
    EXPECT_GT(orders[0], 0); // the box's contact with the floor
    EXPECT_GT(orders[1], 0); // light and box edges are parallel
    EXPECT_GT(orders[2], 0); // the box's vertical edges
}

TEST(Discontinuity, MaxOrderLimitsTheSegments) {
    BoxScene b = box_scene();
    b.scene.mesher.discontinuity.max_order = 1;
    const RadiosityMesh mesh = mesher::build_mesh(b.scene, test::quiet_context());
    ASSERT_FALSE(mesh.discontinuities.empty());
    for (const DiscontinuitySegment& d : mesh.discontinuities)
        EXPECT_LE(d.order, 1);
    b.scene.mesher.discontinuity.enabled = false;
    EXPECT_TRUE(mesher::build_mesh(b.scene, test::quiet_context()).discontinuities.empty());
}

double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 d = b - a;
    const double t = std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0);
    return length(p - (a + d * t));
}

// Light [1.8, 2.2]² at height 3; plate A at height 1 casts the line x = 0.6 on the floor (its
// edge x = 1.0 seen from the light's edge x = 1.8); plate B at height 2 hides that line from
// the light for y > 2.25.
TEST(Discontinuity, BoundaryHiddenByAnotherBlockerIsLeftOut) {
    Scene scene;
    auto white = add_material(scene, "white", Rgb(0.5f));
    auto lamp = add_material(scene, "lamp", Rgb(0.0f), Rgb(5.0f), false);
    add_rect(scene, "floor", white, {-1, -1, 0}, {5, 0, 0}, {0, 6, 0});
    add_rect(scene, "plate_a", white, {1.0, 1.2, 1}, {0.6, 0, 0}, {0, 1.6, 0});
    add_rect(scene, "plate_b", white, {1.3, 1.95, 2}, {0.2, 0, 0}, {0, 0.55, 0});
    add_rect(scene, "light", lamp, {1.8, 1.8, 3}, {0, 0.4, 0}, {0.4, 0, 0});
    scene.mesher.max_edge_length = 0.25;
    const RadiosityMesh mesh = mesher::build_mesh(scene, test::quiet_context());
    const double tol = 1e-6 * mesh.scene_diagonal;
    auto on_boundary = [&](double y) {
        const Vec3 p(0.6, y, 0);
        return std::any_of(mesh.discontinuities.begin(), mesh.discontinuities.end(),
                           [&](const DiscontinuitySegment& d) {
                               return d.surface == 0 && distance_to_segment(p, d.a, d.b) < tol;
                           });
    };
    for (double y = 0.95; y <= 2.15; y += 0.05)
        EXPECT_TRUE(on_boundary(y)) << "visible part missing at y = " << y;
    for (double y = 2.363; y <= 3.25; y += 0.05) // off the crossings with other boundaries
        EXPECT_FALSE(on_boundary(y)) << "hidden part inserted at y = " << y;
    const auto floor = std::uint32_t(test::find_patch(mesh, 0));
    EXPECT_TRUE(test::segment_on_element_edges(mesh, floor, {0.6, 0.95, 0}, {0.6, 2.15, 0}, tol));
}

TEST(Discontinuity, PointLightCastsD0Boundaries) {
    BoxScene b = box_scene();
    b.scene.polygons.pop_back(); // no area light
    PointLight light;
    light.position = {2.2, 2.05, 2.5};
    light.intensity = Rgb(10.0f);
    b.scene.point_lights.push_back(light);
    const RadiosityMesh mesh = mesher::build_mesh(b.scene, test::quiet_context());
    ASSERT_FALSE(mesh.discontinuities.empty());
    for (const DiscontinuitySegment& d : mesh.discontinuities) {
        EXPECT_EQ(d.order, 0);
        EXPECT_EQ(d.source, -2);
    }
    const Poly2 shadow = point_shadow(b, light.position);
    const auto floor = std::uint32_t(test::find_patch(mesh, 0));
    const Poly2 footprint{{b.footprint.begin(), b.footprint.end()}};
    for (std::size_t i = 0; i < shadow.v.size(); ++i) {
        const auto a = shadow.v[i], c = shadow.v[(i + 1) % shadow.v.size()];
        const std::array<double, 2> mid{(a[0] + c[0]) / 2, (a[1] + c[1]) / 2};
        if (inside_depth(footprint, mid) > -1e-4)
            continue; // an edge of the footprint itself
        EXPECT_TRUE(test::segment_on_element_edges(mesh, floor, {a[0], a[1], 0}, {c[0], c[1], 0},
                                                   1e-6 * mesh.scene_diagonal));
    }
}

// A spot sends no light beyond its cut-off, so it casts no boundaries there: the same light
// made isotropic casts boundaries outside the cone (so the check can fail), the spot only
// inside it, and a spot aimed past everything casts none.
TEST(Discontinuity, SpotCastsBoundariesOnlyInsideItsCone) {
    BoxScene b = box_scene();
    b.scene.polygons.pop_back(); // no area light
    PointLight light;
    light.position = {2.2, 2.05, 2.5};
    light.intensity = Rgb(10.0f);
    const Vec3 axis = normalize(Vec3(1.6, 1.7, 0.4) - light.position);
    const double cutoff_deg = 12;
    // Largest angle from the axis over the segments' end and middle points, degrees.
    auto widest_deg = [&](const RadiosityMesh& mesh) {
        double widest = 0;
        for (const DiscontinuitySegment& d : mesh.discontinuities)
            for (const Vec3& x : {d.a, d.b, (d.a + d.b) * 0.5}) {
                const double c = dot(normalize(x - light.position), axis);
                widest = std::max(widest, std::acos(std::clamp(c, -1.0, 1.0)) * 180 / k_pi);
            }
        return widest;
    };
    Scene isotropic = b.scene;
    isotropic.point_lights.push_back(light);
    const RadiosityMesh all = mesher::build_mesh(isotropic, test::quiet_context());
    EXPECT_GT(widest_deg(all), cutoff_deg + 5);

    light.spot = SpotCone{axis, 8, cutoff_deg};
    b.scene.point_lights.push_back(light);
    const RadiosityMesh cone = mesher::build_mesh(b.scene, test::quiet_context());
    ASSERT_FALSE(cone.discontinuities.empty());
    EXPECT_LT(cone.discontinuities.size(), all.discontinuities.size());
    EXPECT_LE(widest_deg(cone), cutoff_deg + 0.01);
    std::printf("isotropic: %zu segments to %.2f deg from the axis; spot (cut-off %g deg): %zu "
                "segments to %.4f deg\n",
                all.discontinuities.size(), widest_deg(all), cutoff_deg,
                cone.discontinuities.size(), widest_deg(cone));

    b.scene.point_lights.back().spot = SpotCone{{1, 0, 0}, 10, 20}; // reaches no surface
    EXPECT_TRUE(mesher::build_mesh(b.scene, test::quiet_context()).discontinuities.empty());
}

TEST(Discontinuity, MeshQualityStaysWithinBounds) {
    const BoxScene b = box_scene();
    const RadiosityMesh mesh = mesher::build_mesh(b.scene, test::quiet_context());
    const auto floor = std::uint32_t(test::find_patch(mesh, 0));
    std::size_t small = 0, total = 0;
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
        if (mesh.element_patch[e] != floor)
            continue;
        ++total;
        const auto& t = mesh.triangles[e];
        for (int k = 0; k < 3; ++k) {
            const Vec3 p = mesh.vertex(t[k]);
            const Vec3 u = normalize(mesh.vertex(t[(k + 1) % 3]) - p);
            const Vec3 v = normalize(mesh.vertex(t[(k + 2) % 3]) - p);
            if (std::acos(std::clamp(dot(u, v), -1.0, 1.0)) * 180 / k_pi < 20.0) {
                ++small;
                break;
            }
        }
    }
    // Angles below 20° only where constraint lines meet at smaller angles (the fans of
    // boundaries leaving the box's corners).
    EXPECT_LT(double(small), 0.05 * double(total)) << small << " of " << total;
    EXPECT_LE(test::longest_edge(mesh), 0.25 * std::sqrt(2.0) + 1e-9);
}

TEST(Discontinuity, MeshDoesNotDependOnTheThreadCount) {
    const BoxScene b = box_scene();
    const RadiosityMesh one = mesher::build_mesh(b.scene, test::quiet_context(1));
    const RadiosityMesh four = mesher::build_mesh(b.scene, test::quiet_context(4));
    EXPECT_EQ(one.positions, four.positions);
    EXPECT_EQ(one.triangles, four.triangles);
    EXPECT_EQ(one.element_patch, four.element_patch);
    ASSERT_EQ(one.discontinuities.size(), four.discontinuities.size());
    for (std::size_t i = 0; i < one.discontinuities.size(); ++i) {
        EXPECT_EQ(one.discontinuities[i].a, four.discontinuities[i].a);
        EXPECT_EQ(one.discontinuities[i].order, four.discontinuities[i].order);
    }
}

} // namespace
} // namespace penumbra
