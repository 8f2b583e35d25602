// The CLI as a user runs it: every kind of bad input gives one clear line naming the file or
// key, a non-zero exit and no output left behind.

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <csignal>
#include <cstring>
#include <utility>
#include <vector>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "common/test_util.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

using test::run_cli;
using test::RunResult;

void write(const fs::path& path, const std::string& text) {
    std::ofstream(path) << text;
}

int count_lines(const std::string& s) {
    int n = 0;
    for (char c : s)
        n += c == '\n';
    return n;
}

// A valid minimal scene: a 1 m emitting square above a floor.
std::string good_scene(const std::string& extra = "") {
    return R"({
  "materials": {"lamp": {"emission": [1, 1, 1], "reflectance": 0}, "floor": {"reflectance": 0.5}},
  "polygons": [
    {"name": "lamp", "material": "lamp", "vertices": [[0,0,1],[0,1,1],[1,1,1],[1,0,1]]},
    {"name": "floor", "material": "floor", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}
  ],
  "mesher": {"max_edge_length": 0.5})" +
           extra + "\n}\n";
}

// The keys that make a bake write sensors and a render: one sensor on the floor, a camera
// and an image of \p width × \p height at \p spp.
std::string sensor_and_camera(int width, int height, int spp) {
    return fmt::format(R"(,
  "sensors": [[0.5, 0.5, 0, 0, 0, 1]],
  "camera": {{"eye": [0.5, -1.5, 0.6], "look_at": [0.5, 0.5, 0.3], "up": [0, 0, 1], "fov_deg": 50}},
  "image": {{"width": {}, "height": {}, "spp": {}}})",
                       width, height, spp);
}

class CliBadInput : public ::testing::Test {
protected:
    void SetUp() override { dir_ = test::temp_dir("cli"); }
    void TearDown() override { fs::remove_all(dir_); }

    // Runs bake on \p scene_file, expects failure mentioning every word in \p mentions.
    void expect_error(const std::string& scene_file, std::initializer_list<const char*> mentions) {
        const fs::path out = dir_ / "out";
        RunResult r = run_cli("bake " + scene_file + " -o " + out.string() + " -q");
        EXPECT_NE(r.exit_code, 0) << r.err;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_EQ(r.err.rfind("penumbra: error: ", 0), 0u) << r.err;
        for (const char* m : mentions)
            EXPECT_NE(r.err.find(m), std::string::npos) << "missing '" << m << "' in: " << r.err;
        EXPECT_FALSE(fs::exists(out)) << "output left behind";
    }
    fs::path dir_;
};

TEST_F(CliBadInput, MissingSceneFile) {
    expect_error((dir_ / "nope.json").string(), {"nope.json", "not found"});
}

TEST_F(CliBadInput, MalformedJson) {
    write(dir_ / "bad.json", "{\n  \"materials\": {,\n}\n");
    expect_error((dir_ / "bad.json").string(), {"bad.json", ":2"});
}

TEST_F(CliBadInput, UnknownKey) {
    write(dir_ / "typo.json", good_scene(",\n  \"solver\": {\"residul\": 0.01}"));
    expect_error((dir_ / "typo.json").string(), {"typo.json", "solver.residul"});
}

TEST_F(CliBadInput, NanVertex) {
    write(dir_ / "nan.obj", "o bad\nv nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    write(dir_ / "nan.json", good_scene(",\n  \"geometry\": \"nan.obj\""));
    expect_error((dir_ / "nan.json").string(), {"nan.obj", "must be finite"});
}

TEST_F(CliBadInput, ZeroAreaFace) {
    write(dir_ / "flat.obj", "o sliver\nv 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    write(dir_ / "flat.json", good_scene(",\n  \"geometry\": \"flat.obj\""));
    expect_error((dir_ / "flat.json").string(), {"flat.obj", "zero-area"});
}

