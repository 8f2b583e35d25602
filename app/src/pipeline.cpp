#include "app/pipeline.h"

#include <chrono>
#include <filesystem>

#include "core/error.h"
#include "core/files.h"
#include "mesher/mesher.h"
#include "raytrace/raytrace.h"
#include "viewer/vtk_output.h"

namespace penumbra::app {

namespace {

class StageTimer {
public:
    StageTimer(std::vector<StageTime>& times, std::string stage)
        : times_(times), stage_(std::move(stage)), start_(std::chrono::steady_clock::now()) {}
    ~StageTimer() {
        auto dt = std::chrono::steady_clock::now() - start_;
        times_.push_back({stage_, std::chrono::duration<double>(dt).count()});
    }

private:
    std::vector<StageTime>& times_;
    std::string stage_;
    std::chrono::steady_clock::time_point start_;
};

} // namespace

BakeResult bake(const Scene& scene, const BakeOptions& options, const Context& ctx) {
    BakeResult result;
    {
        StageTimer t(result.times, "mesh");
        result.mesh = mesher::build_mesh(scene, ctx);
    }
    std::optional<raytrace::EmbreeScene> rt;
    {
        StageTimer t(result.times, "bvh");
        rt.emplace(result.mesh);
    }
    {
        StageTimer t(result.times, "solve");
        result.solution = solver::solve_shooting(scene, result.mesh, *rt, ctx, &result.stats);
    }
    if (!scene.sensors.empty()) {
        StageTimer t(result.times, "sensors");
        result.sensors = solver::evaluate_sensors(scene, result.mesh, result.solution, *rt, ctx);
    }
    if (options.render && scene.camera) {
        StageTimer t(result.times, "render");
        result.render = raytrace::render_solution(*rt, result.solution, *scene.camera, ctx);
    }
    result.rays = rt->rays_traced();
    return result;
}

void write_outputs(const std::string& dir, const Scene& scene, const BakeResult& result) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec)
        throw ConfigError(fmt::format("cannot create output folder '{}': {}", dir, ec.message()));
    auto path = [&](const char* name) { return (fs::path(dir) / name).string(); };
    viewer::write_vtu(path("mesh.vtu"), scene, result.mesh, result.solution);
    if (result.render) {
        write_exr(path("render.exr"), *result.render);
        double exposure = scene.camera->exposure > 0 ? scene.camera->exposure
                                                     : auto_exposure(*result.render);
        write_png(path("render.png"), *result.render, exposure);
    }
    if (!scene.sensors.empty())
        write_text_file(path("sensors.csv"), sensors_csv(scene, result));
    write_text_file(path("summary.json"), summary_json(scene, result));
}

} // namespace penumbra::app
