// Meshing time and element counts (issues #4 and #5). Two tables:
//
// 1. (default) The Cornell box and generated open-plan office floors of n × n offices
//    (office_scene.h: partitions with doors, two desks on legs and a cabinet each, a ceiling
//    panel light per office, no windows; floor and ceiling are single polygons spanning the
//    floor plate, as generated models often have), each meshed with and without
//    discontinuity meshing. Usage: mesh_bench [EDGE_M] [N ...] (default 0.25 m; 1, 2 and 4
//    → 1, 4 and 16 offices).
// 2. (--as-input 128k,512k,1M) Scaling: hr_bench's office floors of about that many input
//    triangles, meshed as input (mesh_input_as_is), or with contact splitting and hidden
//    regions (--contacts) and discontinuity meshing (--discontinuities) switched back on.
//    Each size runs in a child process of its own, so that its peak RSS (VmHWM: the scene,
//    the mesher's working set and the finished mesh) is its own, and a size running longer
//    than --max-seconds is stopped. Columns: seconds (wall, and CPU of all threads, which
//    other jobs on the machine disturb less), microseconds per input triangle and the growth
//    exponent of the wall time against the previous size (1 = linear), plus the
//    element count, the total element area and a fingerprint of the whole mesh (vertices,
//    elements, patches, hidden areas, discontinuity segments), which must not depend on how
//    fast the mesher is.
//    -v prints the mesher's per-stage seconds.

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "bench_process.h"
#include "core/error.h"
#include "core/scene_io.h"
#include "mesher/mesher.h"
#include "office_scene.h"

namespace {

using namespace penumbra;
using bench::Clock;
using bench::parse_size;
using bench::peak_rss_mib;
using bench::seconds_since;

/// Mesher messages on stderr; of the warnings, which the generated floors repeat per office,
/// only the first few.
class StderrSink final : public LogSink {
public:
    void write(LogLevel level, std::string_view message) override {
        if (level >= LogLevel::warn && ++warnings_ > 3) {
            if (warnings_ == 4)
                std::fprintf(stderr, "mesh_bench: (further warnings not shown)\n");
            return;
        }
        const char* tag = level >= LogLevel::warn ? "warning: " : "";
        std::fprintf(stderr, "mesh_bench: %s%.*s\n", tag, int(message.size()), message.data());
    }

private:
    int warnings_ = 0;
};

struct Options {
    double edge = 0.25;
    std::vector<int> offices;
    std::vector<std::string> as_input; ///< sizes for the scaling table
    bool contacts = false, discontinuities = false;
    double max_seconds = 600;
    int threads = 0;
    bool verbose = false;
    std::string child; ///< internal: mesh this one size in this process
};

Context make_context(const Options& o) {
    Context ctx;
    ctx.threads = o.threads;
    if (o.verbose) {
        ctx.log = std::make_shared<StderrSink>();
        ctx.min_level = LogLevel::debug;
    }
    return ctx;
}

/// FNV-1a over the bytes of \p values, continuing from \p h.
template <typename T> std::uint64_t hash_bytes(std::uint64_t h, const std::vector<T>& values) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
    for (std::size_t i = 0; i < values.size() * sizeof(T); ++i)
        h = (h ^ bytes[i]) * 0x100000001b3ull;
    return h;
}

/// A fingerprint of the mesh: equal fingerprints mean the same vertices, elements, patches
/// (side and surface), hidden areas and discontinuity segments, bit for bit.
std::uint64_t fingerprint(const RadiosityMesh& m) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    h = hash_bytes(h, m.positions);
    h = hash_bytes(h, m.vertex_patch);
    h = hash_bytes(h, m.triangles);
    h = hash_bytes(h, m.element_patch);
    h = hash_bytes(h, m.element_twin);
    h = hash_bytes(h, m.element_area);
    h = hash_bytes(h, m.geometry_elements);
    std::vector<double> per_patch, per_surface, segments;
    for (const Patch& p : m.patches)
        per_patch.insert(per_patch.end(),
                         {double(p.surface), double(p.back), p.normal.x, p.normal.y, p.normal.z});
    for (const SurfaceInfo& s : m.surfaces)
        per_surface.insert(per_surface.end(),
                           {double(s.polygon), s.area_m2, s.hidden_front_m2, s.hidden_back_m2});
    for (const DiscontinuitySegment& d : m.discontinuities)
        segments.insert(segments.end(),
                        {d.a.x, d.a.y, d.a.z, d.b.x, d.b.y, d.b.z, double(d.surface),
                         double(source_code(d.source)), double(d.order)});
    h = hash_bytes(h, per_patch);
    h = hash_bytes(h, per_surface);
    return hash_bytes(h, segments);
}

