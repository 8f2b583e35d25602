// Issue #32: a full disk gave a VTK pipeline dump or "cannot write …" without the reason. Each
// output now fails with one line naming the file and the system's reason, exit 4, and leaves
// neither the file nor its temporary. A file size limit (RLIMIT_FSIZE) stands in for the full
// disk: write(2) then fails with EFBIG ("File too large") where a full disk gives ENOSPC, on
// the same path. Each limit is set from the files of the same bake run without one.

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "common/test_util.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

using test::RunResult;

/// The size of every file in \p dir, by name.
std::map<std::string, std::uintmax_t> file_sizes(const fs::path& dir) {
    std::map<std::string, std::uintmax_t> sizes;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.is_regular_file())
            sizes[entry.path().filename().string()] = entry.file_size();
    return sizes;
}

/// The files whose names hold ".tmp": temporaries of write_atomically.
std::vector<std::string> temporaries(const fs::path& dir) {
    std::vector<std::string> found;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.path().filename().string().find(".tmp") != std::string::npos)
            found.push_back(entry.path().filename().string());
    return found;
}

/// Runs the bake \p args into \p out under a limit of \p max_bytes per file and checks the
/// one-line message naming \p file, exit 4, and that neither \p file nor a temporary is left.
void expect_file_too_large(std::vector<std::string> args, const fs::path& out,
                           std::uintmax_t max_bytes, const std::string& file) {
    args.insert(args.end(), {"-o", out.string(), "-q"});
    const RunResult r = test::run_cli_with_file_limit(args, max_bytes);
    EXPECT_EQ(r.exit_code, 4) << r.err;
    EXPECT_EQ(r.err, fmt::format("penumbra: error: cannot write '{}': {}\n", (out / file).string(),
                                 std::strerror(EFBIG)));
    EXPECT_FALSE(fs::exists(out / file));
    EXPECT_TRUE(temporaries(out).empty());
}

// The Cornell box: mesh.vtu is the first file written; solver_state.bin, the largest, comes
// after the others but summary.json. The files written before a failure are whole.
TEST(CliFullDisk, CornellBakeStopsAtTheFileTooLarge) {
    const fs::path dir = test::temp_dir("cli_full_disk");
    // Coarse and loose: the test is of the outputs, not of the solve.
    std::vector<std::string> bake{"bake", test::source_path("data/cornell/scene.json")};
    bake.insert(bake.end(),
                {"--max-edge", "0.3", "--epsilon", "0.03", "--residual", "0.01", "--no-render"});
    std::vector<std::string> unlimited = bake;
    unlimited.insert(unlimited.end(), {"-o", (dir / "whole").string(), "-q"});
    ASSERT_EQ(test::run_cli_with_file_limit(unlimited, std::uint64_t(1) << 40).exit_code, 0);
    const auto whole = file_sizes(dir / "whole");
    const std::uintmax_t mesh = whole.at("mesh.vtu"), state = whole.at("solver_state.bin");
    ASSERT_LT(whole.at("summary.json"), mesh / 2) << "a limit must let summary-sized files pass";

    expect_file_too_large(bake, dir / "mesh", mesh / 2, "mesh.vtu");
    EXPECT_TRUE(fs::is_empty(dir / "mesh"));

    for (const auto& [name, size] : whole) {
        if (name != "solver_state.bin") {
            ASSERT_LT(size, state - 1) << name << " would fail before the state file";
        }
    }
    expect_file_too_large(bake, dir / "state", state - 1, "solver_state.bin");
    EXPECT_EQ(fs::file_size(dir / "state" / "mesh.vtu"), mesh);
    fs::remove_all(dir);
}

// A small scene with a camera: render.exr, larger than the meshes written before it, fails.
TEST(CliFullDisk, RenderImageStopsAtTheFileTooLarge) {
    const fs::path dir = test::temp_dir("cli_full_disk_render");
    std::ofstream(dir / "scene.json") << R"({
  "materials": {"lamp": {"emission": [1, 1, 1], "reflectance": 0}, "floor": {"reflectance": 0.5}},
  "polygons": [
    {"name": "lamp", "material": "lamp", "vertices": [[0,0,1],[0,1,1],[1,1,1],[1,0,1]]},
    {"name": "floor", "material": "floor", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}
  ],
  "mesher": {"max_edge_length": 0.5},
  "camera": {"eye": [0.5, -1.5, 0.6], "look_at": [0.5, 0.5, 0.3], "up": [0, 0, 1], "fov_deg": 50},
  "image": {"width": 320, "height": 240, "spp": 1}
}
)";
    const std::vector<std::string> bake{"bake", (dir / "scene.json").string()};
    std::vector<std::string> unlimited = bake;
    unlimited.insert(unlimited.end(), {"-o", (dir / "whole").string(), "-q"});
    ASSERT_EQ(test::run_cli_with_file_limit(unlimited, std::uint64_t(1) << 40).exit_code, 0);
    const auto whole = file_sizes(dir / "whole");
    const std::uintmax_t exr = whole.at("render.exr");
    for (const char* before : {"mesh.vtu", "discontinuities.vtp"}) {
        if (whole.count(before)) {
            ASSERT_LT(whole.at(before), exr - 1) << before << " would fail before render.exr";
        }
    }
    expect_file_too_large(bake, dir / "out", exr - 1, "render.exr");
    fs::remove_all(dir);
}

} // namespace
} // namespace penumbra
