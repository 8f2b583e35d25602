// Bounded memory as a user meets it (issue #32, docs/memory.md): `--max-memory` and the
// stages' estimates. A run over the limit ends early with one line naming the stage, the
// estimate, the limit and the setting to change, exit 3; bad sizes are one-line errors.

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sys/resource.h>

#include "common/test_util.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

using test::run_cli;
using test::RunResult;

// CPU seconds of the children this process has waited for: a run's own cost, which a loaded
// machine (tests in parallel) does not stretch as it does the wall time.
// How much slower than a Release build this build runs: scripts/sanitize.sh sets
// PENUMBRA_TEST_CPU_SCALE for its sanitized build, where the bounds below would not hold.
double cpu_time_scale() {
    const char* scale = std::getenv("PENUMBRA_TEST_CPU_SCALE");
    return scale && std::atof(scale) >= 1 ? std::atof(scale) : 1.0;
}

double children_cpu_seconds() {
    rusage usage{};
    ::getrusage(RUSAGE_CHILDREN, &usage);
    auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
    return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

int count_lines(const std::string& s) {
    int n = 0;
    for (char c : s)
        n += c == '\n';
    return n;
}

// A 1 m emitting square above a floor, with the JSON members \p extra.
std::string lamp_and_floor(const std::string& extra = "") {
    return R"({
  "materials": {"lamp": {"emission": [1, 1, 1], "reflectance": 0}, "floor": {"reflectance": 0.5}},
  "polygons": [
    {"name": "lamp", "material": "lamp", "vertices": [[0,0,1],[0,1,1],[1,1,1],[1,0,1]]},
    {"name": "floor", "material": "floor", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}
  ])" + extra +
           "\n}\n";
}

