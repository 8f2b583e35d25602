// Discontinuity meshing (issue #5): shadow boundaries on element edges, hidden boundaries
// left out, orders and sources.

#include "mesher/mesher.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

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
            EXPECT_TRUE(
                test::segment_on_element_edges(mesh, floor, point(run_start), point(end - 1), tol))
                << "light vertex " << k << ", shadow edge " << i << ", samples " << run_start << "-"
                << end - 1;
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
        EXPECT_EQ(d.source, LightSource(AreaSource{b.light_polygon}));
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
        EXPECT_EQ(d.source, LightSource(PointSource{0}));
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

// ---- The sun: a disc of 0.533° at infinity ----

Sun make_sun(double altitude_deg, double azimuth_deg) {
    const double alt = altitude_deg * k_pi / 180, az = azimuth_deg * k_pi / 180;
    return Sun{{std::cos(alt) * std::cos(az), std::cos(alt) * std::sin(az), std::sin(alt)},
               Rgb(500.0f),
               0.533};
}

// The direction of the sun's rim at angle phi around its centre.
Vec3 rim_direction(const Sun& sun, double phi) {
    const Frame f = Frame::from_normal(sun.direction);
    const double r = sun.angular_diameter_deg * k_pi / 360;
    return f.to_world({std::sin(r) * std::cos(phi), std::sin(r) * std::sin(phi), std::cos(r)});
}

// The rim directions whose planes through the line pq turn farthest either way around it:
// the planes of the edge's umbra and penumbra boundaries, found numerically (the plane's angle
// around pq sampled over the rim, then a ternary search), not from the mesher's formula.
std::array<Vec3, 2> extreme_rim_directions(const Sun& sun, const Vec3& p, const Vec3& q) {
    const Vec3 e = normalize(q - p);
    const Vec3 b1 = normalize(sun.direction - e * dot(sun.direction, e)), b2 = cross(e, b1);
    std::array<Vec3, 2> out;
    for (int k = 0; k < 2; ++k) {
        const double sign = k == 0 ? 1 : -1;
        auto turn = [&](double phi) {
            const Vec3 d = rim_direction(sun, phi);
            return sign * std::atan2(dot(d, b2), dot(d, b1));
        };
        const int n = 3600;
        int best = 0;
        for (int i = 1; i < n; ++i)
            if (turn(2 * k_pi * i / n) > turn(2 * k_pi * best / n))
                best = i;
        double lo = 2 * k_pi * (best - 1) / n, hi = 2 * k_pi * (best + 1) / n;
        for (int it = 0; it < 200; ++it) {
            const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
            (turn(m1) < turn(m2) ? lo : hi) = turn(m1) < turn(m2) ? m1 : m2;
        }
        out[std::size_t(k)] = rim_direction(sun, 0.5 * (lo + hi));
    }
    return out;
}

// The shadow of p on the floor z = 0 along the direction d toward the sun.
Vec3 floor_shadow(const Vec3& p, const Vec3& d) {
    return p - d * (p.z / d.z);
}

Poly2 direction_shadow(const BoxScene& b, const Vec3& d) {
    std::vector<std::array<double, 2>> pts(b.footprint.begin(), b.footprint.end());
    for (const Vec3& c : b.top) {
        const Vec3 p = floor_shadow(c, d);
        pts.push_back({p.x, p.y});
    }
    return convex_hull(pts);
}

// A box on a floor under an oblique sun: every analytic umbra and penumbra boundary — the
// shadows of the box's silhouette edges along the two rim directions whose planes through the
// edge are extreme — lies on element edges (vertices within 1e-6 × the scene diagonal), where
// it is a boundary: on the penumbra's outer edge (inside no other direction's shadow) or the
// umbra's (inside all), off the footprint. Shadows are taken for 720 rim directions and the
// extreme ones.
struct SunCase {
    double altitude_deg, azimuth_deg;
};

class SunOverBox : public ::testing::TestWithParam<SunCase> {};