TEST_F(CliBadInput, NoEmitter) {
    write(dir_ / "dark.json", R"({"polygons": [{"name": "floor", "material": "floor",
        "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}], "materials": {"floor": {}}})");
    expect_error((dir_ / "dark.json").string(), {"dark.json", "no emitter"});
}

// Each bad spot: exit code 2 (a bad scene), one line naming the file and the key.
TEST_F(CliBadInput, BadSpot) {
    struct Case {
        const char* spot;
        const char* key;
        const char* what;
    };
    const Case cases[] = {
        {R"({"direction": [0, 0, 0], "beam_deg": 10, "cutoff_deg": 20})", "spot.direction",
         "non-zero"},
        {R"({"direction": [0, "NaN", -1], "beam_deg": 10, "cutoff_deg": 20})", "spot.direction",
         "expected 3 numbers"},
        {R"({"direction": [0, 0, -1], "beam_deg": 30, "cutoff_deg": 20})", "spot.beam_deg",
         "cutoff_deg"},
        {R"({"direction": [0, 0, -1], "beam_deg": 10, "cutoff_deg": 200})", "spot.cutoff_deg",
         "180"},
        {R"({"direction": [0, 0, -1], "beam_deg": 10, "cutoff_deg": 20, "angle": 5})", "spot.angle",
         "unknown key"},
    };
    int i = 0;
    for (const Case& c : cases) {
        const fs::path scene = dir_ / ("spot" + std::to_string(i++) + ".json");
        write(scene, good_scene(std::string(",\n  \"point_lights\": [{\"position\": [0.5, 0.5, "
                                            "0.9], \"intensity_cd\": 10, \"spot\": ") +
                                c.spot + "}]"));
        const fs::path out = dir_ / "out";
        RunResult r = run_cli("bake " + scene.string() + " -o " + out.string() + " -q");
        EXPECT_EQ(r.exit_code, 2) << r.err;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_EQ(r.err.rfind("penumbra: error: ", 0), 0u) << r.err;
        for (const std::string& m : {scene.filename().string(),
                                     std::string("point_lights[0].") + c.key, std::string(c.what)})
            EXPECT_NE(r.err.find(m), std::string::npos) << "missing '" << m << "' in: " << r.err;
        EXPECT_FALSE(fs::exists(out)) << "output left behind";
    }
}

// Each bad sun: exit code 2 (a bad scene), one line naming the file and the key.
TEST_F(CliBadInput, BadSun) {
    struct Case {
        const char* sun;
        const char* key;
        const char* what;
    };
    const Case cases[] = {
        {R"({"direction": [0, 0, 0], "illuminance_lx": 1e5})", "sun.direction", "non-zero"},
        {R"({"direction": [0, "NaN", 1], "illuminance_lx": 1e5})", "sun.direction",
         "expected 3 numbers"},
        {R"({"direction": [0, 0, 1], "illuminance_lx": -1})", "sun.illuminance_lx", ">= 0"},
        {R"({"direction": [0, 0, 1], "irradiance_w_m2": [1, 1, -2]})", "sun.irradiance_w_m2",
         ">= 0"},
        {R"({"direction": [0, 0, 1], "illuminance_lx": 1e5, "angular_diameter_deg": -0.5})",
         "sun.angular_diameter_deg", "[0, 10]"},
        {R"({"direction": [0, 0, 1], "illuminance_lx": 1e5, "azimuth": 3})", "sun.azimuth",
         "unknown key"},
    };
    int i = 0;
    for (const Case& c : cases) {
        const fs::path scene = dir_ / ("sun" + std::to_string(i++) + ".json");
        write(scene, good_scene(std::string(",\n  \"sun\": ") + c.sun));
        const fs::path out = dir_ / "out";
        RunResult r = run_cli("bake " + scene.string() + " -o " + out.string() + " -q");
        EXPECT_EQ(r.exit_code, 2) << r.err;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_EQ(r.err.rfind("penumbra: error: ", 0), 0u) << r.err;
        for (const std::string& m :
             {scene.filename().string(), std::string("'") + c.key + "'", std::string(c.what)})
            EXPECT_NE(r.err.find(m), std::string::npos) << "missing '" << m << "' in: " << r.err;
        EXPECT_FALSE(fs::exists(out)) << "output left behind";
    }
}

