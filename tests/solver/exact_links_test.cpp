// Issue #4: exact links between face clusters (solver/src/links/exact_links.cpp): their form
// factor against the analytic rectangle values (docs/validation.md §1), the plane
// their receiver takes against the point form factors, the radiosity their source sends
// against a gather from its roots, and the sloped push that spreads their light.

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "hierarchy/cluster_tree.h"
#include "hierarchy/hierarchy.h"
#include "iteration/cluster_transport.h"
#include "kernels/form_factor.h"
#include "links/link_set.h"
#include "mesher/mesher.h"
#include "office_scene.h"
#include "raytrace/raytrace.h"

namespace penumbra {
namespace {

using solver::ClusterLink;
using solver::NodeRef;

/// Adds the parallelogram origin + [0, 1] u + [0, 1] v split into k × k quads (2k²
/// triangles as meshed as-is: one face cluster of the cluster tree).
void add_tiled_rect(Scene& scene, std::uint32_t material, const Vec3& origin, const Vec3& u,
                    const Vec3& v, int k) {
    for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j)
            test::add_rect(scene, "tile", material,
                           origin + u * (double(i) / k) + v * (double(j) / k), u / double(k),
                           v / double(k));
}

/// Two tiled rectangles meshed as they are, their hierarchy, cluster tree and links.
struct Pair {
    Scene scene;
    RadiosityMesh mesh;
    std::unique_ptr<solver::Hierarchy> h;
    solver::ClusterTree tree;
    solver::ClusterValues cv;
    std::unique_ptr<raytrace::EmbreeScene> embree;
    solver::LinkStore store;
    std::unique_ptr<solver::ClusterTables> tables;
    std::unique_ptr<solver::LinkSet> links;
    NodeRef a = 0, b = 0; ///< the face clusters of the first and the second rectangle

    Pair(const Vec3& oa, const Vec3& ua, const Vec3& va, const Vec3& ob, const Vec3& ub,
         const Vec3& vb, double min_area = 1e-3) {
        const auto grey = test::add_material(scene, "grey", Rgb(0.5f), Rgb{}, false);
        add_tiled_rect(scene, grey, oa, ua, va, 4);
        add_tiled_rect(scene, grey, ob, ub, vb, 4);
        bench::mesh_input_as_is(scene);
        mesh = mesher::build_mesh(scene, test::quiet_context());
        h = std::make_unique<solver::Hierarchy>(mesh);
        tree = solver::build_cluster_tree(*h);
        solver::init_cluster_values(tree, *h, h->emission, cv);
        embree = std::make_unique<raytrace::EmbreeScene>(mesh);
        solver::RefineSettings settings;
        settings.rows.visibility_rays = 16;
        settings.offset = 1e-5 * mesh.scene_diagonal;
        settings.min_area = min_area;
        tables = std::make_unique<solver::ClusterTables>(*h, tree, cv.exitance, cv.exitance_emitted,
                                                         cv.peak, cv.departure);
        links = std::make_unique<solver::LinkSet>(*h, store, tables.get(), *embree,
                                                  scene.point_lights, nullptr, nullptr, settings);
        a = face_cluster(cross(ua, va));
        b = face_cluster(cross(ub, vb));
    }

    /// The largest face cluster facing along \p n.
    NodeRef face_cluster(const Vec3& n) const {
        std::uint32_t best = 0;
        double area = 0;
        for (std::uint32_t c = 0; c < tree.size(); ++c)
            if (tree.planar[c] && dot(tree.normal[c], normalize(n)) > 0.999 &&
                tree.area[c] > area) {
                best = c;
                area = tree.area[c];
            }
        EXPECT_GT(area, 0.0);
        return solver::cluster_ref(best);
    }