TEST_P(SunOverBox, UmbraAndPenumbraBoundariesLieOnElementEdges) {
    BoxScene b = box_scene();
    b.scene.polygons.pop_back(); // no area light
    const Sun sun = make_sun(GetParam().altitude_deg, GetParam().azimuth_deg);
    b.scene.sun = sun;
    const RadiosityMesh mesh = mesher::build_mesh(b.scene, test::quiet_context());
    const auto floor = std::uint32_t(test::find_patch(mesh, 0));
    const double x0 = 1.5, x1 = 2.4, y0 = 1.6, y1 = 2.3, h = 0.8;
    // The box's edges with the normals of their two faces; silhouettes part a lit face from
    // an unlit one.
    struct Edge {
        Vec3 p, q, n1, n2;
    };
    const Vec3 up(0, 0, 1), mx(-1, 0, 0), px(1, 0, 0), my(0, -1, 0), py(0, 1, 0);
    const Edge edges[] = {{{x0, y0, h}, {x1, y0, h}, up, my}, {{x1, y0, h}, {x1, y1, h}, up, px},
                          {{x0, y1, h}, {x1, y1, h}, up, py}, {{x0, y0, h}, {x0, y1, h}, up, mx},
                          {{x1, y0, 0}, {x1, y0, h}, my, px}, {{x1, y1, 0}, {x1, y1, h}, px, py},
                          {{x0, y1, 0}, {x0, y1, h}, py, mx}, {{x0, y0, 0}, {x0, y0, h}, mx, my}};
    std::vector<std::array<Vec3, 2>> silhouette;
    for (const Edge& e : edges)
        if ((dot(e.n1, sun.direction) > 0) != (dot(e.n2, sun.direction) > 0))
            silhouette.push_back({e.p, e.q});
    ASSERT_EQ(silhouette.size(), 4u);
    std::vector<Vec3> dirs;
    for (int i = 0; i < 720; ++i)
        dirs.push_back(rim_direction(sun, 2 * k_pi * i / 720));
    struct Line {
        Vec3 a, b;
        std::size_t dir;
    };
    std::vector<Line> lines;
    for (const auto& [p, q] : silhouette)
        for (const Vec3& d : extreme_rim_directions(sun, p, q)) {
            dirs.push_back(d);
            lines.push_back({floor_shadow(p, d), floor_shadow(q, d), dirs.size() - 1});
        }
    std::vector<Poly2> shadows;
    for (const Vec3& d : dirs)
        shadows.push_back(direction_shadow(b, d));
    const Poly2 footprint{{b.footprint.begin(), b.footprint.end()}};
    const double tol = 1e-6 * mesh.scene_diagonal;
    int checked = 0;
    for (std::size_t li = 0; li < lines.size(); ++li) {
        const Line& line = lines[li];
        const int n = 400;
        auto point = [&](int j) { return line.a + (line.b - line.a) * (double(j) / n); };
        int run_start = -1;
        auto close_run = [&](int end) {
            if (run_start >= 0 && end - run_start >= 2) {
                EXPECT_TRUE(test::segment_on_element_edges(mesh, floor, point(run_start),
                                                           point(end - 1), tol))
                    << "line " << li << ", samples " << run_start << "-" << end - 1;
                ++checked;
            }
            run_start = -1;
        };
        for (int j = 0; j <= n; ++j) {
            const std::array<double, 2> x{point(j).x, point(j).y};
            bool outer = true, umbra = true;
            for (std::size_t m = 0; m < shadows.size(); ++m) {
                if (m == line.dir)
                    continue;
                const double depth = inside_depth(shadows[m], x);
                outer = outer && depth < 1e-9;
                umbra = umbra && depth > -1e-9;
            }
            const bool wanted = (outer || umbra) && inside_depth(footprint, x) < -1e-4;
            if (wanted && run_start < 0)
                run_start = j;
            if (!wanted)
                close_run(j);
        }
        close_run(n + 1);
    }
    EXPECT_GE(checked, 8); // an umbra and a penumbra boundary per silhouette edge
    std::array<int, 3> orders{0, 0, 0};
    for (const DiscontinuitySegment& d : mesh.discontinuities) {
        EXPECT_EQ(d.source, LightSource(SunSource{}));
        ++orders[std::size_t(d.order)];
    }
    std::printf("sun at %g deg altitude, %g deg azimuth over a box: %zu segments (D0 %d, D1 %d, "
                "D2 %d), %d boundary runs checked\n",
                GetParam().altitude_deg, GetParam().azimuth_deg, mesh.discontinuities.size(),
                orders[0], orders[1], orders[2], checked);
    EXPECT_GT(orders[0], 0); // the box's contact with the floor
    EXPECT_EQ(orders[1], 0); // a disc has no straight edges
    EXPECT_GT(orders[2], 0);

    b.scene.mesher.discontinuity.max_order = 1; // the sun's boundaries are D2
    const RadiosityMesh d0 = mesher::build_mesh(b.scene, test::quiet_context());
    ASSERT_FALSE(d0.discontinuities.empty());
    for (const DiscontinuitySegment& d : d0.discontinuities)
        EXPECT_EQ(d.order, 0);
}

INSTANTIATE_TEST_SUITE_P(Suns, SunOverBox,
                         ::testing::Values(SunCase{40, 210}, SunCase{25, 300}, SunCase{60, 100},
                                           SunCase{30, 20}, SunCase{75, 250}, SunCase{50, 135}),
                         [](const ::testing::TestParamInfo<SunCase>& info) {
                             return "altitude" + std::to_string(int(info.param.altitude_deg)) +
                                    "_azimuth" + std::to_string(int(info.param.azimuth_deg));
                         });