// A 2 m black floor with a grid of sensors \p spacing apart, meshed at \p edge metres.
std::string annual_floor(double spacing, double edge) {
    return R"({
  "materials": {"black": {"reflectance": 0}},
  "polygons": [{"name": "floor", "material": "black",
                "vertices": [[0,0,0],[2,0,0],[2,2,0],[0,2,0]]}],
  "grids": {"wp": {"floor": "floor", "height": 0.85, "spacing": )" +
           std::to_string(spacing) + R"(, "wall_offset": 0.5}},
  "mesher": {"max_edge_length": )" +
           std::to_string(edge) + "}\n}\n";
}

class CliMemory : public ::testing::Test {
protected:
    void SetUp() override { dir_ = test::temp_dir("cli-memory"); }
    void TearDown() override { fs::remove_all(dir_); }

    std::string scene(const std::string& name, const std::string& text) const {
        std::ofstream(dir_ / name) << text;
        return (dir_ / name).string();
    }

    // Runs \p args with an output folder of its own; expects exit 3 within \p seconds of
    // CPU, one line naming every part of \p says, and no output file.
    void expect_refused(const std::string& args, const std::vector<std::string>& says,
                        double seconds = 5.0) const {
        const fs::path out = dir_ / "out";
        const double cpu0 = children_cpu_seconds();
        const RunResult r = run_cli(args + " -o " + out.string() + " -q");
        const double cpu = children_cpu_seconds() - cpu0;
        EXPECT_EQ(r.exit_code, 3) << args << ": " << r.err;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_EQ(r.err.rfind("penumbra: error: ", 0), 0u) << r.err;
        for (const std::string& part : says)
            EXPECT_NE(r.err.find(part), std::string::npos) << part << " in: " << r.err;
        EXPECT_LT(cpu, seconds * cpu_time_scale()) << args;
        EXPECT_TRUE(!fs::exists(out) || fs::is_empty(out)) << args;
    }

    fs::path dir_;
};

// solver.epsilon 1e-12 grew the links without bound (60 s and gigabytes, issue #32): the
// refinement pass that would outgrow the limit is refused before it makes its links. (The
// Cornell box at its own element size and --max-memory 200M ends the same way after 8 s of
// CPU, most of it the passes under the limit; this one takes 1.6 s.)
TEST_F(CliMemory, EpsilonGrowingLinksWithoutBoundIsStopped) {
    const std::string cornell = test::source_path("data/cornell/scene.json");
    expect_refused("bake " + cornell +
                       " --max-edge 0.25 --epsilon 1e-12 --max-memory 20M --no-render",
                   {"solve: a refinement pass", "links", "memory limit of 20 MiB",
                    "solver.epsilon (--epsilon)", "--max-memory"});
}

// mesher.element_budget 0 leaves nothing but the memory estimate to bound the elements of a
// tiny element size: refused before meshing, with the size that would fit.
TEST_F(CliMemory, TinyElementsWithoutABudgetAreRefusedBeforeMeshing) {
    const std::string s = scene("nobudget.json", lamp_and_floor(R"(,
  "mesher": {"max_edge_length": 0.5, "element_budget": 0})"));
    expect_refused("bake " + s + " --max-edge 1e-5 --max-memory 1G",
                   {"nobudget.json: meshing with elements of 1e-05 m", "memory limit of 1 GiB",
                    "use --max-edge", "--max-memory"});
}

// A camera image too large for the limit is refused before the solve.
TEST_F(CliMemory, RenderImageOverTheLimitIsRefusedBeforeSolving) {
    const std::string s = scene("big.json", lamp_and_floor(R"(,
  "camera": {"eye": [0.5, -1.5, 0.6], "look_at": [0.5, 0.5, 0.3], "up": [0, 0, 1], "fov_deg": 50},
  "image": {"width": 16384, "height": 16384})"));
    expect_refused("render " + s + " --max-memory 2G",
                   {"render: an image of 16384x16384 pixels", "image.width", "--max-memory"});
}

// `annual`: a year of hourly matrices for ten thousand sensors, and the daylight
// coefficients of a fine mesh by Reinhart's 578 patches, are refused by their estimates (the
// second after the sky matrix and the mesh: 2 s of CPU).
TEST_F(CliMemory, AnnualMatricesOverTheLimitAreRefused) {
    const std::string weather = test::source_path("data/weather/chicago_ohare_tmy3.epw");
    expect_refused("annual " + scene("sensors.json", annual_floor(0.01, 1.0)) + " --weather " +
                       weather + " --max-memory 1G",
                   {"annual: 10201 sensors", "8760 hours", "fewer sensors", "--max-memory"});
    expect_refused(
        "annual " + scene("fine.json", annual_floor(1.0, 0.03)) + " --weather " + weather +
            " --patches 2 --max-memory 30M",
        {"daylight coefficients:", "578 sky patches", "--patches", "--max-edge", "--max-memory"});
}

// Charts at the density asked for would not fit: refused before packing (which took 13 s of
// CPU for these two at 4 000 texels per metre before it was refused).
TEST_F(CliMemory, LightmapTexelsOverTheLimitAreRefused) {
    expect_refused("lightmap " + scene("lm.json", lamp_and_floor()) +
                       " --texels-per-metre 4000 --atlas 4096 --max-memory 1G",
                   {"lightmap: 2 charts at 4000 texels per metre (at least 3.2e+07 texels)",
                    "--texels-per-metre", "--atlas", "--max-memory"});
}

// Bad sizes are one line naming the flag, exit 3, before anything runs.
TEST_F(CliMemory, BadSizesAreOneLineErrors) {
    const std::string s = scene("ok.json", lamp_and_floor());
    for (const char* size : {"nan", "-1G", "4X", "1e400", "0.5", "G", "5000P", ""}) {
        const RunResult r = run_cli("bake " + s + " -o " + (dir_ / "out").string() +
                                    " --max-memory '" + size + "' -q");
        EXPECT_EQ(r.exit_code, 3) << size << ": " << r.err;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find("--max-memory"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("expected a size such as 4G"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir_ / "out")) << size;
    }
}

// Under the limit nothing changes: a bake with a limit far above its needs, or none, writes
// the same files as one with the default limit.
TEST_F(CliMemory, RunsUnderTheLimitAreUnchanged) {
    const std::string s = scene("ok.json", lamp_and_floor());
    std::vector<std::string> meshes;
    for (const char* limit : {"", " --max-memory 0", " --max-memory 64g", " --max-memory 1.5GiB"}) {
        const fs::path out = dir_ / "out";
        fs::remove_all(out);
        const RunResult r =
            run_cli("bake " + s + " -o " + out.string() + limit + " --no-render -q");
        ASSERT_EQ(r.exit_code, 0) << limit << ": " << r.err;
        std::ifstream in(out / "mesh.vtu", std::ios::binary);
        meshes.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    for (std::size_t i = 1; i < meshes.size(); ++i)
        EXPECT_EQ(meshes[i], meshes[0]) << i;
}

} // namespace
} // namespace penumbra