TEST_F(CliBadInput, UnwritableOutputFolder) {
    write(dir_ / "ok.json", good_scene());
    write(dir_ / "a_file", "x");
    const fs::path out = dir_ / "a_file" / "out"; // a folder below a regular file
    RunResult r = run_cli("bake " + (dir_ / "ok.json").string() + " -o " + out.string() + " -q");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(out.string()), std::string::npos) << r.err;
}

TEST_F(CliBadInput, BadFlag) {
    write(dir_ / "ok.json", good_scene());
    RunResult r = run_cli("bake " + (dir_ / "ok.json").string() + " --threads -3");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("--threads"), std::string::npos) << r.err;
}

// Solver choices: an unknown value of a scene key names the key and the known values; an
// unknown flag value names the flag.
TEST_F(CliBadInput, UnknownSolverChoice) {
    write(dir_ / "iteration.json", good_scene(R"(, "solver": {"iteration": "southwell"})"));
    expect_error((dir_ / "iteration.json").string(),
                 {"iteration.json", "solver.iteration", "southwell", "gauss_seidel"});
    write(dir_ / "ok.json", good_scene());
    RunResult r = run_cli("bake " + (dir_ / "ok.json").string() + " --iteration southwell -q");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("--iteration"), std::string::npos) << r.err;
}

TEST(Cli, BakeWritesEveryOutput) {
    const fs::path dir = test::temp_dir("cli-ok");
    write(dir / "ok.json", good_scene(sensor_and_camera(32, 24, 4)));
    const fs::path out = dir / "out";
    RunResult r = run_cli("bake " + (dir / "ok.json").string() + " -o " + out.string() + " -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* f : {"mesh.vtu", "render.exr", "render.png", "sensors.csv", "summary.json",
                          "solver_state.bin"})
        EXPECT_TRUE(fs::exists(out / f)) << f;
    for (const auto& entry : fs::directory_iterator(out))
        EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos);
    // A re-solve from that folder, into another.
    r = run_cli("bake " + (dir / "ok.json").string() + " -o " + (dir / "again").string() +
                " --reuse " + out.string() + " --no-render --no-state -q");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / "again" / "mesh.vtu"));
    EXPECT_FALSE(fs::exists(dir / "again" / "solver_state.bin"));
    // Progressive shooting on the hierarchy, with a series: snapshots while it shoots.
    r = run_cli("bake " + (dir / "ok.json").string() + " -o " + (dir / "shots").string() +
                " --iteration shooting --series 4 --epsilon 1e-2 --no-render -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::size_t steps = 0;
    for (const auto& entry : fs::directory_iterator(dir / "shots" / "series"))
        steps += entry.path().extension() == ".vtu";
    EXPECT_GE(steps, 3u);
    EXPECT_TRUE(fs::exists(dir / "shots" / "series.pvd"));
    fs::remove_all(dir);
}

// Numeric flags take finite numbers in their range: NaN was silently ignored, and CLI11's
// range message printed DBL_MAX in 300 digits without the error prefix (issue #32).
TEST_F(CliBadInput, NonFiniteOrOutOfRangeFlagsAreOneLineErrors) {
    write(dir_ / "ok.json", good_scene());
    const fs::path out = dir_ / "out";
    for (const char* flag :
         {"--max-edge nan", "--epsilon nan", "--residual nan", "--min-area nan", "--max-edge inf",
          "--max-edge 1e400", "--epsilon 5", "--min-area -1", "--series 0", "--method southwell"}) {
        const RunResult r =
            run_cli("bake " + (dir_ / "ok.json").string() + " -o " + out.string() + " " + flag);
        EXPECT_EQ(r.exit_code, 3) << flag << ": " << r.err;
        EXPECT_EQ(count_lines(r.err), 1) << flag << ": " << r.err;
        EXPECT_EQ(r.err.rfind("penumbra: error: ", 0), 0u) << r.err;
        const std::string name(flag, std::string(flag).find(' '));
        EXPECT_NE(r.err.find(name), std::string::npos) << r.err;
        EXPECT_LT(r.err.size(), 200u) << r.err;
        EXPECT_FALSE(fs::exists(out)) << flag;
    }
}

