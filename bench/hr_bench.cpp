// Hierarchical radiosity at growing scene sizes (issue #4). For each target input-triangle
// count, a generated office floor (office_scene.h, meshed as input: about 1.3 elements per
// input triangle and side) goes through the CLI's stages — mesh, Embree BVH, hierarchical solve,
// output (BVH of the leaf mesh, sensors, mesh.vtu/sensors.csv/summary.json into a temporary folder;
// no render) — in a child process of its own, so that each size's peak RSS (VmHWM) is its own and a
// size that runs too long can be stopped. Then it measures raw occlusion throughput on the same
// BVH: random segments between points on the elements (offset off the surface as the solver
// offsets its quadrature points), traced in 4096-ray batches through the same VisibilityQuery
// (EmbreeScene: rtcOccluded1M over 256-ray streams), on the same threads.
//
// Columns: input triangles, elements (both sides: the hierarchy's roots), leaf-mesh elements
// (leaves made conforming), links, peak RSS, seconds per stage, rays the solve traced, the
// mean rays per visibility call, the solve's rays per second of wall time, the raw rays per
// second, their ratio, the share of the solve's thread time spent inside visibility calls, and
// the power balance: (absorbed + escaped) / emitted − 1 in percent (0 for exact transport).
// The peak RSS is read before the raw measurement; it includes the input mesh and its BVH
// during the output stage, which the CLI has freed by then.
//
// Usage: hr_bench [--sizes 1k,2k,8k,32k] [--max-seconds S] [--threads N] [--epsilon E]
//                 [--clustering auto|on|off] [--offices NXxNY] [--tessellation K]
//                 [--min-area A] [--raw-rays N] [--no-solve] [-v]

#include "app/pipeline.h"
#include "bench_process.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "core/scene_io.h"
#include "mesher/mesher.h"
#include "office_scene.h"
#include "raytrace/raytrace.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

namespace {

using namespace penumbra;
using bench::Clock;
using bench::parse_size;
using bench::peak_rss_mib;
using bench::seconds_since;

struct Options {
    std::vector<std::string> sizes{"1k", "2k", "8k", "32k"};
    double max_seconds = 600;
    int threads = 0;
    double epsilon = 0;
    std::string clustering; ///< empty: the scene's (auto)
    std::string offices;    ///< "NXxNY": this many offices instead of the size's
    int tessellation = 0;   ///< > 0: this tessellation instead of the size's
    /// > 0: solver.min_area (m²) instead of the scene's default ((diagonal / 200)²): a few
    /// offices with the minimum area of a bigger floor refine as one of its offices does.
    double min_area = 0;
    std::int64_t raw_rays = 1'000'000;
    bool no_solve = false;
    bool verbose = false;
    std::string child; ///< internal: run this one size in this process
};

class StderrSink final : public LogSink {
public:
    void write(LogLevel level, std::string_view message) override {
        const char* tag = level >= LogLevel::warn ? "warning: " : "";
        std::fprintf(stderr, "hr_bench: %s%.*s\n", tag, int(message.size()), message.data());
    }
};

/// Forwards to another query and adds up the wall time each thread spends in it.
class TimedVisibility final : public VisibilityQuery {
public:
    explicit TimedVisibility(const VisibilityQuery& inner) : inner_(inner) {}

    void occluded(std::span<const Segment> segments, std::span<std::uint8_t> out) const override {
        const Clock::time_point start = Clock::now();
        inner_.occluded(segments, out);
        Tally& t = tally_.local();
        t.seconds += seconds_since(start);
        ++t.calls;
    }
    void first_hit(std::span<const Segment> segments, std::span<std::int32_t> hit) const override {
        const Clock::time_point start = Clock::now();
        inner_.first_hit(segments, hit);
        Tally& t = tally_.local();
        t.seconds += seconds_since(start);
        ++t.calls;
    }
    std::uint64_t rays_traced() const override { return inner_.rays_traced(); }

