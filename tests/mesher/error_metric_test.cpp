// Issue #5's error metric: direct illuminance at 10 000 random points of the floor,
// interpolated linearly from exact values at the mesh vertices, against the exact value at
// the point. At equal element counts (±5 %), the discontinuity mesh must halve the RMS error
// of a mesh without discontinuity segments. The same figure for the Cornell box is reported.

#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "core/rng.h"
#include "core/scene_io.h"
#include "mesher/exact_direct.h"
#include "mesher/mesh_checks.h"
#include "mesher/mesher.h"
#include "mesher/test_scenes.h"

namespace penumbra {
namespace {

using Exact = std::function<double(const Vec3&)>;

/// A triangle of the receiving patch with its vertices' exact values.
struct Tri {
    Vec3 a, b, c;
    double va, vb, vc;
};

struct Metric {
    double rms = 0, mean = 0;
    std::size_t elements = 0, receiver_elements = 0;
};

// Interpolates exact vertex values at p (normal n) inside one of the triangles; -1 if outside.
double interpolate(const std::vector<Tri>& tris, const Vec3& p, const Vec3& n) {
    for (const Tri& t : tris) {
        const Vec3 nn = cross(t.b - t.a, t.c - t.a);
        const double area2 = dot(nn, n);
        const double w1 = dot(cross(p - t.a, t.c - t.a), n) / area2;
        const double w2 = dot(cross(t.b - t.a, p - t.a), n) / area2;
        if (w1 >= -1e-12 && w2 >= -1e-12 && w1 + w2 <= 1 + 1e-12)
            return t.va * (1 - w1 - w2) + t.vb * w1 + t.vc * w2;
    }
    return -1;
}

// RMS over the sample points of (interpolated − exact); the patch is polygon's front side.
// A vertex's value is the exact value's limit from inside each element (taken 10 µm towards
// the centroid): at the foot of a blocker the exact value jumps, and the vertex itself lies
// on the blocker (within float round-off, on either side of it).
Metric measure(const RadiosityMesh& mesh, std::uint32_t polygon, const std::vector<Vec3>& points,
               const Vec3& n, const Exact& exact) {
    const auto patch = std::uint32_t(test::find_patch(mesh, polygon));
    std::vector<Tri> tris;
    Metric m;
    m.elements = mesh.element_count();
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
        if (mesh.element_patch[e] != patch)
            continue;
        ++m.receiver_elements;
        const auto& t = mesh.triangles[e];
        const Vec3 a = mesh.vertex(t[0]), b = mesh.vertex(t[1]), c = mesh.vertex(t[2]);
        const Vec3 centre = (a + b + c) / 3.0;
        auto limit = [&](const Vec3& v) {
            const double d = length(centre - v);
            return exact(v + (centre - v) * (std::min(1e-5, 0.01 * d) / d));
        };
        tris.push_back({a, b, c, limit(a), limit(b), limit(c)});
    }
    double sum2 = 0, sum = 0;
    for (const Vec3& p : points) {
        const double approx = interpolate(tris, p, n);
        EXPECT_GE(approx, 0) << "sample outside the receiver's elements";
        const double e = exact(p);
        sum2 += (approx - e) * (approx - e);
        sum += e;
    }
    m.rms = std::sqrt(sum2 / double(points.size()));
    m.mean = sum / double(points.size());
    return m;
}

// The scene meshed without discontinuity segments, its element size adjusted until the
// element count is within 5 % of \p target.
RadiosityMesh uniform_with_count(Scene scene, std::size_t target) {
    scene.mesher.discontinuity.enabled = false;
    RadiosityMesh mesh;
    for (int i = 0; i < 20; ++i) {
        mesh = mesher::build_mesh(scene, test::quiet_context());
        const double ratio = double(mesh.element_count()) / double(target);
        if (std::abs(ratio - 1) <= 0.04)
            break;
        scene.mesher.max_edge_length *= std::pow(ratio, 0.5 + 0.1 * (i % 3));
    }
    return mesh;
}

std::vector<Vec3> floor_points(std::size_t n, const std::function<Vec3(double, double)>& at,
                               const std::function<bool(const Vec3&)>& reject) {
    Pcg32 rng = Pcg32::for_stream(RngPurpose::form_factor_visibility, 5, 0, 0, 2024);
    std::vector<Vec3> points;
    while (points.size() < n) {
        const Vec3 p = at(rng.next_double(), rng.next_double());
        if (!reject(p))
            points.push_back(p);
    }
    return points;
}

void report(const char* scene, const Metric& disc, const Metric& uniform) {
    std::printf("[ metric   ] %s: discontinuity mesh %zu elements (%zu on the floor), RMS %.4g "
                "W/m2 = %.3g %% of the mean; uniform %zu elements (%zu on the floor), RMS %.4g "
                "W/m2 = %.3g %%; ratio %.2f\n",
                scene, disc.elements, disc.receiver_elements, disc.rms, 100 * disc.rms / disc.mean,
                uniform.elements, uniform.receiver_elements, uniform.rms,
                100 * uniform.rms / uniform.mean, uniform.rms / disc.rms);
}

TEST(ErrorMetric, DiscontinuityMeshHalvesTheErrorOfTheBoxOnTheFloor) {
    const test::BoxUnderLight b = test::box_under_light(0.25);
    const Exact exact = [&](const Vec3& p) {
        return test::exact_irradiance(p, {0, 0, 1}, b.light_vertices, b.radiance, {b.box_vertices});
    };
    const auto& fp = b.footprint;
    const std::vector<Vec3> points = floor_points(
        10000, [](double u, double v) { return Vec3(4 * u, 4 * v, 0); },
        [&](const Vec3& p) { return p.x > fp[0] && p.x < fp[2] && p.y > fp[1] && p.y < fp[3]; });
    const RadiosityMesh disc_mesh = mesher::build_mesh(b.scene, test::quiet_context());
    const RadiosityMesh uniform_mesh = uniform_with_count(b.scene, disc_mesh.element_count());
    const Metric disc = measure(disc_mesh, b.floor, points, {0, 0, 1}, exact);
    const Metric uniform = measure(uniform_mesh, b.floor, points, {0, 0, 1}, exact);
    report("box on the floor", disc, uniform);
    EXPECT_NEAR(double(uniform.elements) / double(disc.elements), 1.0, 0.05);
    EXPECT_GE(uniform.rms, 2.0 * disc.rms);
}

void cornell_report(Scene scene) {
    std::vector<Vec3> light;
    std::vector<std::vector<Vec3>> blocks(2);
    double radiance = 0;
    for (const Polygon& p : scene.polygons) {
        const Material& m = scene.materials[p.material];
        if (!m.emission.is_black()) {
            light = p.vertices;
            radiance = m.emission.g;
        } else if (p.name == "short_block" || p.name == "tall_block") {
            auto& block = blocks[p.name == "short_block" ? 0 : 1];
            block.insert(block.end(), p.vertices.begin(), p.vertices.end());
        }
    }
    ASSERT_EQ(light.size(), 4u);
    const Exact exact = [&](const Vec3& p) {
        return test::exact_irradiance(p, {0, 1, 0}, light, radiance, blocks);
    };
    // The floor (polygon 0) without the blocks' footprints (hidden, no elements there).
    const RadiosityMesh disc_mesh = mesher::build_mesh(scene, test::quiet_context());
    const auto floor = std::uint32_t(test::find_patch(disc_mesh, 0));
    std::vector<Tri> floor_tris;
    for (std::size_t e = 0; e < disc_mesh.element_count(); ++e)
        if (disc_mesh.element_patch[e] == floor) {
            const auto& t = disc_mesh.triangles[e];
            floor_tris.push_back(
                {disc_mesh.vertex(t[0]), disc_mesh.vertex(t[1]), disc_mesh.vertex(t[2]), 0, 0, 0});
        }
    const Polygon& f = scene.polygons[0];
    const std::vector<Vec3> points = floor_points(
        10000,
        [&](double u, double v) {
            return f.vertices[1] + (f.vertices[0] - f.vertices[1]) * u +
                   (f.vertices[2] - f.vertices[1]) * v;
        },
        [&](const Vec3& p) {
            const Vec3 q(p.x, 0, p.z);
            return interpolate(floor_tris, q, {0, 1, 0}) < 0 ||
                   interpolate(floor_tris, q + Vec3(1e-3, 0, 0), {0, 1, 0}) < 0 ||
                   interpolate(floor_tris, q - Vec3(1e-3, 0, 0), {0, 1, 0}) < 0;
        });
    const RadiosityMesh uniform_mesh = uniform_with_count(scene, disc_mesh.element_count());
    const Metric disc = measure(disc_mesh, 0, points, {0, 1, 0}, exact);
    const Metric uniform = measure(uniform_mesh, 0, points, {0, 1, 0}, exact);
    const std::string name = "Cornell box, " +
                             std::to_string(int(std::lround(1000 * scene.mesher.max_edge_length))) +
                             " mm (green)";
    report(name.c_str(), disc, uniform);
    EXPECT_NEAR(double(uniform.elements) / double(disc.elements), 1.0, 0.05);
}

// Report only: at the scene's element size and at 40 mm.
TEST(ErrorMetric, CornellBoxReport) {
    Scene scene = load_scene(test::source_path("data/cornell/scene.json"));
    cornell_report(scene);
    scene.mesher.max_edge_length = 0.04;
    cornell_report(scene);
}

TEST(ExactDirect, AgreesWithLambertAndBlocksCompletely) {
    const std::vector<Vec3> light{{-0.5, -0.5, 2}, {-0.5, 0.5, 2}, {0.5, 0.5, 2}, {0.5, -0.5, 2}};
    const Vec3 p(0, 0, 0), n(0, 0, 1);
    const double open = test::exact_irradiance(p, n, light, 1.0, {});
    EXPECT_NEAR(open, test::polygon_irradiance(p, n, light), 1e-12);
    EXPECT_NEAR(open, 1.0 / 4.0, 0.02); // ≈ L A / h² for a small source
    const std::vector<Vec3> slab{{-1, -1, 1},   {1, -1, 1},   {1, 1, 1},   {-1, 1, 1},
                                 {-1, -1, 1.1}, {1, -1, 1.1}, {1, 1, 1.1}, {-1, 1, 1.1}};
    EXPECT_NEAR(test::exact_irradiance(p, n, light, 1.0, {slab}), 0.0, 1e-12);
    // A blocker over exactly half of the light, by symmetry.
    const std::vector<Vec3> half{{0, -1, 1},   {1, -1, 1},   {1, 1, 1},   {0, 1, 1},
                                 {0, -1, 1.1}, {1, -1, 1.1}, {1, 1, 1.1}, {0, 1, 1.1}};
    EXPECT_NEAR(test::exact_irradiance(p, n, light, 1.0, {half}), open / 2, 1e-9);
    // Two overlapping blockers count once.
    EXPECT_NEAR(test::exact_irradiance(p, n, light, 1.0, {half, half}), open / 2, 1e-9);
}

} // namespace
} // namespace penumbra