// An element size far below what the budget allows (over 100 times its elements) is refused
// before meshing (issue #32: the Cornell box at --max-edge 1e-6 meshed for minutes into
// gigabytes).
TEST(CliBudget, ElementSizeFarBelowTheBudgetIsRefusedBeforeMeshing) {
    const std::string scene = test::source_path("data/cornell/scene.json");
    const fs::path out = fs::path(test::temp_dir("cli-budget")) / "out";
    for (const char* edge : {"1e-6", "1e-4"}) {
        const RunResult r =
            run_cli("bake " + scene + " -o " + out.string() + " --max-edge " + edge + " -q");
        EXPECT_EQ(r.exit_code, 3) << r.err;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        for (const char* part : {"scene.json", "mesher.element_budget", "--max-edge"})
            EXPECT_NE(r.err.find(part), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out));
    }
}

// A point light on a surface lost its power without a word (issue #32: relative imbalance
// 0.93): within the contact tolerance of a surface it is an error naming the light.
TEST_F(CliBadInput, PointLightOnASurface) {
    for (const char* z : {"0", "0.0005"}) {
        write(dir_ / "on.json", good_scene(fmt::format(R"(,
  "point_lights": [{{"name": "bulb", "position": [0.5, 0.5, {}], "intensity_cd": 10}}])",
                                                       z)));
        expect_error((dir_ / "on.json").string(),
                     {"on.json", "point_lights[0].position", "'bulb'", "floor"});
    }
    write(dir_ / "above.json", good_scene(R"(,
  "point_lights": [{"name": "bulb", "position": [0.5, 0.5, 0.01], "intensity_cd": 10}])"));
    const RunResult r = run_cli("bake " + (dir_ / "above.json").string() + " -o " +
                                (dir_ / "out").string() + " --no-render -q");
    EXPECT_EQ(r.exit_code, 0) << r.err;
}

// A minimum area that lets the hierarchy grow without bound is refused before refining (issue
// #32: solver.min_area 1e-30 refined on and on).
TEST(CliBudget, MinimumAreaFarBelowTheBudgetIsRefused) {
    const std::string scene = test::source_path("data/cornell/scene.json");
    const fs::path out = fs::path(test::temp_dir("cli-min-area")) / "out";
    const RunResult r = run_cli("bake " + scene + " -o " + out.string() + " --min-area 1e-30 -q");
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    for (const char* part : {"solver.min_area", "mesher.element_budget", "--min-area"})
        EXPECT_NE(r.err.find(part), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out / "mesh.vtu"));
}

TEST_F(CliBadInput, ReuseOfAMissingOrWrongState) {
    write(dir_ / "ok.json", good_scene());
    const fs::path out = dir_ / "out";
    RunResult r = run_cli("bake " + (dir_ / "ok.json").string() + " -o " + out.string() +
                          " --reuse " + (dir_ / "nowhere").string() + " -q");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("nowhere"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
    r = run_cli("bake " + (dir_ / "ok.json").string() + " -o " + out.string() + " --reuse " +
                (dir_ / "ok.json").string() + " -q");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("not a Penumbra solver state"), std::string::npos) << r.err;
    r = run_cli("bake " + (dir_ / "ok.json").string() + " -o " + out.string() + " --reuse " +
                (dir_ / "ok.json").string() + " --method shooting -q");
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_NE(r.err.find("--reuse"), std::string::npos) << r.err;
}

