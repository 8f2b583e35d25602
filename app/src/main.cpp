// penumbra: the command-line interface. Parses flags, builds the context, runs the pipeline
// and maps errors to exit codes; nothing else lives here.

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <new>
#include <optional>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>
#include <unistd.h>

#include "app/annual.h"
#include "app/lightmap.h"
#include "app/pipeline.h"
#include "app/probes.h"
#include "app/serve.h"
#include "cli_checks.h"
#include "core/error.h"
#include "core/files.h"
#include "core/memory.h"
#include "core/scene_io.h"
#include "terminal.h"

namespace {

using namespace penumbra;

enum ExitCode : int {
    k_ok = 0,
    k_unexpected = 1,
    k_input = 2,
    k_config = 3,
    k_external = 4,
    k_internal = 5,
    k_out_of_memory = 6,
    k_cancelled = 130,  // also SIGINT (128 + 2)
    k_terminated = 143, // SIGTERM (128 + 15)
};

/// SIGINT and SIGTERM remove the temporary files of the outputs being written, then end the
/// process with the shell's code for the signal; only async-signal-safe calls.
extern "C" void on_terminating_signal(int signal) {
    remove_temp_files_on_signal();
    ::_exit(signal == SIGINT ? k_cancelled : k_terminated);
}

void install_signal_handlers() {
    struct sigaction action {};
    action.sa_handler = on_terminating_signal;
    sigemptyset(&action.sa_mask);
    for (int signal : {SIGINT, SIGTERM})
        ::sigaction(signal, &action, nullptr);
}

struct CommonFlags {
    int threads = 0;
    std::uint64_t seed = 0;
    bool quiet = false;
    int verbose = 0;
    std::string max_memory; ///< empty: default_memory_limit_bytes()
};

struct BakeFlags {
    std::string scene;
    std::string output = "out";
    double max_edge_m = 0;
    double residual = 0;
    bool no_render = false;
    std::string method;
    double epsilon = 0;
    double min_area_m2 = 0;
    std::string clustering;
    std::string iteration;
    std::string reuse;
    std::string camera; ///< bake and render: a camera of the scene's `cameras`; empty = `camera`
    bool no_state = false;
    std::int64_t series_every_shots = 0;
};

/// `penumbra render`'s own flags; the scene and solver flags are BakeFlags'.
struct RenderFlags {
    BakeFlags scene;
    int spp = 0; ///< 0 = the scene's image.spp
    std::string gather = "final";
    int gather_depth = 0;
    std::optional<int> photons;            ///< unset: the scene's render.caustic_photons
    std::optional<double> photon_radius_m; ///< unset: the scene's render.caustic_radius
    std::optional<int> light_samples;      ///< unset: the scene's render.light_samples
    std::optional<int> gather_rays;        ///< unset: the scene's render.gather_rays
    std::optional<double> edge_tolerance;  ///< unset: the scene's render.edge_tolerance
    std::string solution; ///< an earlier bake's folder (or its solver state) to start from
    std::optional<std::string> irradiance_cache; ///< "on" or "off"; unset: the scene's
};

/// `penumbra annual`'s own flags; the scene and element flags are BakeFlags'.
struct AnnualFlags {
    BakeFlags scene;
    app::AnnualOptions options;
    app::AnnualWriteOptions write;
    std::string heat_map;
    std::string occupancy;
    bool from_illuminance = false;
};

/// `penumbra lightmap`'s own flags; the scene and solver flags are BakeFlags'. Unset: the
/// scene's `lightmap` settings, else the defaults of lightmap::AtlasSettings.
struct LightmapFlags {
    BakeFlags scene;
    std::optional<double> texels_per_metre;
    std::optional<int> atlas_size;
    std::optional<int> padding;
    bool float_exr = false;
    bool directional = false;
    bool no_seam_stitch = false;
    std::optional<int> gather; ///< final-gather paths per texel sample; unset: lightmap.gather
};

Context make_context(const CommonFlags& flags) {
    Context ctx;
    ctx.log = app::make_stderr_log_sink();
    ctx.progress = flags.quiet ? nullptr : app::make_terminal_progress();
    ctx.threads = flags.threads;
    ctx.seed = flags.seed;
    ctx.min_level =
        flags.quiet ? LogLevel::warn : (flags.verbose > 0 ? LogLevel::debug : LogLevel::info);
    // The flag's validator has read it already.
    ctx.max_memory_bytes = flags.max_memory.empty() ? default_memory_limit_bytes()
                                                    : *parse_memory_size(flags.max_memory);
    return ctx;
}

void add_common_flags(CLI::App& cmd, CommonFlags& flags) {
    cmd.add_option("--threads", flags.threads, "worker threads (0 = all cores)")
        ->check(CLI::Range(0, 1024));
    cmd.add_option("--seed", flags.seed, "master seed of all random streams");
    cmd.add_flag("-q,--quiet", flags.quiet, "only warnings and errors, no progress bars");
    cmd.add_flag("-v,--verbose", flags.verbose, "debug messages");
}

/// `--max-memory`, on the commands that solve.
void add_memory_flag(CLI::App& cmd, CommonFlags& flags) {
    cmd.add_option("--max-memory", flags.max_memory,
                   "most memory the stages' estimates may reach, e.g. 4G or 500M (powers of "
                   "1024; 0 = no limit; default 80 % of the machine's or the cgroup's memory)")
        ->check(app::memory_size());
}

/// The scene with the solver and mesher flags of bake and daylight applied.
Scene load_with_overrides(const BakeFlags& flags, SceneLight light = SceneLight::own) {
    Scene scene = load_scene(flags.scene, light);
    if (flags.max_edge_m > 0)
        scene.mesher.max_edge_length = flags.max_edge_m;
    if (flags.residual > 0)
        scene.solver.residual = flags.residual;
    if (!flags.method.empty())
        scene.solver.method = *parse_enum<SolverMethod>(flags.method);
    if (flags.epsilon > 0)
        scene.solver.epsilon = flags.epsilon;
    if (flags.min_area_m2 > 0)
        scene.solver.min_area = flags.min_area_m2;
    if (!flags.clustering.empty())
        scene.solver.clustering = *parse_enum<Clustering>(flags.clustering);
    if (!flags.iteration.empty())
        scene.solver.iteration = *parse_enum<SolverIteration>(flags.iteration);
    if (!flags.camera.empty())
        scene.select_camera(flags.camera);
    return scene;
}

/// The solver state an earlier bake wrote: \p path names its folder or the state file;
/// \p flag names the option for messages.
std::shared_ptr<const solver::HierarchicalState>
read_state(const Scene& scene, const std::string& path, const char* flag) {
    if (scene.solver.method != SolverMethod::hierarchical)
        throw ConfigError(fmt::format("{} needs the hierarchical method, not '{}'", flag,
                                      enum_name(scene.solver.method)));
    namespace fs = std::filesystem;
    const fs::path given(path);
    return solver::read_hierarchical_state(
        fs::is_directory(given) ? (given / app::k_solver_state_file).string() : path);
}

void log_power_balance(const Context& ctx, const std::string& output,
                       const app::BakeResult& result) {
    const auto& pb = result.stats.power;
    ctx.info("wrote {}: {} elements, {} rays, emitted {:.4g} lm, absorbed {:.4g} lm, escaped "
             "{:.4g} lm, unshot {:.4g} lm",
             output, result.mesh.element_count(), result.rays, to_photometric(pb.emitted),
             to_photometric(pb.absorbed), to_photometric(pb.escaped), to_photometric(pb.residual));
}

/// The scene, the output folder and the flags that override the scene's solver settings: the
/// same for bake and daylight.
void add_solve_flags(CLI::App& cmd, BakeFlags& flags) {
    cmd.add_option("scene", flags.scene, "scene file (JSON, docs/scene-format.md)")->required();
    cmd.add_option("-o,--output", flags.output, "output folder (created if missing)");
    cmd.add_option(
           "--max-edge", flags.max_edge_m,
           "element size in metres: edges up to √2 × this (overrides mesher.max_edge_length)")
        ->check(app::positive_number());
    cmd.add_option("--residual", flags.residual,
                   "stop when unshot power / emitted power falls below this")
        ->check(app::number_in(1e-12, 0.999999));
    cmd.add_option("--method", flags.method, "solver method (overrides solver.method)")
        ->check(CLI::IsMember(enum_names<SolverMethod>()));
    cmd.add_option("--epsilon", flags.epsilon,
                   "hierarchical: refinement threshold, relative to the brightest source's "
                   "exitance (overrides solver.epsilon)")
        ->check(app::number_in(1e-12, 1.0));
    cmd.add_option("--min-area", flags.min_area_m2,
                   "hierarchical: smallest element area in m² (overrides solver.min_area)")
        ->check(app::positive_number());
    cmd.add_option("--clustering", flags.clustering,
                   "hierarchical: start from a cluster tree (on), from all pairs of mesh "
                   "elements (off), or cluster above 3 000 elements (auto; overrides "
                   "solver.clustering)")
        ->check(CLI::IsMember(enum_names<Clustering>()));
    cmd.add_option("--iteration", flags.iteration,
                   "hierarchical: how each solve between refinements iterates: jacobi, "
                   "gauss_seidel (blocks of 32 roots) or shooting (progressive, on the "
                   "hierarchy; overrides solver.iteration)")
        ->check(CLI::IsMember(enum_names<SolverIteration>()));
}

/// The lightmap options of \p scene's `lightmap` key, with the flags' overrides.
app::LightmapOptions lightmap_options(const Scene& scene, const LightmapFlags& flags) {
    app::LightmapOptions options;
    if (scene.lightmap)
        options.atlas.size = scene.lightmap->atlas_size;
    options.atlas.texels_per_metre =
        flags.texels_per_metre.value_or(options.atlas.texels_per_metre);
    options.atlas.size = flags.atlas_size.value_or(options.atlas.size);
    options.atlas.padding = flags.padding.value_or(options.atlas.padding);
    options.exr = flags.float_exr ? ExrPixels::float32 : ExrPixels::half;
    options.directional = flags.directional || (scene.lightmap && scene.lightmap->directional);
    options.stitch_seams = !flags.no_seam_stitch;
    options.gather_samples = flags.gather.value_or(scene.lightmap ? scene.lightmap->gather : 0);
    return options;
}

void log_lightmaps(const Context& ctx, const std::string& output, const app::LightmapResult& r) {
    std::string coverage;
    for (double c : r.layout.coverage)
        coverage += fmt::format("{}{:.4f}", coverage.empty() ? "" : ", ", c);
    ctx.info("wrote lightmaps to {}: {} charts in {} atlas(es) of {}², coverage {}; {} texels, "
             "{} of them hidden; {} rays",
             output, r.charts.charts.size(), r.atlases.size(), r.layout.size, coverage,
             r.counts.texels, r.counts.hidden_texels, r.rays);
    ctx.info("stitched {} seam edges ({} samples, {} texels): seam error mean {:.4g}, max "
             "{:.4g} W/m² before; mean {:.4g}, max {:.4g} W/m² after",
             r.seams.edges, r.seams.samples, r.seams.texels, r.seams.before.mean,
             r.seams.before.max, r.seams.after.mean, r.seams.after.max);
}

// The scene's `probes`, when it has them, from \p baked into \p output.
void write_scene_probes(const Context& ctx, const Scene& scene, const app::BakeResult& baked,
                        const std::string& output) {
    if (!scene.probes)
        return;
    const app::ProbeResult probes = app::compute_probes(scene, *scene.probes, baked, ctx);
    app::write_probes(output, scene, probes);
    ctx.info("wrote {} light probes to {} (probes.json, probes.vtp): {} rays each, {:.2f} s",
             probes.probes.size(), output, probes.rays_per_probe, probes.seconds);
}

int run_bake(const BakeFlags& flags, const CommonFlags& common) {
    Context ctx = make_context(common);
    Scene scene = load_with_overrides(flags);
    check_output_dir(flags.output);
    std::shared_ptr<const solver::HierarchicalState> previous;
    if (!flags.reuse.empty())
        previous = read_state(scene, flags.reuse, "--reuse");
    // The scene's `lightmap` key asks for lightmaps too; its charts and atlases first, so
    // that bad settings fail before the solve.
    const app::LightmapOptions lightmap = lightmap_options(scene, LightmapFlags{});
    std::optional<app::LightmapResult> lightmaps;
    if (scene.lightmap)
        lightmaps = app::plan_lightmaps(scene, lightmap, ctx);
    app::BakeOptions options;
    options.reuse = previous.get();
    options.render = !flags.no_render;
    options.series_every_shots = flags.series_every_shots;
    options.series_dir = flags.output;
    options.keep_state = !flags.no_state;
    options.keep_input_mesh = scene.lightmap.has_value();
    app::BakeResult result = app::bake(scene, options, ctx);
    app::write_outputs(flags.output, scene, result, !flags.no_state);
    log_power_balance(ctx, flags.output, result);
    if (lightmaps) {
        app::fill_lightmaps(scene, result, *lightmaps, ctx);
        app::write_lightmaps(flags.output, scene, lightmap, *lightmaps);
        log_lightmaps(ctx, flags.output, *lightmaps);
    }
    write_scene_probes(ctx, scene, result, flags.output);
    return k_ok;
}

// Mesh, solve and the final gather: render.exr, render.png and render.json only.
int run_render(const RenderFlags& flags, const CommonFlags& common) {
    Context ctx = make_context(common);
    Scene scene = load_with_overrides(flags.scene);
    if (!scene.camera)
        throw InputError(flags.scene.scene, "camera",
                         "the scene has no camera, which `penumbra render` needs");
    check_output_dir(flags.scene.output);
    scene.render.caustic_photons = flags.photons.value_or(scene.render.caustic_photons);
    if (flags.photon_radius_m)
        scene.render.caustic_radius_m = flags.photon_radius_m;
    scene.render.light_samples = flags.light_samples.value_or(scene.render.light_samples);
    scene.render.gather_rays = flags.gather_rays.value_or(scene.render.gather_rays);
    scene.render.edge_tolerance = flags.edge_tolerance.value_or(scene.render.edge_tolerance);
    raytrace::RenderOptions render;
    render.spp = flags.spp > 0 ? flags.spp : scene.camera->samples_per_pixel;
    render.gather = *parse_enum<raytrace::GatherMode>(flags.gather);
    render.gather_depth = flags.gather_depth;
    render.irradiance_cache = scene.render.irradiance_cache;
    if (flags.irradiance_cache)
        render.irradiance_cache =
            *flags.irradiance_cache == "on"
                ? std::optional(scene.render.irradiance_cache.value_or(IrradianceCacheSettings{}))
                : std::nullopt;
    const bool solves = render.gather != raytrace::GatherMode::none;
    std::shared_ptr<const solver::HierarchicalState> previous;
    if (!flags.solution.empty() && !solves)
        ctx.warn("--solution {} is not read: --gather none traces its paths without a solution",
                 flags.solution);
    else if (!flags.solution.empty())
        previous = read_state(scene, flags.solution, "--solution");
    app::BakeOptions options;
    options.reuse = previous.get();
    options.render_options = render;
    options.keep_state = false;
    options.solve = solves;
    app::BakeResult result = app::bake(scene, options, ctx);
    app::write_render_outputs(flags.scene.output, scene, result);
    const double seconds = result.times.empty() ? 0.0 : result.times.back().seconds;
    ctx.info("wrote {}: {}x{} pixels, {} samples, {} gather, {:.2f} s render, {:.3g} rays/s",
             flags.scene.output, result.render->width, result.render->height, render.spp,
             flags.gather, seconds, seconds > 0 ? double(result.render_rays) / seconds : 0.0);
    return k_ok;
}

// The bake pipeline without render, solver state or series: mesh.vtu, the sensors and grids.
int run_daylight(const BakeFlags& flags, const CommonFlags& common) {
    Context ctx = make_context(common);
    Scene scene = load_with_overrides(flags);
    if (!scene.sky && !scene.sun)
        throw InputError(flags.scene, "",
                         "the scene has no sky or sun, which `penumbra daylight` needs (use "
                         "`penumbra bake` for a scene lit by lamps)");
    check_output_dir(flags.output);
    app::BakeOptions options;
    options.render = false;
    options.keep_state = false;
    app::BakeResult result = app::bake(scene, options, ctx);
    app::write_outputs(flags.output, scene, result, false);
    log_power_balance(ctx, flags.output, result);
    return k_ok;
}

// The bake pipeline without render or solver state, then the lightmaps: lightmap_N.exr/png and
// lightmaps.json. The charts and atlases come first: bad settings fail before the solve.
int run_lightmap(const LightmapFlags& flags, const CommonFlags& common) {
    Context ctx = make_context(common);
    const Scene scene = load_with_overrides(flags.scene);
    const app::LightmapOptions options = lightmap_options(scene, flags);
    app::LightmapResult result = app::plan_lightmaps(scene, options, ctx);
    check_output_dir(flags.scene.output);
    // Re-bake: the stored hierarchy and links, the new reflectances and emissions.
    std::shared_ptr<const solver::HierarchicalState> previous;
    if (!flags.scene.reuse.empty())
        previous = read_state(scene, flags.scene.reuse, "--reuse");
    app::BakeOptions bake_options = app::lightmap_bake_options();
    bake_options.reuse = previous.get();
    const app::BakeResult baked = app::bake(scene, bake_options, ctx);
    app::fill_lightmaps(scene, baked, result, ctx);
    app::write_lightmaps(flags.scene.output, scene, options, result);
    log_lightmaps(ctx, flags.scene.output, result);
    write_scene_probes(ctx, scene, baked, flags.scene.output);
    return k_ok;
}

// "8-18": occupied from 8:00 to 18:00 (EPW hours 9 to 18).
annual::Occupancy parse_occupancy(const std::string& text) {
    annual::Occupancy o;
    char dash = 0;
    std::istringstream in(text);
    if (!(in >> o.start_hour >> dash >> o.end_hour) || dash != '-' || !in.eof() ||
        o.start_hour < 0 || o.end_hour > 24 || o.start_hour >= o.end_hour)
        throw ConfigError(fmt::format(
            "--occupancy '{}': give START-END in whole hours, 0 <= START < END <= 24", text));
    return o;
}

int run_annual(AnnualFlags& flags, const CommonFlags& common) {
    Context ctx = make_context(common);
    const Scene scene = load_with_overrides(flags.scene, SceneLight::weather);
    check_output_dir(flags.scene.output);
    flags.write.directory = flags.scene.output;
    if (!flags.heat_map.empty())
        flags.write.heat_map_sensor = flags.heat_map;
    if (!flags.occupancy.empty())
        flags.options.occupancy = parse_occupancy(flags.occupancy);
    if (flags.from_illuminance)
        flags.options.sky.input = annual::WeatherInput::illuminance;
    app::check_annual_run(scene, flags.options, flags.write);
    const app::AnnualResult result = app::run_annual(scene, flags.options, ctx);
    app::write_annual(scene, result, flags.write, ctx);
    ctx.info("wrote {}: {} sensors, {} hours ({} occupied), {} sky patches and {} sun bins",
             flags.write.directory, scene.sensors.size(), result.weather.hours.size(),
             std::count(result.occupied.begin(), result.occupied.end(), true), result.patches,
             result.sun_bins);
    for (const auto& [stage, seconds] : result.seconds)
        ctx.info("  {}: {:.1f} s", stage, seconds);
    for (const app::BlindsGroup& group : result.blinds)
        ctx.info("blinds of {}: closed in {} of the year's hours",
                 group.name.empty() ? "the sensors of no grid" : "grid " + group.name,
                 std::count(group.closed.begin(), group.closed.end(), true));
    for (std::size_t g = 0; g < scene.grids.size(); ++g)
        ctx.info("grid {}: sDA {:.1f} %, ASE {:.1f} %", scene.grids[g].name,
                 100 * result.grids[g].spatial_daylight_autonomy,
                 100 * result.grids[g].annual_sunlight_exposure);
    return k_ok;
}

int run_view(const app::ViewRequest& request, const CommonFlags& common) {
    Context ctx = make_context(common);
    ctx.progress = nullptr;
    app::view(request, ctx);
    return k_ok;
}

// Serves a bake and the client page on localhost until stopped (Ctrl-C).
int run_serve(const app::ServeOptions& options, const CommonFlags& common) {
    const Context ctx = make_context(common);
    app::serve(options, ctx, [&](int port) {
        std::printf("serving %s at http://127.0.0.1:%d/ (Ctrl-C stops)\n",
                    options.roots.bake.string().c_str(), port);
        std::fflush(stdout);
    });
    return k_ok;
}

int run_validate(const std::string& path, const CommonFlags& common) {
    Context ctx = make_context(common);
    Scene scene = load_scene(path);
    ctx.info("{}: {} polygons, {} materials, {} point lights{}, {} sensors{}", path,
             scene.polygons.size(), scene.materials.size(), scene.point_lights.size(),
             scene.sun ? ", sun" : "", scene.sensors.size(), scene.camera ? ", camera" : "");
    return k_ok;
}

int report(const char* kind, const std::string& message, int code) {
    std::fprintf(stderr, "penumbra: %s%s\n", kind, message.c_str());
    return code;
}

} // namespace