// Plate A (height 1) casts its edge x = 1.6 on the floor at x ≈ 2.18 ± 6 mm (the umbra and
// penumbra boundaries) under a sun at 60° altitude from −x; plate B (height 2) takes the sun
// from that edge, and so from both boundaries, for y > 2.25.
TEST(Discontinuity, SunBoundaryHiddenByAnotherBlockerIsLeftOut) {
    Scene scene;
    auto white = add_material(scene, "white", Rgb(0.5f));
    add_rect(scene, "floor", white, {-1, -1, 0}, {5, 0, 0}, {0, 6, 0});
    add_rect(scene, "plate_a", white, {1.0, 1.2, 1}, {0.6, 0, 0}, {0, 1.6, 0});
    add_rect(scene, "plate_b", white, {0.9, 2.25, 2}, {0.25, 0, 0}, {0, 0.95, 0});
    const Sun sun = make_sun(60, 180);
    scene.sun = sun;
    scene.mesher.max_edge_length = 0.25;
    const RadiosityMesh mesh = mesher::build_mesh(scene, test::quiet_context());
    const double tol = 1e-6 * mesh.scene_diagonal;
    const auto floor = std::uint32_t(test::find_patch(mesh, 0));
    const Vec3 p(1.6, 0, 1), q(1.6, 1, 1); // the edge's line
    for (const Vec3& d : extreme_rim_directions(sun, p, q)) {
        const double x = floor_shadow(p, d).x;
        auto on_boundary = [&](double y) {
            const Vec3 at(x, y, 0);
            return std::any_of(mesh.discontinuities.begin(), mesh.discontinuities.end(),
                               [&](const DiscontinuitySegment& s) {
                                   return s.surface == 0 && distance_to_segment(at, s.a, s.b) < tol;
                               });
        };
        for (double y = 1.3; y <= 2.15; y += 0.05)
            EXPECT_TRUE(on_boundary(y)) << "visible part missing at x = " << x << ", y = " << y;
        for (double y = 2.35; y <= 2.7; y += 0.05)
            EXPECT_FALSE(on_boundary(y)) << "hidden part inserted at x = " << x << ", y = " << y;
        EXPECT_TRUE(test::segment_on_element_edges(mesh, floor, {x, 1.3, 0}, {x, 2.15, 0}, tol));
    }
}

// The sun below a receiver's horizon casts nothing on it: a one-sided wall facing away from
// the sun gets no boundaries from the box's shadow, the same wall two-sided does (on its side
// facing the sun).
TEST(Discontinuity, SunCastsNothingOnAReceiverFacingAway) {
    for (bool two_sided : {false, true}) {
        BoxScene b = box_scene();
        b.scene.polygons.pop_back(); // no area light
        b.scene.sun = make_sun(40, 210);
        auto wall_material = add_material(b.scene, "wall", Rgb(0.5f), {}, two_sided);
        const auto wall = std::uint32_t(b.scene.polygons.size());
        add_rect(b.scene, "wall", wall_material, {3.0, 1.5, 0}, {0, 2, 0}, {0, 0, 1.5}); // faces +x
        const RadiosityMesh mesh = mesher::build_mesh(b.scene, test::quiet_context());
        const auto on_wall = std::count_if(mesh.discontinuities.begin(), mesh.discontinuities.end(),
                                           [&](const DiscontinuitySegment& d) {
                                               return mesh.surfaces[d.surface].polygon == wall;
                                           });
        if (two_sided)
            EXPECT_GT(on_wall, 0);
        else
            EXPECT_EQ(on_wall, 0);
    }
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
    for (const bool sun : {false, true}) {
        BoxScene b = box_scene();
        if (sun)
            b.scene.sun = make_sun(40, 210); // with the area light
        const RadiosityMesh one = mesher::build_mesh(b.scene, test::quiet_context(1));
        const RadiosityMesh four = mesher::build_mesh(b.scene, test::quiet_context(4));
        EXPECT_EQ(one.positions, four.positions) << "sun " << sun;
        EXPECT_EQ(one.triangles, four.triangles);
        EXPECT_EQ(one.element_patch, four.element_patch);
        ASSERT_EQ(one.discontinuities.size(), four.discontinuities.size());
        for (std::size_t i = 0; i < one.discontinuities.size(); ++i) {
            EXPECT_EQ(one.discontinuities[i].a, four.discontinuities[i].a);
            EXPECT_EQ(one.discontinuities[i].order, four.discontinuities[i].order);
            EXPECT_EQ(one.discontinuities[i].source, four.discontinuities[i].source);
        }
    }
}

} // namespace
} // namespace penumbra