// ---- Table 1: Cornell box and n × n offices, with and without discontinuity meshing ----

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
    std::uint64_t hash;
};

Run mesh(const Scene& scene, const Context& ctx) {
    const Clock::time_point start = Clock::now();
    const RadiosityMesh m = mesher::build_mesh(scene, ctx);
    return {seconds_since(start), m.element_count(), m.discontinuities.size(), fingerprint(m)};
}

void report(const std::string& name, Scene scene, const Context& ctx) {
    const Run with = mesh(scene, ctx);
    scene.mesher.discontinuity.enabled = false;
    const Run without = mesh(scene, ctx);
    std::printf("%-22s %8zu %7.3f %10zu %9zu %8.2f %10zu %8.2f  %016llx %016llx\n", name.c_str(),
                scene.polygons.size(), scene.mesher.max_edge_length, with.elements, with.segments,
                with.seconds, without.elements, without.seconds,
                static_cast<unsigned long long>(with.hash),
                static_cast<unsigned long long>(without.hash));
    std::fflush(stdout);
}

void office_table(const Options& o) {
    const Context ctx = make_context(o);
    std::printf("%-22s %8s %7s %10s %9s %8s %10s %8s  %-16s %-16s\n", "scene", "polygons", "edge_m",
                "elements", "segments", "mesh_s", "no_disc_el", "no_disc_s", "fingerprint",
                "no_disc_fp");
    Scene cornell = load_scene("data/cornell/scene.json");
    report("cornell (scene edge)", cornell, ctx);
    cornell.mesher.max_edge_length = 0.02;
    report("cornell", cornell, ctx);
    for (int n : o.offices)
        report("office " + std::to_string(n) + "x" + std::to_string(n), office(n, o.edge), ctx);
}

// ---- Table 2: scaling with the input size, one child process per size ----

/// CPU seconds (user + system) of this process so far, all threads.
double cpu_seconds() {
    rusage usage{};
    ::getrusage(RUSAGE_SELF, &usage);
    auto secs = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
    return secs(usage.ru_utime) + secs(usage.ru_stime);
}

/// Meshes one size; prints "triangles surfaces elements vertices area seconds cpu_seconds
/// peak_mib hash".
int run_child(const Options& o) {
    const Context ctx = make_context(o);
    Scene scene = bench::office_floor(bench::office_params_for_triangles(parse_size(o.child)));
    bench::mesh_input_as_is(scene);
    scene.mesher.split_contacts = o.contacts;
    scene.mesher.discontinuity.enabled = o.discontinuities;
    const Clock::time_point start = Clock::now();
    const double cpu_start = cpu_seconds();
    const RadiosityMesh m = mesher::build_mesh(scene, ctx);
    const double seconds = seconds_since(start), cpu = cpu_seconds() - cpu_start;
    double area = 0;
    for (double a : m.element_area)
        area += a;
    std::printf("%lld %zu %zu %zu %.9e %.3f %.3f %.1f %016llx\n",
                static_cast<long long>(bench::input_triangle_count(scene)), m.surfaces.size(),
                m.element_count(), m.vertex_count(), area, seconds, cpu, peak_rss_mib(),
                static_cast<unsigned long long>(fingerprint(m)));
    return 0;
}

struct ChildRow {
    long long triangles = 0;
    std::size_t surfaces = 0, elements = 0, vertices = 0;
    double area = 0, seconds = 0, cpu = 0, peak_mib = 0;
    unsigned long long hash = 0;
};