int main(int argc, char** argv) {
    install_signal_handlers();
    CLI::App cli{"Penumbra: radiosity-first lighting (mesh, solve, render, sensors, view)"};
    cli.require_subcommand(1);
    CommonFlags common;
    BakeFlags bake;
    auto* bake_cmd = cli.add_subcommand("bake", "mesh, solve and write every output of a scene");
    add_solve_flags(*bake_cmd, bake);
    bake_cmd->add_flag("--no-render", bake.no_render, "skip the camera render");
    bake_cmd->add_option("--camera", bake.camera,
                         "render the camera of the scene's 'cameras' with this name");
    bake_cmd->add_option("--reuse", bake.reuse,
                         "hierarchical: re-solve from an earlier bake's folder (or its "
                         "solver_state.bin): same geometry, new reflectances or emissions; keeps "
                         "its links and refines them where the new radiosities need it");
    bake_cmd->add_flag(
        "--no-state", bake.no_state,
        "hierarchical: do not write solver_state.bin (it holds every link), and free "
        "the links once the solve is done");
    bake_cmd
        ->add_option("--series", bake.series_every_shots,
                     "write the solution every K shots as series/mesh_*.vtu + series.pvd")
        ->check(app::positive_number());
    add_memory_flag(*bake_cmd, common);
    add_common_flags(*bake_cmd, common);
    RenderFlags render;
    auto* render_cmd = cli.add_subcommand(
        "render", "mesh, solve and render the scene's camera with the final gather: "
                  "render.exr, render.png, render.json");
    add_solve_flags(*render_cmd, render.scene);
    render_cmd
        ->add_option("--spp", render.spp, "samples per pixel (default: the scene's image.spp)")
        ->check(CLI::Range(1, 1 << 20));
    render_cmd
        ->add_option("--gather", render.gather,
                     "final: read the radiosity one diffuse bounce away (default); none: a pure "
                     "path tracer (no solve); radiosity: the solution's interpolated view")
        ->check(CLI::IsMember(enum_names<raytrace::GatherMode>()));
    render_cmd
        ->add_option("--gather-depth", render.gather_depth,
                     "final: diffuse bounces traced before the solution is read (default 0)")
        ->check(CLI::Range(0, 64));
    render_cmd
        ->add_option("--irradiance-cache", render.irradiance_cache,
                     "final: on = indirect light at Lambertian camera hits from Ward's "
                     "irradiance cache (default: the scene's render.irradiance_cache, else off)")
        ->check(CLI::IsMember({"on", "off"}));
    add_memory_flag(*render_cmd, common);
    render_cmd
        ->add_option("--photons", render.photons,
                     "final: caustic photons to store; 0 = no caustics (default: the scene's "
                     "render.caustic_photons, else 100000)")
        ->check(CLI::Range(0, 100'000'000));
    render_cmd
        ->add_option("--photon-radius", render.photon_radius_m,
                     "final: a fixed radius of the caustic density estimate, metres (default: "
                     "the 64 nearest photons')")
        ->check(app::positive_number());
    render_cmd
        ->add_option("--light-samples", render.light_samples,
                     "light samples at each camera sample's first diffuse or glossy hit "
                     "(default: the scene's render.light_samples)")
        ->check(CLI::Range(1, 1024));
    render_cmd
        ->add_option("--gather-rays", render.gather_rays,
                     "BSDF samples (gather rays) there, rounded up to a square (default: the "
                     "scene's render.gather_rays)")
        ->check(CLI::Range(1, 1024));
    render_cmd
        ->add_option("--edge-tolerance", render.edge_tolerance,
                     "edge refinement's tolerance, W/(sr·m²); 0 = none (default: the scene's "
                     "render.edge_tolerance)")
        ->check(CLI::Range(0.0, 1e9));
    render_cmd->add_option("--camera", render.scene.camera,
                           "render the camera of the scene's 'cameras' with this name");
    render_cmd->add_option(
        "--solution", render.solution,
        "start from an earlier bake's solution (its folder or "
        "solver_state.bin), as bake --reuse: its hierarchy and links are "
        "kept and the sweeps start from its radiosities; not read with --gather none");
    add_common_flags(*render_cmd, common);
    BakeFlags daylight;
    auto* daylight_cmd = cli.add_subcommand(
        "daylight", "mesh, solve and write the daylight results of a scene with a sky or sun: "
                    "sensors.csv, the grids' statistics, plans and points, mesh.vtu");
    add_solve_flags(*daylight_cmd, daylight);
    add_memory_flag(*daylight_cmd, common);
    add_common_flags(*daylight_cmd, common);
    AnnualFlags annual;
    auto* annual_cmd = cli.add_subcommand(
        "annual", "a year of hourly illuminance at the scene's sensors from an EPW weather file "
                  "(daylight coefficients) and the climate-based metrics: DA, UDI, sDA, ASE");
    annual_cmd->add_option("scene", annual.scene.scene, "scene file (JSON, docs/scene-format.md)")
        ->required();
    annual_cmd->add_option("-o,--output", annual.scene.output,
                           "output folder (created if missing)");
    annual_cmd->add_option("--weather", annual.options.weather_file, "EPW weather file")
        ->required();
    annual_cmd
        ->add_option("--patches", annual.options.subdivision,
                     "sky patches: 1 = Tregenza's 145 and the ground (default), 2–4 = Reinhart's "
                     "subdivisions (577, 1297, 2305 and the ground)")
        ->check(CLI::Range(1, 4));
    annual_cmd
        ->add_option("--sun-bins", annual.options.sun_subdivision,
                     "the suns' reflected light is solved once per Reinhart patch of this "
                     "subdivision that the year's suns fall in (default 2: about 6° across)")
        ->check(CLI::Range(1, 8));
    annual_cmd->add_option("--occupancy", annual.occupancy,
                           "occupied hours START-END of every day, local standard time "
                           "(default 8-18: EPW hours 9 to 18)");
    annual_cmd
        ->add_option("--ground-reflectance", annual.options.sky.ground_reflectance,
                     "the ground's reflectance (default 0.2)")
        ->check(CLI::Range(0.0, 1.0));
    annual_cmd->add_flag("--from-illuminance", annual.from_illuminance,
                         "build each hour's sky from the file's illuminance fields rather than "
                         "its irradiance with Perez's efficacies");
    annual_cmd->add_flag("--hourly", annual.write.hourly,
                         "also write every hour's illuminance (hourly_illuminance.f32 + .json)");
    annual_cmd->add_option("--heat-map", annual.heat_map,
                           "the sensor of the hour × day heat map (default: the first grid's "
                           "first point)");
    annual_cmd->add_flag("--blinds", annual.options.blinds,
                         "LM-83's blinds rule: per grid, the hours in which more than 2 % of its "
                         "points get over 1000 lx of direct sun take the illuminance of the "
                         "scene's `annual.blinds` state (ASE stays that of the open state)");
    annual_cmd->add_flag("--mesh", annual.options.mesh,
                         "also the metrics on every element of the mesh (annual_mesh.vtu); "
                         "memory: elements × (patches + 2 × sun bins) floats");
    annual_cmd
        ->add_option("--max-edge", annual.scene.max_edge_m,
                     "element size in metres (overrides mesher.max_edge_length)")
        ->check(app::positive_number());
    annual_cmd
        ->add_option("--epsilon", annual.scene.epsilon,
                     "refinement threshold of the coefficients' links (overrides solver.epsilon)")
        ->check(app::number_in(1e-12, 1.0));
    add_memory_flag(*annual_cmd, common);
    add_common_flags(*annual_cmd, common);
    LightmapFlags lightmap;
    auto* lightmap_cmd = cli.add_subcommand(
        "lightmap", "mesh and solve a scene, then bake its lightmaps: per atlas lightmap_N.exr "
                    "(irradiance, W/m²) and lightmap_N.png; scene.gltf (MOZ_lightmap), "
                    "preview.exr/.png and lightmaps.json");
    add_solve_flags(*lightmap_cmd, lightmap.scene);
    lightmap_cmd
        ->add_option("--texels-per-metre", lightmap.texels_per_metre,
                     "texel density on the surfaces (default 20)")
        ->check(app::positive_number());
    lightmap_cmd
        ->add_option("--atlas", lightmap.atlas_size,
                     "texels along each side of an atlas (default: the scene's lightmap.atlas, "
                     "else 1024)")
        ->check(CLI::Range(1, 8192));
    lightmap_cmd
        ->add_option("--padding", lightmap.padding,
                     "free texels around each chart, filled by dilation (default 2)")
        ->check(CLI::Range(0, 4096));
    lightmap_cmd->add_flag("--float", lightmap.float_exr,
                           "32-bit float EXR channels (default: half)");
    lightmap_cmd->add_flag("--directional", lightmap.directional,
                           "also the L1 spherical harmonics of the incident radiance: "
                           "lightmap_N_L00/L1m1/L10/L11.exr (default: the scene's "
                           "lightmap.directional)");
    lightmap_cmd
        ->add_option("--gather", lightmap.gather,
                     "fill each texel sample with N final-gather paths (the render's) instead "
                     "of direct light + the solution's indirect light; 0 = off (default: the "
                     "scene's lightmap.gather, else 0)")
        ->check(CLI::Range(0, 1 << 16));
    lightmap_cmd->add_option("--reuse", lightmap.scene.reuse,
                             "hierarchical: re-bake from an earlier bake's folder (or its "
                             "solver_state.bin) after a change of light intensities or "
                             "reflectances: its links are kept, no new form factors");
    lightmap_cmd->add_flag("--no-seam-stitch", lightmap.no_seam_stitch,
                           "leave the seams between charts as filled (the error is still "
                           "reported)");
    add_memory_flag(*lightmap_cmd, common);
    add_common_flags(*lightmap_cmd, common);
    std::string validate_scene_path;
    auto* validate_cmd = cli.add_subcommand("validate", "load and check a scene, write nothing");
    validate_cmd->add_option("scene", validate_scene_path, "scene file")->required();
    add_common_flags(*validate_cmd, common);
    app::ServeOptions serve{{PENUMBRA_CLIENT_DIR, {}}, 8000};
    auto* serve_cmd = cli.add_subcommand(
        "serve", "show a lightmap bake in the browser: serves OUT and the client page "
                 "(client/) on http://127.0.0.1:PORT/ until stopped");
    serve_cmd->add_option("output", serve.roots.bake, "a `penumbra lightmap` output folder")
        ->required();
    serve_cmd->add_option("--port", serve.port, "TCP port on 127.0.0.1 (default 8000; 0: any free)")
        ->check(CLI::Range(0, 65535));
    serve_cmd->add_option("--client", serve.roots.client,
                          "the client page's folder (default: this build's source client/)");
    serve_cmd->add_flag("-q,--quiet", common.quiet, "only warnings and errors");
    serve_cmd->add_flag("-v,--verbose", common.verbose, "debug messages: every request");
    app::ViewRequest view;
    auto* view_cmd = cli.add_subcommand(
        "view", "show a bake's mesh.vtu or series.pvd in a window, or render it to a PNG");
    view_cmd
        ->add_option("input", view.input,
                     "output folder (series.pvd, else mesh.vtu) or .vtu/.vtp/.pvd file")
        ->required();
    view_cmd->add_option("--png", view.png, "render off-screen to this PNG file, no window");
    view_cmd->add_option("--size", view.size, "picture size WxH (default: the scene camera's)");
    view_cmd->add_option("--array", view.array,
                         "array to show (default true_colour; a/A cycles in the window)");
    view_cmd->add_flag("--log", view.log_scale, "logarithmic colour scale");
    view_cmd->add_flag("--edges", view.edges, "draw element edges");
    view_cmd->add_flag("--sensors", view.sensors, "draw the sensor points (sensors.vtp)");
    view_cmd->add_flag("--discontinuities", view.discontinuities,
                       "draw the shadow boundaries (discontinuities.vtp)");
    view_cmd->add_option("--step", view.step, "series step to show, from 0 (default: the last)");
    view_cmd->add_option("--script", view.script, "scripted events (tests)")->group("");
    view_cmd->footer("Window controls:\n" + app::view_controls_help());
    view_cmd->add_flag("-q,--quiet", common.quiet, "only warnings and errors");
    view_cmd->add_flag("-v,--verbose", common.verbose, "debug messages");
    try {
        cli.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) // --help, --version
            return cli.exit(e);
        std::fprintf(stderr, "%s\n", app::cli_error_line(e).c_str());
        return k_config;
    }
    try {
        if (*bake_cmd)
            return run_bake(bake, common);
        if (*render_cmd)
            return run_render(render, common);
        if (*daylight_cmd)
            return run_daylight(daylight, common);
        if (*annual_cmd)
            return run_annual(annual, common);
        if (*lightmap_cmd)
            return run_lightmap(lightmap, common);
        if (*view_cmd)
            return run_view(view, common);
        if (*serve_cmd)
            return run_serve(serve, common);
        return run_validate(validate_scene_path, common);
    } catch (const InputError& e) {
        return report("error: ", e.what(), k_input);
    } catch (const ConfigError& e) {
        return report("error: ", e.what(), k_config);
    } catch (const ExternalError& e) {
        return report("error: ", e.what(), k_external);
    } catch (const InternalError& e) {
        return report("internal error (please report): ", e.what(), k_internal);
    } catch (const Cancelled&) {
        return report("", "cancelled", k_cancelled);
    } catch (const std::bad_alloc&) {
        return report("error: ", "out of memory; try a larger --max-edge", k_out_of_memory);
    } catch (const std::exception& e) {
        return report("error: ", e.what(), k_unexpected);
    } catch (...) {
        return report("error: ", "unknown exception", k_unexpected);
    }
}
