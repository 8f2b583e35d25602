// Meshing time and element counts (issue #5): the Cornell box and generated open-plan office
// floors of nx × ny offices (partitions with doors, two desks on legs and a cabinet each, a
// ceiling panel light per office; floor and ceiling are single polygons spanning the floor
// plate, as generated models often have). Each scene is meshed with and without
// discontinuity meshing. Usage: mesh_bench [EDGE_M] [N ...] (default 0.25 m; 1, 2 and 4 → 1,
// 4 and 16 offices).

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "core/scene_io.h"
#include "mesher/mesher.h"

namespace {

using namespace penumbra;

void rect(Scene& s, const std::string& name, std::uint32_t m, const Vec3& o, const Vec3& u,
          const Vec3& v) {
    s.polygons.push_back({{o, o + u, o + u + v, o + v}, m, name, "office:" + name});
}

// An axis-aligned box [lo, hi] with outward faces; without a bottom face if \p open_bottom.
void box(Scene& s, const std::string& name, std::uint32_t m, const Vec3& lo, const Vec3& hi,
         bool open_bottom) {
    const Vec3 d = hi - lo;
    const Vec3 ex(d.x, 0, 0), ey(0, d.y, 0), ez(0, 0, d.z);
    rect(s, name + "_top", m, lo + ez, ex, ey);
    rect(s, name + "_y0", m, lo, ex, ez);
    rect(s, name + "_y1", m, lo + ey + ex, ex * -1.0, ez);
    rect(s, name + "_x0", m, lo + ey, ey * -1.0, ez);
    rect(s, name + "_x1", m, lo + ex, ey, ez);
    if (!open_bottom)
        rect(s, name + "_bottom", m, lo, ey, ex);
}

void desk(Scene& s, const std::string& name, std::uint32_t m, double x, double y) {
    box(s, name + "_top", m, {x, y, 0.69}, {x + 1.6, y + 0.8, 0.72}, false);
    for (double lx : {x + 0.05, x + 1.5})
        for (double ly : {y + 0.05, y + 0.7})
            box(s, name + "_leg", m, {lx, ly, 0}, {lx + 0.05, ly + 0.05, 0.69}, true);
}

// A partition along x = x0 from y0 to y1 with a 0.9 × 2.1 m door, as three rectangles.
void partition_x(Scene& s, std::uint32_t m, double x0, double y0, double y1, double h) {
    const double door = y0 + 0.5;
    rect(s, "partition", m, {x0, y0, 0}, {0, 0, h}, {0, door - y0, 0});
    rect(s, "partition", m, {x0, door + 0.9, 0}, {0, 0, h}, {0, y1 - door - 0.9, 0});
    rect(s, "lintel", m, {x0, door, 2.1}, {0, 0, h - 2.1}, {0, 0.9, 0});
}

void partition_y(Scene& s, std::uint32_t m, double y0, double x0, double x1, double h) {
    const double door = x0 + 0.5;
    rect(s, "partition", m, {x0, y0, 0}, {door - x0, 0, 0}, {0, 0, h});
    rect(s, "partition", m, {door + 0.9, y0, 0}, {x1 - door - 0.9, 0, 0}, {0, 0, h});
    rect(s, "lintel", m, {door, y0, 2.1}, {0.9, 0, 0}, {0, 0, h - 2.1});
}

Scene office(int n, double edge) {
    Scene s;
    s.name = "office";
    s.materials = {{"wall", Rgb(0.7f)}, {"desk", Rgb(0.4f)}, {"panel", Rgb(0.0f), Rgb(30.0f)}};
    s.materials[2].two_sided = false;
    const double w = 4.0, d = 3.5, h = 2.8;
    const double W = w * n, D = d * n;
    rect(s, "floor", 0, {0, 0, 0}, {W, 0, 0}, {0, D, 0});
    rect(s, "ceiling", 0, {0, 0, h}, {0, D, 0}, {W, 0, 0});
    rect(s, "wall_y0", 0, {0, 0, 0}, {0, 0, h}, {W, 0, 0});
    rect(s, "wall_y1", 0, {0, D, 0}, {W, 0, 0}, {0, 0, h});
    rect(s, "wall_x0", 0, {0, 0, 0}, {0, D, 0}, {0, 0, h});
    rect(s, "wall_x1", 0, {W, 0, 0}, {0, 0, h}, {0, D, 0});
    for (int i = 1; i < n; ++i) {
        partition_x(s, 0, w * i, 0, D, h);
        partition_y(s, 0, d * i, 0, W, h);
    }
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double x = w * i, y = d * j;
            const std::string tag = std::to_string(i) + "_" + std::to_string(j);
            desk(s, "desk_a" + tag, 1, x + 0.4, y + 0.5);
            desk(s, "desk_b" + tag, 1, x + 2.1, y + 2.2);
            box(s, "cabinet" + tag, 1, {x + 3.0, y + 0.0, 0}, {x + 3.8, y + 0.4, 1.2}, true);
            rect(s, "panel" + tag, 2, {x + 1.4, y + 1.45, h - 0.01}, {0, 0.6, 0}, {1.2, 0, 0});
        }
    s.mesher.max_edge_length = edge;
    s.mesher.element_budget = 0;
    return s;
}

struct Run {
    double seconds;
    std::size_t elements, segments;
    double hidden;
};

Run mesh(const Scene& scene) {
    Context ctx; // all cores
    const auto start = std::chrono::steady_clock::now();
    const RadiosityMesh m = mesher::build_mesh(scene, ctx);
    Run r{std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
          m.element_count(), m.discontinuities.size(), 0.0};
    for (const SurfaceInfo& s : m.surfaces)
        r.hidden += s.hidden_front_m2 + s.hidden_back_m2;
    return r;
}

void report(const std::string& name, Scene scene) {
    const Run with = mesh(scene);
    scene.mesher.discontinuity.enabled = false;
    const Run without = mesh(scene);
    std::printf("%-22s %8zu %7.3f %10zu %9zu %8.2f %10zu %8.2f\n", name.c_str(),
                scene.polygons.size(), scene.mesher.max_edge_length, with.elements,
                with.segments, with.seconds, without.elements, without.seconds);
}

} // namespace

int main(int argc, char** argv) {
    const double edge = argc > 1 ? std::stod(argv[1]) : 0.25;
    std::vector<int> sizes;
    for (int i = 2; i < argc; ++i)
        sizes.push_back(std::stoi(argv[i]));
    if (sizes.empty())
        sizes = {1, 2, 4};
    try {
        std::printf("%-22s %8s %7s %10s %9s %8s %10s %8s\n", "scene", "polygons", "edge_m",
                    "elements", "segments", "mesh_s", "no_disc_el", "no_disc_s");
        Scene cornell = load_scene("data/cornell/scene.json");
        report("cornell (scene edge)", cornell);
        cornell.mesher.max_edge_length = 0.02;
        report("cornell", cornell);
        for (int n : sizes)
            report("office " + std::to_string(n) + "x" + std::to_string(n), office(n, edge));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "mesh_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