    /// Thread-seconds spent in occluded() and the number of calls, over all threads.
    std::pair<double, std::uint64_t> totals() const {
        std::pair<double, std::uint64_t> sum{0.0, 0};
        for (const Tally& t : tally_) {
            sum.first += t.seconds;
            sum.second += t.calls;
        }
        return sum;
    }

private:
    struct Tally {
        double seconds = 0;
        std::uint64_t calls = 0;
    };
    const VisibilityQuery& inner_;
    mutable tbb::enumerable_thread_specific<Tally> tally_;
};

/// Segments between uniformly sampled points of the elements (by area, either side), each
/// point moved off its surface by 1e-5 × the scene diagonal, as the solver does.
std::vector<Segment> random_segments(const RadiosityMesh& mesh, std::size_t count) {
    std::vector<double> cdf(mesh.element_count());
    double total = 0;
    for (std::size_t e = 0; e < cdf.size(); ++e)
        cdf[e] = total += mesh.element_area[e];
    Pcg32 rng(0x6872'6265'6e63'68ULL, 1); // "hrbench": a fixed stream, not a solver stream
    const double offset = 1e-5 * mesh.scene_diagonal;
    auto sample = [&] {
        const double at = rng.next_double() * total;
        const auto e = std::uint32_t(std::min<std::size_t>(
            std::upper_bound(cdf.begin(), cdf.end(), at) - cdf.begin(), cdf.size() - 1));
        const auto& t = mesh.triangles[e];
        const double r1 = std::sqrt(rng.next_double()), r2 = rng.next_double();
        const Vec3 p = mesh.vertex(t[0]) * (1 - r1) + mesh.vertex(t[1]) * (r1 * (1 - r2)) +
                       mesh.vertex(t[2]) * (r1 * r2);
        return p + mesh.patch_of(e).normal * offset;
    };
    std::vector<Segment> segments(count);
    for (Segment& s : segments) {
        const Vec3 p = sample(), q = sample();
        s = {Vec3f(p), Vec3f(q - p), 0.0f, 1.0f};
    }
    return segments;
}

/// Rays per second of \p visibility on \p segments, in parallel 4096-ray batches.
double raw_rays_per_second(const VisibilityQuery& visibility, std::span<const Segment> segments,
                           const Context& ctx) {
    constexpr std::size_t k_batch = 4096;
    std::vector<std::uint8_t> blocked(segments.size());
    const Clock::time_point start = Clock::now();
    run_in_arena(ctx, [&] {
        parallel_for_index((segments.size() + k_batch - 1) / k_batch, 1, [&](std::size_t b) {
            const std::size_t begin = b * k_batch;
            const std::size_t n = std::min(k_batch, segments.size() - begin);
            visibility.occluded(segments.subspan(begin, n), std::span(blocked).subspan(begin, n));
        });
    });
    return double(segments.size()) / seconds_since(start);
}

struct Row {
    bench::OfficeParams params;
    std::int64_t triangles = 0;
    std::size_t elements = 0, leaves = 0;
    std::uint64_t links = 0, rays = 0, calls = 0;
    double peak_mib = 0, mesh_s = 0, bvh_s = 0, solve_s = 0, output_s = 0;
    double raw_rays_s = 0, in_visibility = 0;
    double power_error = 0; ///< (absorbed + escaped) / emitted − 1, summed over the channels
    bool solved = false;    ///< false with --no-solve: no solve and output stages
};

/// The output stage of the CLI without the render: BVH of the leaf mesh, sensors, files.
void write_outputs(const Scene& scene, app::BakeResult& result, const Context& ctx) {
    const raytrace::EmbreeScene leaf_rt(result.mesh);
    result.sensors = solver::evaluate_sensors(scene, result.mesh, result.solution, leaf_rt, ctx);
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("hr_bench." + std::to_string(::getpid()));
    app::write_outputs(dir.string(), scene, result);
    std::filesystem::remove_all(dir);
}

/// "NXxNY" as {NX, NY}, or a one-line error.
std::pair<int, int> parse_offices(const std::string& text) {
    int nx = 0, ny = 0;
    char tail = 0;
    if (std::sscanf(text.c_str(), "%dx%d%c", &nx, &ny, &tail) != 2 || nx < 1 || ny < 1 ||
        nx > 1000 || ny > 1000)
        throw std::runtime_error("--offices: expected NXxNY with 1 ≤ NX, NY ≤ 1000, got '" + text +
                                 "'");
    return {nx, ny};
}

Row run_size(std::int64_t target, const Options& options, const Context& ctx) {
    Row row;
    row.params = bench::office_params_for_triangles(target);
    if (!options.offices.empty())
        std::tie(row.params.rooms_x, row.params.rooms_y) = parse_offices(options.offices);
    if (options.tessellation > 0)
        row.params.tessellation = options.tessellation;
    Scene scene = bench::office_floor(row.params);
    bench::mesh_input_as_is(scene);
    if (options.epsilon > 0)
        scene.solver.epsilon = options.epsilon;
    if (!options.clustering.empty())
        scene.solver.clustering = *parse_enum<Clustering>(options.clustering);
    if (options.min_area > 0)
        scene.solver.min_area = options.min_area;
    validate_scene(scene);
    row.triangles = bench::input_triangle_count(scene);
    auto stage = [&](double& seconds, const char* name, const std::function<void()>& run) {
        const Clock::time_point start = Clock::now();
        run();
        seconds = seconds_since(start);
        // Always shown, so that a size stopped by --max-seconds tells how far it got.
        fmt::print(stderr, "hr_bench: {}: {} {:.2f} s\n", options.child, name, seconds);
    };
    app::BakeResult result;
    RadiosityMesh mesh;
    stage(row.mesh_s, "mesh", [&] { mesh = mesher::build_mesh(scene, ctx); });
    std::optional<raytrace::EmbreeScene> rt;
    stage(row.bvh_s, "bvh", [&] { rt.emplace(mesh); });
    if (!options.no_solve) {
        const TimedVisibility timed(*rt);
        stage(row.solve_s, "solve", [&] {
            solver::SolveResult solved = solver::solve(scene, mesh, timed, ctx, &result.stats);
            result.solution = std::move(solved.solution);
            result.mesh = solved.refined_mesh ? std::move(*solved.refined_mesh) : mesh;
        });
        row.rays = rt->rays_traced();
        const auto [visibility_seconds, calls] = timed.totals();
        row.calls = calls;
        row.in_visibility = visibility_seconds / (row.solve_s * thread_count(ctx));
        stage(row.output_s, "output", [&] { write_outputs(scene, result, ctx); });
        row.solved = true;
        const solver::PowerBalance& pb = result.stats.power;
        row.power_error = (pb.absorbed.sum() + pb.escaped.sum()) / pb.emitted.sum() - 1.0;
    }
    row.elements = mesh.element_count();
    row.leaves = result.mesh.element_count();
    row.links = result.stats.links;
    row.peak_mib = peak_rss_mib(); // before the raw measurement's own buffers
    const std::vector<Segment> segments = random_segments(mesh, std::size_t(options.raw_rays));
    row.raw_rays_s = raw_rays_per_second(*rt, segments, ctx);
    return row;
}

void print_header() {
    fmt::print("{:<6} {:>7} {:>3} {:>9} {:>9} {:>9} {:>10} {:>8} {:>7} {:>7} {:>8} {:>8} {:>11} "
               "{:>6} {:>8} {:>8} {:>6} {:>5} {:>6}\n",
               "size", "offices", "k", "input_tri", "elements", "leaves", "links", "peak_MiB",
               "mesh_s", "bvh_s", "solve_s", "output_s", "rays", "batch", "Mray/s", "raw_Mr/s",
               "ratio", "vis%", "power%");
    std::fflush(stdout);
}

void print_row(const std::string& size, const Row& r) {
    const bool s = r.solved;
    // A column of a stage that did not run (--no-solve) shows "-".
    auto num = [](bool known, double value, int width, int precision) {
        return known ? fmt::format("{:>{}.{}f}", value, width, precision)
                     : fmt::format("{:>{}}", "-", width);
    };
    const double rays_s = double(r.rays) / r.solve_s;
    fmt::print("{:<6} {:>7} {:>3} {:>9} {:>9} {} {} {} {} {} {} {} {} {} {} {} {} {} {}\n", size,
               fmt::format("{}x{}", r.params.rooms_x, r.params.rooms_y), r.params.tessellation,
               r.triangles, r.elements, num(s, double(r.leaves), 9, 0),
               num(s, double(r.links), 10, 0), num(true, r.peak_mib, 8, 0),
               num(true, r.mesh_s, 7, 2), num(true, r.bvh_s, 7, 2), num(s, r.solve_s, 8, 2),
               num(s, r.output_s, 8, 2), num(s, double(r.rays), 11, 0),
               num(s, double(r.rays) / double(r.calls), 6, 1), num(s, rays_s * 1e-6, 8, 2),
               num(true, r.raw_rays_s * 1e-6, 8, 2), num(s, rays_s / r.raw_rays_s, 6, 3),
               num(s, 100.0 * r.in_visibility, 5, 1), num(s, 100.0 * r.power_error, 6, 2));
    std::fflush(stdout);
}

int run_child(const Options& options) {
    Context ctx;
    ctx.threads = options.threads;
    ctx.log = std::make_shared<StderrSink>();
    ctx.min_level = options.verbose ? LogLevel::debug : LogLevel::warn;
    print_row(options.child, run_size(parse_size(options.child), options, ctx));
    return 0;
}

/// Runs this program on one size in a child process; stops it after max_seconds.
void run_in_child(const std::string& size, const Options& options) {
    std::vector<std::string> args = {"hr_bench", "--child", size};
    args.insert(args.end(), {"--threads", std::to_string(options.threads)});
    args.insert(args.end(), {"--raw-rays", std::to_string(options.raw_rays)});
    if (options.epsilon > 0)
        args.insert(args.end(), {"--epsilon", std::to_string(options.epsilon)});
    if (!options.clustering.empty())
        args.insert(args.end(), {"--clustering", options.clustering});
    if (!options.offices.empty())
        args.insert(args.end(), {"--offices", options.offices});
    if (options.tessellation > 0)
        args.insert(args.end(), {"--tessellation", std::to_string(options.tessellation)});
    if (options.min_area > 0)
        args.insert(args.end(), {"--min-area", fmt::format("{}", options.min_area)});
    if (options.no_solve)
        args.push_back("--no-solve");
    if (options.verbose)
        args.push_back("-v");
    const bench::ChildRun run = bench::run_self(std::move(args), options.max_seconds, false);
    if (run.stopped)
        std::printf("%-6s stopped after %.0f s (--max-seconds)\n", size.c_str(),
                    options.max_seconds);
    else if (!run.failure().empty())
        std::printf("%-6s failed: %s\n", size.c_str(), run.failure().c_str());
    std::fflush(stdout);
}

} // namespace

int main(int argc, char** argv) {
    CLI::App cli{"hr_bench: hierarchical radiosity on generated office floors of growing size"};
    Options o;
    cli.add_option("--sizes", o.sizes, "target input triangles, e.g. 1k,2k,8k,32k,128k,1M")
        ->delimiter(',');
    cli.add_option("--max-seconds", o.max_seconds, "stop a size after this many seconds")
        ->check(CLI::PositiveNumber);
    cli.add_option("--threads", o.threads, "worker threads (0 = all cores)")
        ->check(CLI::Range(0, 1024));
    cli.add_option("--epsilon", o.epsilon, "solver.epsilon (default: the scene's, 1e-3)")
        ->check(CLI::PositiveNumber);
    cli.add_option("--clustering", o.clustering, "solver.clustering (default: the scene's, auto)")
        ->check(CLI::IsMember({"auto", "on", "off"}))
        ->check(CLI::IsMember(penumbra::enum_names<penumbra::Clustering>()));
    cli.add_option(
        "--offices", o.offices,
        "NXxNY offices (e.g. 2x1) instead of the size's; the size then only names the row");
    cli.add_option("--tessellation", o.tessellation,
                   "split every rectangle k x k (2k^2 triangles) instead of the size's k")
        ->check(CLI::Range(1, 64));
    cli.add_option("--min-area", o.min_area,
                   "solver.min_area in m^2 (default: the scene's, (diagonal / 200)^2)")
        ->check(CLI::PositiveNumber);
    cli.add_option("--raw-rays", o.raw_rays, "segments for the raw throughput")
        ->check(CLI::Range(std::int64_t(1), std::int64_t(1) << 32));
    cli.add_flag("--no-solve", o.no_solve,
                 "only mesh, BVH and raw throughput (sizes too large to solve)");
    cli.add_flag("-v,--verbose", o.verbose, "solver and mesher messages on stderr");
    cli.add_option("--child", o.child, "internal: run one size in this process")->group("");
    CLI11_PARSE(cli, argc, argv);
    try {
        if (!o.child.empty())
            return run_child(o);
        for (const std::string& size : o.sizes)
            parse_size(size); // reject a bad list before the first run
        if (!o.offices.empty())
            parse_offices(o.offices); // as the sizes: a bad value fails before the first run
        print_header();
        for (const std::string& size : o.sizes)
            run_in_child(size, o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "hr_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