    /// The roots below face cluster \p n.
    std::vector<std::uint32_t> roots(NodeRef n) const {
        std::vector<std::uint32_t> out;
        std::vector<std::uint32_t> stack{solver::cluster_index(n)};
        while (!stack.empty()) {
            const std::uint32_t c = stack.back();
            stack.pop_back();
            for (std::uint32_t k = tree.child_begin[c]; k < tree.child_begin[c + 1]; ++k) {
                const NodeRef child = tree.children[k];
                if (solver::is_cluster(child))
                    stack.push_back(solver::cluster_index(child));
                else
                    out.push_back(child);
            }
        }
        return out;
    }

    /// What face cluster \p q gathers from face cluster \p p of radiosities \p b: over q's
    /// roots (by area), Σ F_r B_r / Σ F_r over p's roots.
    double gathered(NodeRef q, NodeRef p, const std::vector<Rgb>& b) const {
        double num = 0, den = 0;
        for (std::uint32_t x : roots(q))
            for (std::uint32_t r : roots(p)) {
                const double f = solver::form_factor_point_triangle(h->centroid(x), h->normal[x],
                                                                    h->triangle[r]) *
                                 h->area[x];
                num += f * b[r].g;
                den += f;
            }
        return num / den;
    }

    /// Point form factor from \p x (normal \p n) to the roots of face cluster \p p.
    double point_ff(const Vec3& x, const Vec3& n, NodeRef p) const {
        double f = 0;
        for (std::uint32_t r : roots(p))
            f += solver::form_factor_point_triangle(x, n, h->triangle[r]);
        return f;
    }
};

// F of an exact link between two face clusters (the mean over its receiver's points of the
// contour integral over the source's outline) against the closed forms: within 0.5 %
// (measured 0.16 to 0.28 %, from 4 points per root). The plane the receiver takes is flat
// where the pair is symmetric.
TEST(ExactLinks, FormFactorMatchesAnalyticRectangles) {
    struct Case {
        double width, gap, expected;
    };
    for (const Case& c : {Case{1, 1, 0.199825}, Case{1, 0.5, 0.415253}, Case{2, 1, 0.285875}}) {
        // Floor facing up, ceiling above it facing down.
        Pair pair({0, 0, 0}, {c.width, 0, 0}, {0, 1, 0}, {0, 0, c.gap}, {0, 1, 0}, {c.width, 0, 0});
        const ClusterLink link = pair.links->exact_link(pair.a, pair.b);
        ASSERT_TRUE(link.exact);
        ASSERT_FALSE(link.unresolved());
        std::printf("%g x 1 at %g: F %.6f, analytic %.6f\n", c.width, c.gap, double(link.g),
                    c.expected);
        EXPECT_NEAR(link.g, c.expected, 5e-3 * c.expected) << c.width << " x 1 at " << c.gap;
        EXPECT_FLOAT_EQ(link.visible(), 1.0f);
        const double radius = 0.5 * std::hypot(c.width, 1.0);
        EXPECT_LT(length(pair.tables->exact_slope(link)) * radius, 1e-3 * link.g);
    }
    // A floor and the wall standing on its edge, whose point form factor is steepest where
    // they meet.
    Pair pair({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {0, 1, 0});
    const ClusterLink link = pair.links->exact_link(pair.a, pair.b);
    ASSERT_TRUE(link.exact);
    ASSERT_FALSE(link.unresolved());
    std::printf("perpendicular 1 x 1 sharing an edge: F %.6f, analytic %.6f\n", double(link.g),
                0.200044);
    EXPECT_NEAR(link.g, 0.200044, 5e-3 * 0.200044);
}

// A wall standing across a floor sees the part of the floor in front of it: the exact link
// clips the floor's outline to each of the wall's points' tangent planes (clipped_contour).
// Its F is the mean, over the same points (4 per root), of the point form factors to the
// floor's roots clipped one by one: within 1e-6, with the wall on a line of the floor's
// tiling (its vertices on the plane) and off it.
TEST(ExactLinks, SourceAcrossTheReceiversPlaneIsClipped) {
    for (const double at : {0.5, 0.4}) {
        // Floor [0, 1]² facing up (4 x 4 tiles: lines at x = 0.25, 0.5, 0.75); a 1 x 1 wall
        // at x = `at` facing −x.
        Pair pair({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {at, 1, 0}, {0, 0, 1}, {0, -1, 0});
        const ClusterLink link = pair.links->exact_link(pair.b, pair.a);
        ASSERT_TRUE(link.exact);
        ASSERT_FALSE(link.unresolved());
        std::array<std::array<double, 2>, solver::k_max_quadrature_points> bary;
        std::size_t m = 0;
        solver::quadrature_barycentrics(1, bary.data(), &m);
        double sum = 0, area = 0;
        for (std::uint32_t r : pair.roots(pair.b)) {
            const auto& t = pair.h->triangle[r];
            for (std::size_t k = 0; k < m; ++k) {
                const Vec3 x =
                    t[0] * (1.0 - bary[k][0] - bary[k][1]) + t[1] * bary[k][0] + t[2] * bary[k][1];
                sum += pair.point_ff(x, pair.h->normal[r], pair.a) * pair.h->area[r] / double(m);
            }
            area += pair.h->area[r];
        }
        const double expected = sum / area;
        std::printf("wall at x = %g: F %.7f, root by root %.7f\n", at, double(link.g), expected);
        EXPECT_GT(expected, 0.05);
        EXPECT_NEAR(link.g, expected, 1e-6);
    }
}

// A wall beside a floor lights it by a gradient across the floor: the plane the floor
// cluster takes (F + slope · offset) stays within half the link's spread of the point form
// factors at its roots' centroids, at least twice as close as its mean alone, and gives the
// cluster the same power as the mean.
TEST(ExactLinks, ReceiverPlaneFollowsThePointFormFactors) {
    // Floor [0, 1]² facing up; wall at x = 1.5 facing −x.
    Pair pair({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1.5, 0, 0}, {0, 0, 1}, {0, 1, 0});
    const ClusterLink link = pair.links->exact_link(pair.a, pair.b);
    ASSERT_TRUE(link.exact);
    ASSERT_FALSE(link.unresolved());
    const Vec3 slope = pair.tables->exact_slope(link);
    EXPECT_GT(slope.x, 0.0); // brighter toward the wall
    const Vec3 m = pair.tree.centroid[solver::cluster_index(pair.a)];
    double plane_error = 0, mean_error = 0, weighted = 0, area = 0;
    for (std::uint32_t r : pair.roots(pair.a)) {
        const Vec3 x = pair.h->centroid(r);
        const double truth = pair.point_ff(x, pair.h->normal[r], pair.b);
        const double plane = link.g + dot(slope, x - m);
        plane_error = std::max(plane_error, std::abs(plane - truth));
        mean_error = std::max(mean_error, std::abs(double(link.g) - truth));
        weighted += plane * pair.h->area[r];
        area += pair.h->area[r];
    }
    EXPECT_LE(plane_error, 0.5 * link.spread() * 1.001);
    EXPECT_LT(plane_error, 0.5 * mean_error);
    EXPECT_NEAR(weighted / area, link.g, 1e-6);
}

// A wall whose radiosity falls with height sends the floor beside it what a gather from its
// roots weighted by their form factors gives (the floor, 0.5 m away, sees its bright foot at
// grazing angles and most of it higher up): within 1 % (measured 0.48 %), and at least 3
// times closer than the wall's mean radiosity (4.7 % off).
TEST(ExactLinks, SourceSendsTheRadiosityItsReceiverSees) {
    Pair pair({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1.5, 0, 0}, {0, 0, 1}, {0, 1, 0});
    std::vector<Rgb> b(pair.h->size(), Rgb{});
    for (std::uint32_t r : pair.roots(pair.b))
        b[r] = Rgb(float(1.0 + 2.0 * (1.0 - pair.h->centroid(r).z)));
    solver::pull_clusters(pair.tree, *pair.h, b, pair.cv);
    const ClusterLink link = pair.links->exact_link(pair.a, pair.b);
    ASSERT_TRUE(link.exact);
    const Rgb source_mean =
        pair.tables->face_mean(solver::cluster_index(link.source), pair.cv.exitance);
    const double sent = pair.tables->exact_source_radiosity(link, source_mean, pair.cv.gradient).g;
    double area = 0, mean = 0;
    for (std::uint32_t r : pair.roots(pair.b)) {
        mean += b[r].g * pair.h->area[r];
        area += pair.h->area[r];
    }
    mean /= area;
    const double truth = pair.gathered(pair.a, pair.b, b);
    std::printf("sent %.5f, gather %.5f, mean %.5f\n", sent, truth, mean);
    EXPECT_NEAR(sent, truth, 0.01 * truth);
    EXPECT_LT(std::abs(sent - truth) * 3, std::abs(mean - truth));
}

// A pair linked both ways is made in one computation (make_exact_pair): each end's points give
// its own link's form factor and the other link's offset. Both links are the ones made one
// by one (the same receiver points and rays): equal form factors, spreads, slopes and
// visibility. Their offsets come from each source's own points (128 here, where one link
// alone takes 32): within 1 cm of the single links' on these 1 m squares, and the radiosity
// each sends within 1 % of a gather from the source's roots. The two are reciprocal,
// F_ab A_a = F_ba A_b within 0.5 %.
TEST(ExactLinks, PairLinkedBothWaysIsMadeAsItsTwoLinks) {
    Pair pair({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1.5, 0, 0}, {0, 0, 1}, {0, 1, 0});
    std::vector<Rgb> b(pair.h->size(), Rgb{});
    for (std::uint32_t r : pair.roots(pair.b)) // the wall: brighter toward its foot
        b[r] = Rgb(float(1.0 + 2.0 * (1.0 - pair.h->centroid(r).z)));
    for (std::uint32_t r : pair.roots(pair.a)) // the floor: brighter toward the wall
        b[r] = Rgb(float(1.0 + pair.h->centroid(r).x));
    solver::pull_clusters(pair.tree, *pair.h, b, pair.cv);
    const auto [ab, ba] = pair.links->exact_pair(pair.a, pair.b);
    const ClusterLink single[2] = {pair.links->exact_link(pair.a, pair.b),
                                   pair.links->exact_link(pair.b, pair.a)};
    const ClusterLink* paired[2] = {&ab, &ba};
    for (int k = 0; k < 2; ++k) {
        const ClusterLink &l = *paired[k], &s = single[k];
        ASSERT_TRUE(l.exact);
        EXPECT_EQ(l.receiver, s.receiver);
        EXPECT_EQ(l.source, s.source);
        EXPECT_GT(l.g, 0.0f);
        EXPECT_FLOAT_EQ(l.g, s.g);
        EXPECT_FLOAT_EQ(l.spread(), s.spread());
        EXPECT_FLOAT_EQ(l.d.z, s.d.z);
        EXPECT_FLOAT_EQ(l.slope_t, s.slope_t);
        EXPECT_NEAR(l.d.y, s.d.y, 0.01);
        EXPECT_EQ(l.v_bits, s.v_bits);
        EXPECT_EQ(l.rays, s.rays);
        const Rgb mean = pair.tables->face_mean(solver::cluster_index(l.source), pair.cv.exitance);
        const double sent = pair.tables->exact_source_radiosity(l, mean, pair.cv.gradient).g;
        const double truth = pair.gathered(l.receiver, l.source, b);
        std::printf("pair: %s sends %.5f, gather %.5f\n", k == 0 ? "wall" : "floor", sent, truth);
        EXPECT_NEAR(sent, truth, 0.01 * truth);
    }
    const double area_a = pair.tree.area[solver::cluster_index(pair.a)];
    const double area_b = pair.tree.area[solver::cluster_index(pair.b)];
    EXPECT_NEAR(ab.g * area_a, ba.g * area_b, 5e-3 * ab.g * area_a);
}

// planar_gradients recovers a linear function of position over a face cluster, and the
// push spreads a face cluster's slope over its roots without adding or losing power.
TEST(ExactLinks, GradientsAndSlopedPush) {
    Pair pair({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1.5, 0, 0}, {0, 0, 1}, {0, 1, 0});
    const Vec3 g(0.7, -0.3, 0); // in the floor's plane
    std::vector<Rgb> value(pair.h->size(), Rgb{});
    for (std::uint32_t r : pair.roots(pair.a))
        value[r] = Rgb(float(2.0 + dot(g, pair.h->centroid(r))));
    std::vector<solver::Slope> gradient;
    solver::planar_gradients(pair.tree, *pair.h, value, gradient);
    const std::uint32_t c = solver::cluster_index(pair.a);
    for (std::size_t axis = 0; axis < 3; ++axis)
        EXPECT_NEAR(gradient[c][axis].g, g[axis], 1e-5) << "axis " << axis;

    solver::ClusterValues cv = pair.cv;
    cv.gathered_direct.assign(pair.tree.size(), solver::Lobes{});
    cv.gathered_indirect.assign(pair.tree.size(), solver::Lobes{});
    cv.slope_direct.assign(pair.tree.size(), solver::Slope{});
    cv.slope_indirect.assign(pair.tree.size(), solver::Slope{});
    cv.slope_indirect[c] = {Rgb(float(g.x)), Rgb(float(g.y)), Rgb(0.0f)};
    solver::push_clusters(pair.tree, *pair.h, cv);
    const Vec3 m = pair.tree.centroid[c];
    double power = 0, scale = 0;
    for (std::uint32_t r : pair.roots(pair.a)) {
        const double expected = dot(g, pair.h->centroid(r) - m);
        EXPECT_NEAR(cv.root_indirect[r].g, expected, 1e-5);
        power += cv.root_indirect[r].g * pair.h->area[r];
        scale += std::abs(expected) * pair.h->area[r];
    }
    EXPECT_LT(std::abs(power), 1e-5 * scale);
}

// Reflected light is not resolved below the minimum area: a floor and the wall beside it,
// both bright and both 1 m² (32 roots each), keep their one exact link each way however small
// the threshold when the minimum area is 2 m², and are refined down to links to each of
// their roots (1/32 m²) when it is 0.05 m².
TEST(ExactLinks, FaceClustersWithinTheMinimumAreaAreNotSplit) {
    for (const double min_area : {2.0, 0.05}) {
        Pair pair({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1.5, 0, 0}, {0, 0, 1}, {0, 1, 0}, min_area);
        std::vector<Rgb> b(pair.h->size(), Rgb(1.0f));
        std::vector<float> b_range(pair.h->size(), 0.0f);
        solver::init_cluster_values(pair.tree, *pair.h, b, pair.cv);
        pair.links->link_clusters();
        pair.links->set_threshold(1e-9);
        pair.links->set_cluster_threshold(1e-9);
        pair.links->refine(b, b_range);
        std::size_t between_clusters = 0, to_roots = 0;
        for (const ClusterLink& l : pair.store.cluster_links()) {
            between_clusters += l.exact && ((l.receiver == pair.a && l.source == pair.b) ||
                                            (l.receiver == pair.b && l.source == pair.a));
            to_roots += !solver::is_cluster(l.receiver);
        }
        to_roots += pair.store.links().size();
        std::printf("min area %g m²: %zu links, %zu of them to roots\n", min_area,
                    pair.store.link_count(), to_roots);
        if (min_area > 1.0) {
            EXPECT_EQ(between_clusters, 2u);
            EXPECT_EQ(pair.store.link_count(), 2u);
        } else {
            EXPECT_EQ(between_clusters, 0u);
            EXPECT_EQ(to_roots, pair.store.link_count()); // a root's mean F is all it takes
            EXPECT_GE(to_roots, 64u);
        }
    }
}

} // namespace
} // namespace penumbra
