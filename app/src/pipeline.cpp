#include "app/pipeline.h"

#include "memory_checks.h"
#include "outputs.h"

#include <algorithm>
#include <chrono>
#include <filesystem>

#include "core/error.h"
#include "core/files.h"
#include "mesher/mesher.h"
#include "raytrace/raytrace.h"
#include "viewer/view.h"
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

raytrace::RenderOptions default_render_options(const Scene& scene) {
    raytrace::RenderOptions options;
    options.spp = scene.camera ? scene.camera->samples_per_pixel : options.spp;
    const bool lobes = std::any_of(scene.materials.begin(), scene.materials.end(),
                                   [](const Material& m) { return m.lobe.has_value(); });
    options.gather = lobes ? raytrace::GatherMode::final_gather : raytrace::GatherMode::radiosity;
    options.irradiance_cache = scene.render.irradiance_cache;
    return options;
}

BakeResult bake(const Scene& scene, const BakeOptions& options, const Context& ctx) {
    BakeResult result;
    if (options.render)
        check_render_memory(scene, ctx); // before the solve, which would take long
    {
        StageTimer t(result.times, "mesh");
        result.mesh = mesher::build_mesh(scene, ctx);
    }
    std::optional<raytrace::EmbreeScene> rt;
    {
        StageTimer t(result.times, "bvh");
        rt.emplace(result.mesh);
    }
    if (options.solve) {
        StageTimer t(result.times, "solve");
        std::optional<viewer::SeriesWriter> series;
        solver::SolveObserver observer;
        if (options.series_every_shots > 0) {
            series.emplace(options.series_dir, scene);
            observer.every_shots = options.series_every_shots;
            observer.on_pass = [&](const Solution& snapshot, std::int64_t shots, double, bool) {
                series->add(result.mesh, snapshot, shots);
            };
        }
        // Light that reaches diffuse surfaces through specular ones (docs/rendering.md): the
        // sources' (L S+ D) from caustic photons; the diffuse surfaces' (D S+ D) traced by
        // the solve once it has a guess of their exitance.
        SpecularLight specular;
        specular.irradiance = raytrace::caustic_irradiance(
            raytrace::shoot_caustic_photons(*rt, scene, ctx), result.mesh);
        if (!specular.irradiance.empty())
            specular.trace_transfers = [&](std::span<const Rgb> exitance) {
                return raytrace::specular_transfers(*rt, scene, exitance, ctx);
            };
        solver::SolveResult solved =
            solver::solve(scene, result.mesh, *rt, ctx, &result.stats, series ? &observer : nullptr,
                          options.reuse, &specular);
        result.solution = std::move(solved.solution);
        if (options.keep_state)
            result.solver_state = std::move(solved.state);
        if (solved.refined_mesh) {
            // The solution lives on the leaf mesh: trace that from now on.
            result.rays += rt->rays_traced();
            rt.reset();
            if (options.keep_input_mesh)
                result.input_mesh = std::move(result.mesh);
            result.mesh = std::move(*solved.refined_mesh);
            rt.emplace(result.mesh);
        }
        if (series) {
            // The last step is the final solution, on the mesh it lives on.
            if (solved.refined_mesh)
                series->add(result.mesh, result.solution, series->last_shots());
            result.series_dir = options.series_dir;
            result.series_steps = series->step_count();
        }
    }
    if (options.solve && !scene.sensors.empty()) {
        StageTimer t(result.times, "sensors");
        result.sensors = solver::evaluate_sensors(scene, result.mesh, result.solution, *rt, ctx);
    }
    if (options.render && scene.camera) {
        StageTimer t(result.times, "render");
        result.render_options = options.render_options.value_or(default_render_options(scene));
        const std::uint64_t before = rt->rays_traced();
        result.render = raytrace::render_final_gather(*rt, scene, result.solution, *scene.camera,
                                                      result.render_options, ctx);
        result.render_rays = rt->rays_traced() - before;
    }
    result.rays += rt->rays_traced();
    return result;
}

void write_outputs(const std::string& dir, const Scene& scene, const BakeResult& result,
                   bool save_state) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec)
        throw ConfigError(fmt::format("cannot create output folder '{}': {}", dir, ec.message()));
    const OutputTarget target{scene, result, dir, save_state};
    // Temporary files of a bake that was killed before it could remove them.
    std::vector<std::string> names;
    for (const OutputWriter& writer : bake_writers()) {
        names.insert(names.end(), writer.files.begin(), writer.files.end());
        if (writer.scene_files)
            for (const std::string& name : writer.scene_files(target))
                names.push_back(name);
    }
    remove_stale_temp_files(dir, names);
    // Files of an earlier bake that this one does not write would mix two bakes in the viewer.
    for (const OutputWriter& writer : bake_writers()) {
        if (writer.wanted(target))
            writer.write(target);
        else
            remove_output(writer, target);
    }
}

void view(const ViewRequest& request, const Context& ctx) {
    viewer::ViewOptions options;
    options.input = request.input;
    options.png = request.png;
    if (!request.size.empty())
        viewer::parse_image_size(request.size, options.width, options.height);
    options.array = request.array;
    options.log_scale = request.log_scale;
    options.edges = request.edges;
    options.sensors = request.sensors;
    options.discontinuities = request.discontinuities;
    options.step = request.step;
    for (std::size_t start = 0; start < request.script.size();) {
        std::size_t end = std::min(request.script.find(',', start), request.script.size());
        if (end > start)
            options.script.push_back(request.script.substr(start, end - start));
        start = end + 1;
    }
    viewer::view(options, ctx);
}

std::string view_controls_help() {
    return viewer::view_controls_help();
}

} // namespace penumbra::app