/// Runs this program on one size in a child process; false if it failed or was stopped.
bool run_in_child(const std::string& size, const Options& o, ChildRow& row) {
    std::vector<std::string> args = {"mesh_bench", "--child", size, "--threads",
                                     std::to_string(o.threads)};
    if (o.contacts)
        args.push_back("--contacts");
    if (o.discontinuities)
        args.push_back("--discontinuities");
    if (o.verbose)
        args.push_back("-v");
    const bench::ChildRun run = bench::run_self(std::move(args), o.max_seconds, true);
    if (run.stopped) {
        std::printf("%-6s stopped after %.0f s (--max-seconds)\n", size.c_str(), o.max_seconds);
        return false;
    }
    if (!run.failure().empty() ||
        std::sscanf(run.out.c_str(), "%lld %zu %zu %zu %le %lf %lf %lf %llx", &row.triangles,
                    &row.surfaces, &row.elements, &row.vertices, &row.area, &row.seconds, &row.cpu,
                    &row.peak_mib, &row.hash) != 9) {
        std::printf("%-6s failed (%s)\n", size.c_str(),
                    run.failure().empty() ? "unreadable output" : run.failure().c_str());
        return false;
    }
    return true;
}

void scaling_table(const Options& o) {
    for (const std::string& size : o.as_input)
        parse_size(size); // reject a bad list before the first run
    std::printf("as input%s%s\n", o.contacts ? ", contacts and hidden regions" : "",
                o.discontinuities ? ", discontinuity meshing" : "");
    std::printf("%-6s %9s %8s %9s %9s %14s %8s %8s %7s %6s %8s %16s\n", "size", "input_tri",
                "surfaces", "elements", "vertices", "area_m2", "mesh_s", "cpu_s", "us/tri", "exp",
                "peak_MiB", "fingerprint");
    std::fflush(stdout);
    ChildRow previous;
    for (const std::string& size : o.as_input) {
        ChildRow r;
        if (!run_in_child(size, o, r)) {
            previous = {};
            continue;
        }
        const std::string exponent =
            previous.triangles > 0
                ? fmt::format("{:.2f}", std::log(r.seconds / previous.seconds) /
                                            std::log(double(r.triangles) / previous.triangles))
                : "-";
        std::printf("%-6s %9lld %8zu %9zu %9zu %14.6f %8.2f %8.2f %7.2f %6s %8.0f %016llx\n",
                    size.c_str(), r.triangles, r.surfaces, r.elements, r.vertices, r.area,
                    r.seconds, r.cpu, 1e6 * r.seconds / double(r.triangles), exponent.c_str(),
                    r.peak_mib, r.hash);
        std::fflush(stdout);
        previous = r;
    }
}

} // namespace

int main(int argc, char** argv) {
    CLI::App cli{"mesh_bench: meshing time and element counts"};
    Options o;
    std::vector<std::string> positional;
    cli.add_option("args", positional, "EDGE_M [N ...]: element size and office floors n x n");
    cli.add_option("--as-input", o.as_input,
                   "scaling table: office floors of about these input triangles, meshed as "
                   "input (e.g. 128k,512k,1M)")
        ->delimiter(',');
    cli.add_flag("--contacts", o.contacts, "--as-input: contact splitting and hidden regions on");
    cli.add_flag("--discontinuities", o.discontinuities, "--as-input: discontinuity meshing on");
    cli.add_option("--max-seconds", o.max_seconds, "--as-input: stop a size after this long")
        ->check(CLI::PositiveNumber);
    cli.add_option("--threads", o.threads, "worker threads (0 = all cores)")
        ->check(CLI::Range(0, 1024));
    cli.add_flag("-v,--verbose", o.verbose, "mesher messages and seconds per stage on stderr");
    cli.add_option("--child", o.child, "internal: mesh one size in this process")->group("");
    CLI11_PARSE(cli, argc, argv);
    try {
        if (!o.child.empty())
            return run_child(o);
        if (!positional.empty())
            o.edge = std::stod(positional[0]);
        for (std::size_t i = 1; i < positional.size(); ++i)
            o.offices.push_back(std::stoi(positional[i]));
        if (!o.as_input.empty()) {
            scaling_table(o);
            return 0;
        }
        if (o.offices.empty())
            o.offices = {1, 2, 4};
        office_table(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "mesh_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
