// Meshing time and element counts (issue #5): the Cornell box and generated open-plan office
// floors of n × n offices (office_scene.h: partitions with doors, two desks on legs and a
// cabinet each, a ceiling panel light per office, no windows; floor and ceiling are single
// polygons spanning the floor plate, as generated models often have). Each scene is meshed
// with and without discontinuity meshing. Usage: mesh_bench [EDGE_M] [N ...] (default 0.25 m;
// 1, 2 and 4 → 1, 4 and 16 offices).

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "core/scene_io.h"
#include "mesher/mesher.h"
#include "office_scene.h"

namespace {

using namespace penumbra;

Scene office(int n, double edge) {
    bench::OfficeParams params;
    params.rooms_x = params.rooms_y = n;
    params.windows_per_room = 0;
    Scene s = bench::office_floor(params);
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
