// Bakes a scene at several maximum element edge lengths and prints elements, rays, seconds
// per stage and the power balance. Usage: bake_sizes SCENE [EDGE_M ...] (default: the Cornell
// box at 0.10, 0.05 and 0.025 m). See bench/README.md.

#include <cstdio>
#include <string>
#include <vector>

#include "app/pipeline.h"
#include "core/scene_io.h"

int main(int argc, char** argv) {
    using namespace penumbra;
    const std::string path = argc > 1 ? argv[1] : "data/cornell/scene.json";
    std::vector<double> edges;
    for (int i = 2; i < argc; ++i)
        edges.push_back(std::stod(argv[i]));
    if (edges.empty())
        edges = {0.10, 0.05, 0.04};
    try {
        const Scene base = load_scene(path);
        std::printf("%-8s %9s %12s %8s %8s %8s %8s %8s %10s %10s %10s %10s\n", "edge_m", "elements",
                    "rays", "mesh_s", "bvh_s", "solve_s", "render_s", "total_s", "emitted_lm",
                    "absorb_lm", "escape_lm", "imbalance");
        for (double edge : edges) {
            Scene scene = base;
            scene.mesher.max_edge_length = edge;
            Context ctx;
            app::BakeResult r = app::bake(scene, app::BakeOptions{}, ctx);
            double t[5] = {0, 0, 0, 0, 0}, total = 0;
            const char* names[5] = {"mesh", "bvh", "solve", "render", "sensors"};
            for (const auto& st : r.times) {
                for (int k = 0; k < 5; ++k)
                    if (st.stage == names[k])
                        t[k] = st.seconds;
                total += st.seconds;
            }
            const auto& pb = r.stats.power;
            std::printf("%-8.4g %9zu %12llu %8.2f %8.2f %8.2f %8.2f %8.2f %10.4g %10.4g %10.4g "
                        "%10.2e\n",
                        edge, r.mesh.element_count(), (unsigned long long)r.rays, t[0], t[1], t[2],
                        t[3], total, to_photometric(pb.emitted), to_photometric(pb.absorbed),
                        to_photometric(pb.escaped), pb.relative_imbalance());
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bake_sizes: %s\n", e.what());
        return 1;
    }
    return 0;
}
