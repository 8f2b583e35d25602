// Issue #4: a re-solve after a material change keeps the hierarchy and links of the earlier
// solve (solver_state.bin), takes the new reflectances, re-runs the oracle and iterates; it
// must equal a full solve of the changed scene.

#include <algorithm>
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "app/pipeline.h"
#include "common/bake_util.h"
#include "common/test_util.h"
#include "core/error.h"
#include "core/files.h"
#include "core/rng.h"
#include "core/scene_io.h"
#include "state/solver_state.h"

namespace penumbra {
namespace {

// Bakes without the render, as a re-solve from \p reuse when given.
app::BakeResult bake(const Scene& scene, const solver::HierarchicalState* reuse = nullptr) {
    return test::bake(scene, 0, reuse);
}

Scene cornell(double max_edge = 0.1, double epsilon = 3e-3) {
    Scene scene = load_scene(test::source_path("data/cornell/scene.json"));
    scene.mesher.max_edge_length = max_edge;
    scene.solver.epsilon = epsilon;
    return scene;
}

// A coarse solve for the tests of the state itself.
Scene coarse_cornell() {
    return cornell(0.2, 3e-2);
}

std::uint32_t material_index(const Scene& scene, const std::string& name) {
    for (std::uint32_t m = 0; m < scene.materials.size(); ++m)
        if (scene.materials[m].name == name)
            return m;
    throw std::runtime_error("no material " + name);
}

TEST(Reuse, ResolveAfterReflectanceChangeEqualsFullSolve) {
    Scene before = cornell();
    const app::BakeResult first = bake(before);
    ASSERT_TRUE(first.solver_state);
    Scene after = before;
    after.materials[material_index(after, "red")].reflectance = Rgb(0.2f, 0.3f, 0.8f);
    const app::BakeResult resolved = bake(after, first.solver_state.get());
    const app::BakeResult full = bake(after);
    const double change = test::relative_patch_l1(first, full);
    const double error = test::relative_patch_l1(resolved, full);
    std::printf("patch L1: before vs after %.4f, re-solve vs full solve %.2e\n", change, error);
    EXPECT_GT(change, 0.01); // the change matters
    EXPECT_LT(error, 1e-3);
    // Point values differ by the two solves' refinements (their accuracy at this ε).
    for (std::size_t s = 0; s < full.sensors.size(); ++s)
        EXPECT_NEAR(resolved.sensors[s].illuminance_total_lx, full.sensors[s].illuminance_total_lx,
                    0.015 * full.sensors[s].illuminance_total_lx)
            << "sensor " << s;
}

// Without keep_state (the CLI's --no-state) the bake frees the links with the solve: its
// result holds no state, and its solution is the same, element by element.
TEST(Reuse, BakeWithoutStateKeepsNoLinks) {
    const Scene scene = coarse_cornell();
    app::BakeOptions options;
    options.render = false;
    options.keep_state = false;
    const app::BakeResult without = app::bake(scene, options, test::quiet_context());
    const app::BakeResult with = bake(scene);
    EXPECT_FALSE(without.solver_state);
    ASSERT_TRUE(with.solver_state);
    ASSERT_EQ(without.solution.radiosity.size(), with.solution.radiosity.size());
    std::size_t differ = 0;
    for (std::size_t e = 0; e < with.solution.radiosity.size(); ++e) {
        const Rgb a = without.solution.radiosity[e], b = with.solution.radiosity[e];
        differ += a.r != b.r || a.g != b.g || a.b != b.b;
    }
    EXPECT_EQ(differ, 0u);
}

TEST(Reuse, RefusesAnotherGeometry) {
    Scene scene = coarse_cornell();
    const app::BakeResult first = bake(scene);
    scene.mesher.max_edge_length = 0.25;
    EXPECT_THROW(bake(scene, first.solver_state.get()), ConfigError);
}

TEST(Reuse, StateFileRoundTrips) {
    const Scene scene = coarse_cornell();
    const app::BakeResult first = bake(scene);
    const std::string dir = test::temp_dir("reuse_state");
    app::write_outputs(dir, scene, first);
    const auto read = solver::read_hierarchical_state(dir + "/" + app::k_solver_state_file);
    const app::BakeResult from_file = bake(scene, read.get());
    const app::BakeResult from_memory = bake(scene, first.solver_state.get());
    ASSERT_EQ(from_file.solution.radiosity.size(), from_memory.solution.radiosity.size());
    for (std::size_t e = 0; e < from_file.solution.radiosity.size(); ++e)
        ASSERT_EQ(from_file.solution.radiosity[e], from_memory.solution.radiosity[e]);
    EXPECT_THROW(solver::read_hierarchical_state(dir + "/summary.json"), InputError);
}

// Issue #32: a state file with a few corrupted bytes was accepted (21 of 34 corruptions) and
// gave NaN sensors; its checksum now refuses any one corrupted byte, and an intact file reads.
TEST(Reuse, StateFileRefusesEveryCorruptedByte) {
    const Scene scene = coarse_cornell();
    const app::BakeResult first = bake(scene);
    const std::string dir = test::temp_dir("reuse_corrupt");
    app::write_outputs(dir, scene, first);
    const std::string path = dir + "/" + app::k_solver_state_file;
    const std::string intact = read_text_file(path);
    constexpr std::size_t k_positions = 34;
    std::size_t accepted = 0;
    for (std::size_t i = 0; i < k_positions; ++i) {
        std::string bytes = intact;
        bytes[i * (bytes.size() - 1) / (k_positions - 1)] ^= char(0x5a);
        write_text_file(path, bytes);
        try {
            solver::read_hierarchical_state(path);
            ++accepted;
        } catch (const InputError&) {
        }
    }
    EXPECT_EQ(accepted, 0u);
    write_text_file(path, intact);
    const auto read = solver::read_hierarchical_state(path);
    EXPECT_EQ(read->mesh_hash, first.solver_state->mesh_hash);
    EXPECT_EQ(read->radiosity, first.solver_state->radiosity);
    EXPECT_EQ(read->hierarchy.area, first.solver_state->hierarchy.area);
    EXPECT_EQ(read->links.size(), first.solver_state->links.size());
}

// The state file is written and read as a stream, its checksum computed piece by piece (a
// second copy of the links was held to hash them). Its last word must still be the checksum of
// the bytes before it as one piece, computed here on its own (core/rng.h's mix64 over 64-bit
// words, from the byte count), so that files of earlier builds stay readable.
TEST(Reuse, StreamedChecksumIsTheChecksumOfTheWholeFile) {
    const Scene scene = coarse_cornell();
    const app::BakeResult first = bake(scene);
    const std::string dir = test::temp_dir("reuse_checksum");
    app::write_outputs(dir, scene, first);
    const std::string bytes = read_text_file(dir + "/" + app::k_solver_state_file);
    ASSERT_GT(bytes.size(), 16u);
    const std::size_t payload = bytes.size() - sizeof(std::uint64_t);
    std::uint64_t h = hash_words({payload});
    for (std::size_t at = 0; at < payload; at += 8) {
        std::uint64_t word = 0;
        std::memcpy(&word, bytes.data() + at, std::min<std::size_t>(8, payload - at));
        h = mix64(h ^ mix64(word + 0x632be59bd9b4e019ULL));
    }
    std::uint64_t stored = 0;
    std::memcpy(&stored, bytes.data() + payload, sizeof(stored));
    EXPECT_EQ(stored, h);
    EXPECT_EQ(solver::state_checksum({bytes.data(), payload}), h);
    EXPECT_EQ(bytes.compare(0, 8, "PNBRHRS9"), 0);
}

} // namespace
} // namespace penumbra