// Every output names its files (app/src/outputs.h): a bake into the folder of an earlier one
// leaves none of the earlier bake's files that it does not write itself.
TEST(CliOutputs, RebakeRemovesTheEarlierBakesOtherFiles) {
    const fs::path dir = test::temp_dir("cli-rebake");
    write(dir / "full.json", good_scene(sensor_and_camera(16, 12, 1)));
    write(dir / "bare.json", good_scene());
    const fs::path out = dir / "out";
    RunResult r =
        run_cli("bake " + (dir / "full.json").string() + " -o " + out.string() + " --series 2 -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* f : {"render.exr", "render.png", "sensors.csv", "sensors.vtp", "series.pvd",
                          "solver_state.bin"})
        ASSERT_TRUE(fs::exists(out / f)) << f;
    write(out / "notes.txt", "a user's file");
    r = run_cli("bake " + (dir / "bare.json").string() + " -o " + out.string() + " --no-state -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* f : {"render.exr", "render.png", "sensors.csv", "sensors.vtp", "series.pvd",
                          "series", "solver_state.bin"})
        EXPECT_FALSE(fs::exists(out / f)) << f << " of the earlier bake was left";
    for (const char* f : {"mesh.vtu", "summary.json", "notes.txt"})
        EXPECT_TRUE(fs::exists(out / f)) << f;
    fs::remove_all(dir);
}

