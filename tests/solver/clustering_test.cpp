// Issue #4: clustering for hierarchical radiosity (solver/src/hierarchy/cluster_tree.h): light
// exchanged through cluster links keeps the closed-box furnace and agrees with the unclustered
// solve. Reference values: docs/validation.md §2.

#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "app/pipeline.h"
#include "common/bake_util.h"
#include "common/test_util.h"
#include "hierarchy/cluster_tree.h"
#include "hierarchy/hierarchy.h"
#include "links/link_set.h"
#include "mesher/mesher.h"
#include "office_scene.h"
#include "output/point_gather.h"
#include "output/vertex_values.h"
#include "raytrace/raytrace.h"

namespace penumbra {
namespace {

using test::add_material;

using test::bake;

// A closed room lit by a small ceiling lamp, with a box on the floor, its low corner at \p o:
// nothing escapes, so the absorbed power must equal the emitted power.
void add_lamp_room(Scene& scene, const Vec3& o) {
    auto wall = add_material(scene, "wall", Rgb(0.6f));
    auto lamp = add_material(scene, "lamp", Rgb(0.0f), Rgb(50.0f), false);
    test::add_room(scene, o, o + Vec3(4, 3, 2.5), wall);
    test::add_rect(scene, "lamp", lamp, o + Vec3(1.8, 1.3, 2.49), {0, 0.4, 0}, {0.4, 0, 0});
    // a box on the floor, outward faces
    const Vec3 lo = o + Vec3(2.5, 0.5, 0), hi = o + Vec3(3.3, 1.3, 0.7);
    test::add_rect(scene, "box_top", wall, {lo.x, lo.y, hi.z}, {0.8, 0, 0}, {0, 0.8, 0});
    test::add_rect(scene, "box_x0", wall, {lo.x, lo.y, lo.z}, {0, 0, 0.7}, {0, 0.8, 0});
    test::add_rect(scene, "box_x1", wall, {hi.x, lo.y, lo.z}, {0, 0.8, 0}, {0, 0, 0.7});
    test::add_rect(scene, "box_y0", wall, {lo.x, lo.y, lo.z}, {0.8, 0, 0}, {0, 0, 0.7});
    test::add_rect(scene, "box_y1", wall, {lo.x, hi.y, lo.z}, {0, 0, 0.7}, {0.8, 0, 0});
}

Scene lamp_room(const std::string& clustering, double eps) {
    Scene scene;
    scene.solver.epsilon = eps;
    scene.solver.clustering = *parse_enum<Clustering>(clustering);
    scene.solver.residual = 1e-5;
    add_lamp_room(scene, {0, 0, 0});
    scene.mesher.max_edge_length = 0.4;
    scene.sensors = {{"floor", {1, 1, 0}, {0, 0, 1}},
                     {"wall", {0, 1.5, 1.2}, {1, 0, 0}},
                     {"ceiling", {3, 2, 2.5}, {0, 0, -1}},
                     {"behind_box", {3.5, 0.9, 0}, {0, 0, 1}}};
    return scene;
}

double relative(double a, double b) {
    return std::abs(a - b) / std::abs(b);
}

// Clustered links carry the same light as links between all pairs of elements: nothing
// escapes the closed room, so the absorbed power is the emitted power (a conservation law the
// point approximation of cluster links would break), and the sensors agree with the
// unclustered solve. Clustering needs far fewer links.
TEST(Clustering, ClosedRoomConservesPowerAndAgreesWithAllPairs) {
    const app::BakeResult all = bake(lamp_room("off", 1e-2));
    const app::BakeResult clustered = bake(lamp_room("on", 1e-2));
    const auto& pb = clustered.stats.power;
    EXPECT_LT(relative(pb.absorbed.g + pb.escaped.g, pb.emitted.g), 0.015);
    ASSERT_EQ(all.sensors.size(), clustered.sensors.size());
    // Measured at most 0.57 % (1.16 % while exact links gave their receivers one value).
    for (std::size_t s = 0; s < all.sensors.size(); ++s)
        EXPECT_LT(
            relative(clustered.sensors[s].irradiance_total.g, all.sensors[s].irradiance_total.g),
            0.01)
            << "sensor " << s;
    EXPECT_LT(clustered.stats.links * 2, all.stats.links);
}

// Shrinking ε makes the clustered solution converge: the power balance tightens.
TEST(Clustering, ErrorFallsWithEpsilon) {
    double previous = 1;
    for (double eps : {3e-2, 3e-3}) {
        const app::BakeResult r = bake(lamp_room("on", eps));
        const auto& pb = r.stats.power;
        const double error = relative(pb.absorbed.g + pb.escaped.g, pb.emitted.g);
        std::printf("lamp room, eps %g: %zu links, power error %.3g\n", eps, r.stats.links, error);
        EXPECT_LT(error, previous) << "eps " << eps;
        previous = error;
    }
    // Measured 0.03 % (0.10 % while exact links gave their receivers one value, with twice as
    // many links; 0.34 % before the kernels were scaled to the true cosines, with reflected
    // light weighed at 1/3 rather than 1/5 in the cluster oracle).
    EXPECT_LT(previous, 0.0025);
}

// Two offices of tessellation 3, meshed as input (no contact splitting).
RadiosityMesh tessellated_offices() {
    bench::OfficeParams params;
    params.rooms_x = 2;
    params.rooms_y = 1;
    params.tessellation = 3;
    Scene scene = bench::office_floor(params);
    bench::mesh_input_as_is(scene);
    return mesher::build_mesh(scene, test::quiet_context());
}

// The cluster tree's lower part is face clusters: on the office floor, every leaf cluster's
// roots lie in one plane and face one way, and every root is in exactly one leaf.
TEST(Clustering, LeafClustersArePlanarOnTessellatedOffices) {
    const RadiosityMesh mesh = tessellated_offices();
    const solver::Hierarchy h(mesh);
    const solver::ClusterTree tree = solver::build_cluster_tree(h);
    std::vector<int> seen(h.root_count, 0);
    std::size_t leaves = 0;
    for (std::size_t c = 0; c < tree.size(); ++c) {
        const auto begin = tree.child_begin[c], end = tree.child_begin[c + 1];
        if (solver::is_cluster(tree.children[begin]))
            continue;
        ++leaves;
        const std::uint32_t first = tree.children[begin];
        for (auto k = begin; k < end; ++k) {
            const std::uint32_t r = tree.children[k];
            ++seen[r];
            EXPECT_GT(dot(h.normal[r], h.normal[first]), 1.0 - 1e-9) << "cluster " << c;
            EXPECT_NEAR(dot(h.normal[first], h.centroid(r) - h.centroid(first)), 0.0,
                        1e-9 * h.diagonal)
                << "cluster " << c;
        }
    }
    EXPECT_GT(leaves, h.root_count / 8);
    for (std::size_t r = 0; r < h.root_count; ++r)
        EXPECT_EQ(seen[r], 1) << "root " << r;
}

// The levels that the sweeps' passes over the tree run in parallel: every cluster once, each
// level after its parents' (a parent's depth is one less), the top cluster alone first.
TEST(Clustering, LevelsHoldEveryClusterBelowItsParent) {
    const RadiosityMesh mesh = tessellated_offices();
    const solver::Hierarchy h(mesh);
    const solver::ClusterTree tree = solver::build_cluster_tree(h);
    const solver::ClusterLevels& levels = tree.levels;
    ASSERT_EQ(levels.order.size(), tree.size());
    ASSERT_GE(levels.begin.size(), 3u); // the tree is more than one level deep
    EXPECT_EQ(levels.begin[1] - levels.begin[0], 1u);
    EXPECT_EQ(levels.order[0], 0u);
    std::vector<int> depth(tree.size(), -1);
    for (std::size_t d = 0; d + 1 < levels.begin.size(); ++d)
        for (std::uint32_t k = levels.begin[d]; k < levels.begin[d + 1]; ++k) {
            ASSERT_EQ(depth[levels.order[k]], -1) << "cluster " << levels.order[k] << " twice";
            depth[levels.order[k]] = int(d);
        }
    for (std::size_t c = 1; c < tree.size(); ++c)
        EXPECT_EQ(depth[c], depth[std::size_t(tree.parent[c])] + 1) << "cluster " << c;
}

// The links stay grouped by receiver and ordered by source (the in-place flag sort of
// LinkStore::sort_and_index), with receiver_offsets() bounding each group, after linking the
// roots and after a refinement that splits many of them.
TEST(Clustering, LinksAreSortedByReceiverThenSource) {
    Scene scene = lamp_room("off", 1e-2);
    const RadiosityMesh mesh = mesher::build_mesh(scene, test::quiet_context());
    solver::Hierarchy h(mesh);
    const raytrace::EmbreeScene embree(mesh);
    solver::RefineSettings settings;
    settings.rows.visibility_rays = 4;
    settings.offset = 1e-5 * mesh.scene_diagonal;
    settings.min_area = 1e-3;
    solver::LinkStore store;
    solver::LinkSet links(h, store, nullptr, embree, scene.point_lights, nullptr, nullptr,
                          settings);
    auto check = [&](const char* when) {
        const auto& all = store.links();
        const auto& offsets = store.receiver_offsets();
        ASSERT_EQ(offsets.size(), h.size() + 1) << when;
        ASSERT_EQ(offsets.back(), all.size()) << when;
        for (std::size_t n = 0; n < h.size(); ++n)
            for (std::uint32_t k = offsets[n]; k < offsets[n + 1]; ++k) {
                ASSERT_EQ(all[k].receiver, n) << when;
                if (k > offsets[n]) {
                    ASSERT_LT(all[k - 1].source, all[k].source) << when;
                }
            }
    };
    links.link_roots();
    const std::size_t linked = store.links().size();
    check("linked");
    std::vector<Rgb> b = h.emission;
    std::vector<float> b_range(h.size(), 0.0f);
    links.set_threshold(1e-4 * 50.0);
    ASSERT_TRUE(links.refine(b, b_range));
    EXPECT_GT(store.links().size(), linked + linked / 20); // measured 956 k -> 1.03 M
    check("refined");
}

TEST(Clustering, IdenticalFor1And2And4Threads) {
    const app::BakeResult one = bake(lamp_room("on", 1e-2), 1);
    for (int threads : {2, 4}) {
        const app::BakeResult r = bake(lamp_room("on", 1e-2), threads);
        EXPECT_EQ(one.stats.links, r.stats.links);
        ASSERT_EQ(one.solution.radiosity.size(), r.solution.radiosity.size());
        EXPECT_EQ(0, std::memcmp(one.solution.radiosity.data(), r.solution.radiosity.data(),
                                 one.solution.radiosity.size() * sizeof(Rgb)))
            << threads << " threads";
    }
}

// Two such rooms side by side, each sealed by its own walls 0.2 m apart: every ray between
// them is blocked, and the second room must cost about the links of the first, not a
// cascade of cluster links split level after level because four blocked rays cannot prove
// the pair dark (they get more rays instead: measured 2.06 times one room's links, 2.22
// before; since a wall plane proves the pairs across it dark, 2.04). Each room keeps its own
// light: the sensors of the second equal the first's.
TEST(Clustering, SealedNeighbourAddsAboutItsOwnLinks) {
    const app::BakeResult one = bake(lamp_room("on", 3e-3));
    Scene pair = lamp_room("on", 3e-3);
    add_lamp_room(pair, {4.2, 0, 0});
    const std::size_t n = pair.sensors.size();
    for (std::size_t s = 0; s < n; ++s) {
        Sensor moved = pair.sensors[s];
        moved.position.x += 4.2;
        pair.sensors.push_back(moved);
    }
    const app::BakeResult two = bake(pair);
    std::printf("lamp room: %zu links, two sealed rooms: %zu links\n", one.stats.links,
                two.stats.links);
    EXPECT_LT(double(two.stats.links), 2.08 * double(one.stats.links));
    for (std::size_t s = 0; s < n; ++s)
        EXPECT_LT(
            relative(two.sensors[s + n].irradiance_total.g, two.sensors[s].irradiance_total.g),
            0.02)
            << "sensor " << s;
}

// Issue #4: on the generated office floors (tests/support/office_scene.h), links at 8 000 input
// triangles over links at 2 000 is at most 5: with clusters the links grow about linearly.
TEST(Clustering, LinksGrowAboutLinearlyOnOfficeFloors) {
    std::uint64_t links[2] = {0, 0};
    std::int64_t triangles[2] = {0, 0};
    const std::int64_t targets[2] = {2000, 8000};
    for (int k = 0; k < 2; ++k) {
        Scene scene = bench::office_floor(bench::office_params_for_triangles(targets[k]));
        bench::mesh_input_as_is(scene);
        scene.solver.clustering = Clustering::on;
        scene.solver.epsilon = 3e-2;
        scene.sensors.clear();
        triangles[k] = bench::input_triangle_count(scene);
        links[k] = bake(scene).stats.links;
    }
    std::printf("office floors: %lld triangles -> %llu links, %lld triangles -> %llu links\n",
                (long long)triangles[0], (unsigned long long)links[0], (long long)triangles[1],
                (unsigned long long)links[1]);
    EXPECT_GT(double(triangles[1]) / double(triangles[0]), 3.5);
    EXPECT_LE(double(links[1]) / double(links[0]), 5.0);
}

// An open hall, 16 × 8 × 3 m, lit by a 4 × 2 grid of ceiling panels, with a row of boxes.
Scene panel_hall() {
    Scene scene;
    scene.solver.clustering = Clustering::on;
    scene.solver.epsilon = 3e-2;
    auto wall = add_material(scene, "wall", Rgb(0.5f));
    auto panel = add_material(scene, "panel", Rgb(0.0f), Rgb(60.0f), false);
    test::add_room(scene, {0, 0, 0}, {16, 8, 3}, wall);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 2; ++j)
            test::add_rect(scene, "panel", panel, {2.0 + 4.0 * i, 2.0 + 4.0 * j, 2.99}, {0, 0.6, 0},
                           {0.6, 0, 0});
    for (int i = 0; i < 3; ++i) {
        const Vec3 lo(3.5 + 4.0 * i, 3.5, 0), hi(4.5 + 4.0 * i, 4.5, 1.2);
        test::add_rect(scene, "box_top", wall, {lo.x, lo.y, hi.z}, {1, 0, 0}, {0, 1, 0});
        test::add_rect(scene, "box_x0", wall, {lo.x, lo.y, 0}, {0, 0, 1.2}, {0, 1, 0});
        test::add_rect(scene, "box_x1", wall, {hi.x, lo.y, 0}, {0, 1, 0}, {0, 0, 1.2});
        test::add_rect(scene, "box_y0", wall, {lo.x, lo.y, 0}, {1, 0, 0}, {0, 0, 1.2});
        test::add_rect(scene, "box_y1", wall, {lo.x, hi.y, 0}, {0, 0, 1.2}, {1, 0, 0});
    }
    scene.mesher.max_edge_length = 0.8;
    return scene;
}

// A vertex gathers direct light exactly from the emitters that element links bring to its
// elements, and takes what cluster links bring (the far panels of the hall) as its
// elements' mean, rather than gathering from every emitter of the scene, which grows as the
// scene's size squared. Against an exact gather from every emitter at every 5th vertex (from
// where the vertices gather: inside the elements on a boundary): relative L1 below 1.5 % at
// ε = 3e-2 (measured 0.44 %; 0.61 % before boundary vertices gathered from inside, 2.5 %
// without the far part).
TEST(Clustering, VertexDirectLightAgreesWithAGatherFromEveryEmitter) {
    const Scene scene = panel_hall();
    const app::BakeResult r = bake(scene);
    const RadiosityMesh& mesh = r.mesh;
    raytrace::EmbreeScene rt(mesh);
    const solver::ElementGeometry geo(mesh);
    std::vector<Rgb> emission(mesh.element_count());
    for (std::size_t e = 0; e < emission.size(); ++e)
        emission[e] = mesh.patch_of(std::uint32_t(e)).emission;
    const solver::GatherSources every = solver::direct_sources(scene, emission);
    const std::vector<Vec3> at = solver::vertex_gather_positions(mesh, geo.offset);
    double difference = 0, total = 0;
    for (std::uint32_t v = 0; v < mesh.vertex_count(); v += 5) {
        const solver::GatherPoint p{at[v], mesh.patches[mesh.vertex_patch[v]].normal, v,
                                    RngPurpose::vertex_visibility};
        const double exact =
            solver::gather_direct(geo, every, rt, p, scene.solver.visibility_rays, 0).g;
        difference += std::abs(double(r.solution.vertex_irradiance_direct[v].g) - exact);
        total += exact;
    }
    std::printf("hall: %zu links, vertex direct light against every emitter: relative L1 %.3g\n",
                r.stats.links, difference / total);
    EXPECT_LT(difference / total, 0.015);
}

} // namespace
} // namespace penumbra