// Issue #32: `view --png /dev/full` replaced the device with a PNG, and `--png` onto a folder
// said "cannot write …: Success". Neither is a regular file: refused by name, left as it was.
// A fifo of the test's own stands for the device: a build without the check, run as root,
// would otherwise replace the machine's /dev/null.
TEST(CliOutputs, NeverReplacesWhatIsNotARegularFile) {
    const fs::path dir = test::temp_dir("cli_not_regular");
    write(dir / "ok.json", good_scene());
    const fs::path out = dir / "out";
    RunResult r =
        run_cli("bake " + (dir / "ok.json").string() + " -o " + out.string() + " --no-render -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const fs::path fifo = dir / "device.png";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0666), 0);
    r = run_cli("view " + out.string() + " --png " + fifo.string() + " -q");
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_NE(r.err.find("device.png' is not a regular file"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::is_fifo(fifo));

    const fs::path folder = dir / "folder_out";
    fs::create_directories(folder / "mesh.vtu");
    r = run_cli("bake " + (dir / "ok.json").string() + " -o " + folder.string() +
                " --no-render -q");
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_NE(r.err.find("mesh.vtu' is not a regular file"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("Success"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::is_directory(folder / "mesh.vtu"));
}

// The temporary files ".NAME.tmpPID" in \p dir.
std::vector<fs::path> temp_files(const fs::path& dir) {
    std::vector<fs::path> found;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
        if (it->path().filename().string().find(".tmp") != std::string::npos)
            found.push_back(it->path());
    return found;
}

// Issue #32: SIGINT or SIGTERM while an output is written left its temporary file. The bake is
// sent the signal as soon as a temporary file appears; it must exit with 130 or 143 and leave
// none. A bake that ends before one is seen is tried again (the write is a race by nature).
TEST(CliOutputs, SignalWhileWritingLeavesNoTemporaryFile) {
    const fs::path dir = test::temp_dir("cli_signal");
    write(dir / "big.json", good_scene().replace(good_scene().find("0.5}"), 4, "0.02}"));
    for (const auto& [signal, exit_code] : {std::pair{SIGTERM, 143}, std::pair{SIGINT, 130}}) {
        bool caught = false;
        for (int attempt = 0; attempt < 10 && !caught; ++attempt) {
            const fs::path out = dir / fmt::format("out{}-{}", signal, attempt);
            fs::create_directories(out);
            const pid_t pid = ::fork();
            ASSERT_GE(pid, 0);
            if (pid == 0) {
                std::freopen("/dev/null", "w", stderr);
                ::execl(PENUMBRA_CLI, PENUMBRA_CLI, "bake", (dir / "big.json").c_str(), "-o",
                        out.c_str(), "--no-render", "-q", static_cast<char*>(nullptr));
                ::_exit(127);
            }
            int status = 0;
            while (::waitpid(pid, &status, WNOHANG) == 0) {
                if (!temp_files(out).empty()) {
                    ::kill(pid, signal);
                    ::waitpid(pid, &status, 0);
                    caught = true;
                    break;
                }
            }
            if (caught) {
                ASSERT_TRUE(WIFEXITED(status)) << strsignal(signal);
                EXPECT_EQ(WEXITSTATUS(status), exit_code) << strsignal(signal);
                EXPECT_TRUE(temp_files(out).empty()) << strsignal(signal);
            }
        }
        EXPECT_TRUE(caught) << "no bake was seen writing a temporary file: " << strsignal(signal);
    }
}

// A temporary file of a killed bake (its PID no longer alive) is removed by the next bake into
// the same folder; one whose process is alive (this test's) is left alone.
TEST(CliOutputs, BakeRemovesStaleTemporaryFiles) {
    const fs::path dir = test::temp_dir("cli_stale_temp");
    write(dir / "ok.json", good_scene());
    const fs::path out = dir / "out";
    fs::create_directories(out);
    const pid_t dead = ::fork(); // a PID certainly not alive once reaped
    if (dead == 0)
        ::_exit(0);
    ::waitpid(dead, nullptr, 0);
    const fs::path stale = out / (".mesh.vtu.tmp" + std::to_string(dead));
    const fs::path live = out / (".solver_state.bin.tmp" + std::to_string(::getpid()));
    const fs::path other = out / (".notes.txt.tmp" + std::to_string(dead));
    for (const fs::path& p : {stale, live, other})
        write(p, "partial");
    const RunResult r =
        run_cli("bake " + (dir / "ok.json").string() + " -o " + out.string() + " --no-render -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_FALSE(fs::exists(stale));
    EXPECT_TRUE(fs::exists(live));
    EXPECT_TRUE(fs::exists(other)); // not one of our outputs
}

// `daylight` needs a sky or a sun: a scene lit by a lamp only is one line naming the scene.
TEST_F(CliBadInput, DaylightWithoutSkyOrSun) {
    write(dir_ / "lamp.json", good_scene());
    const fs::path out = dir_ / "out";
    const RunResult r =
        run_cli("daylight " + (dir_ / "lamp.json").string() + " -o " + out.string() + " -q");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("lamp.json"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("no sky or sun"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
}

// A sun of 10 000 lx normal illuminance at 53.13° altitude over a black floor: every point of
// the work plane receives E_n cos θ = 8 000 lx. `daylight` writes the grid's results and the
// mesh, no render and no solver state; a killed run's temporary grid file is removed.
TEST(CliDaylight, SunlitWorkPlane) {
    const fs::path dir = test::temp_dir("cli-daylight");
    write(dir / "sun.json", R"({
  "materials": {"black": {"reflectance": 0}},
  "polygons": [{"name": "floor", "material": "black",
                "vertices": [[0,0,0],[4,0,0],[4,6,0],[0,6,0]]}],
  "sun": {"direction": [0, -0.6, 0.8], "illuminance_lx": 10000},
  "grids": {"wp": {"floor": "floor", "height": 0.85, "spacing": 0.5, "wall_offset": 0.5}},
  "camera": {"eye": [2, -3, 2], "look_at": [2, 3, 0]},
  "mesher": {"max_edge_length": 1},
  "solver": {"method": "shooting"}
})");
    const fs::path out = dir / "out";
    fs::create_directories(out);
    const pid_t dead = ::fork();
    if (dead == 0)
        ::_exit(0);
    ::waitpid(dead, nullptr, 0);
    const fs::path stale = out / (".grid_wp.png.tmp" + std::to_string(dead));
    write(stale, "partial");
    const RunResult r =
        run_cli("daylight " + (dir / "sun.json").string() + " -o " + out.string() + " -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* f :
         {"mesh.vtu", "sensors.csv", "grids.csv", "grid_wp.png", "grid_wp.vtp", "summary.json"})
        EXPECT_TRUE(fs::exists(out / f)) << f;
    for (const char* f : {"render.png", "render.exr", "solver_state.bin"})
        EXPECT_FALSE(fs::exists(out / f)) << f;
    EXPECT_FALSE(fs::exists(stale));
    std::ifstream in(out / "grids.csv");
    std::string header, row;
    std::getline(in, header);
    std::getline(in, row);
    double avg = 0, min = 0, max = 0, uniformity = 0;
    ASSERT_EQ(
        std::sscanf(row.c_str(), "wp,work_plane,77,%lf,%lf,%lf,%lf", &avg, &min, &max, &uniformity),
        4)
        << row;
    for (double lx : {avg, min, max})
        EXPECT_NEAR(lx, 8000, 8);
    EXPECT_NEAR(uniformity, 1, 1e-3);
    fs::remove_all(dir);
}

// `annual` on an unobstructed black floor under Chicago's year: every output file (the mesh's
// too), one row per sensor, the hourly values' size; bad flags and files (--blinds without
// the scene's shaded state) are one-line errors that leave no output folder.
TEST(CliAnnual, OutputsAndBadInput) {
    const fs::path dir = test::temp_dir("cli-annual");
    write(dir / "floor.json", R"({
  "materials": {"black": {"reflectance": 0}},
  "polygons": [{"name": "floor", "material": "black",
                "vertices": [[0,0,0],[2,0,0],[2,2,0],[0,2,0]]}],
  "grids": {"wp": {"floor": "floor", "height": 0.85, "spacing": 1, "wall_offset": 0.5}},
  "mesher": {"max_edge_length": 1}
})");
    const std::string weather = test::source_path("data/weather/chicago_ohare_tmy3.epw");
    const std::string scene = (dir / "floor.json").string();
    const fs::path out = dir / "out";
    const RunResult r = run_cli("annual " + scene + " --weather " + weather + " -o " +
                                out.string() + " --hourly --mesh -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* f : {"annual.csv", "summary.json", "annual_wp_da.png", "annual_wp.vtp",
                          "hourly_illuminance.f32", "hourly_illuminance.json", "annual_mesh.vtu"})
        EXPECT_TRUE(fs::exists(out / f)) << f;
    std::ifstream csv(out / "annual.csv");
    std::string line;
    int rows = -1; // the header
    while (std::getline(csv, line))
        ++rows;
    EXPECT_GE(rows, 1);
    EXPECT_EQ(fs::file_size(out / "hourly_illuminance.f32"),
              std::uintmax_t(rows) * 8760u * sizeof(float));

    struct Bad {
        std::string args;
        int code;
        std::string says;
    };
    const std::vector<Bad> bad = {
        {"annual " + scene + " --weather " + (dir / "none.epw").string(), 2, "none.epw"},
        {"annual " + scene + " --weather " + weather + " --occupancy 18-8", 3, "--occupancy"},
        {"annual " + scene + " --weather " + weather + " --heat-map nosuch", 3, "nosuch"},
        {"annual " + scene + " --weather " + weather + " --patches 7", 3, "--patches"},
        {"annual " + scene + " --weather " + weather + " --blinds", 2, "annual.blinds"},
    };
    for (const Bad& b : bad) {
        const fs::path fresh = dir / "fresh";
        const RunResult e = run_cli(b.args + " -o " + fresh.string() + " -q");
        EXPECT_EQ(e.exit_code, b.code) << b.args << ": " << e.err;
        EXPECT_EQ(count_lines(e.err), 1) << e.err;
        EXPECT_NE(e.err.find(b.says), std::string::npos) << e.err;
        EXPECT_FALSE(fs::exists(fresh / "annual.csv")) << b.args;
    }
    fs::remove_all(dir);
}

} // namespace
} // namespace penumbra
