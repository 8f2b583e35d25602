// Bounded memory (issue #32, docs/memory.md): the documented bytes per element, node, link,
// pixel and texel are the code's (a changed structure cannot leave the table stale), the
// limit's parsing, and the refinement check against the system a solve really builds.

#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "common/bake_util.h"
#include "common/test_util.h"
#include "core/error.h"
#include "core/memory.h"
#include "hierarchical_system.h"
#include "memory/memory_use.h"
#include "memory_checks.h"
#include "mesher/mesher.h"
#include "raytrace/raytrace.h"

namespace penumbra {
namespace {

// The rows "| `k_name` | bytes | …" of docs/memory.md.
std::map<std::string, std::size_t> documented_figures() {
    std::ifstream in(test::source_path("docs/memory.md"));
    const std::regex row(R"(^\| `(k_[a-z_]+)` \| (\d+) \|)");
    std::map<std::string, std::size_t> out;
    std::smatch m;
    for (std::string line; std::getline(in, line);)
        if (std::regex_search(line, m, row))
            out[m[1]] = std::stoul(m[2]);
    return out;
}

TEST(MemoryFigures, DocumentedFiguresMatchTheCode) {
    const std::map<std::string, std::size_t> code = {
        {"k_mesh_bytes_per_element", k_mesh_bytes_per_element},
        {"k_triangulation_bytes_per_element", k_triangulation_bytes_per_element},
        {"k_hierarchy_bytes_per_node", solver::k_hierarchy_bytes_per_node},
        {"k_values_bytes_per_node", solver::k_values_bytes_per_node},
        {"k_bytes_per_node", solver::k_bytes_per_node},
        {"k_bytes_per_element_link", solver::k_bytes_per_element_link},
        {"k_bytes_per_cluster_link", solver::k_bytes_per_cluster_link},
        {"k_bytes_per_light_link", solver::k_bytes_per_light_link},
        {"k_render_bytes_per_pixel", k_render_bytes_per_pixel},
        {"k_lightmap_bytes_per_texel", app::k_lightmap_bytes_per_texel},
        {"k_lightmap_bytes_per_covered_texel", app::k_lightmap_bytes_per_covered_texel},
        {"k_hourly_matrices", app::k_hourly_matrices},
    };
    EXPECT_EQ(documented_figures(), code);
}

TEST(MemoryLimit, SizesParseInPowersOf1024) {
    EXPECT_EQ(parse_memory_size("1048576"), 1048576u);
    EXPECT_EQ(parse_memory_size("500M"), 500u << 20);
    EXPECT_EQ(parse_memory_size("4G"), std::uint64_t(4) << 30);
    EXPECT_EQ(parse_memory_size("4g"), std::uint64_t(4) << 30);
    EXPECT_EQ(parse_memory_size("1.5GiB"), std::uint64_t(3) << 29);
    EXPECT_EQ(parse_memory_size("2KB"), 2048u);
    EXPECT_EQ(parse_memory_size("1T"), std::uint64_t(1) << 40);
    EXPECT_EQ(parse_memory_size("0"), 0u);
    for (const char* bad : {"", "G", "nan", "inf", "-1G", "0.5", "4X", "4 G", "4GB ", "1e400",
                            "5000P", "8E", "4iB", "1e30"})
        EXPECT_FALSE(parse_memory_size(bad)) << bad;
}

TEST(MemoryLimit, DefaultIsAFractionOfWhatTheMachineHas) {
    const std::uint64_t available = available_memory_bytes();
    ASSERT_GT(available, 0u);
    EXPECT_NEAR(double(default_memory_limit_bytes()), k_default_memory_fraction * double(available),
                1.0);
}

TEST(MemoryLimit, OverTheLimitIsOneLineNamingBothSizes) {
    EXPECT_NO_THROW(check_memory(0, "x", 1e30, "y")); // no limit
    EXPECT_NO_THROW(check_memory(1024, "x", 1024, "y"));
    try {
        check_memory(std::uint64_t(200) << 20, "solve: a pass", 3.5 * double(1 << 30),
                     "use a larger solver.epsilon");
        FAIL() << "no error";
    } catch (const ConfigError& e) {
        EXPECT_STREQ(e.what(), "solve: a pass needs about 3.5 GiB, over the memory limit of 200 "
                               "MiB (--max-memory): use a larger solver.epsilon, or raise "
                               "--max-memory");
    }
}

using solver::HierarchicalSystem;

class RefinementMemory : public ::testing::TestWithParam<Clustering> {};

// What the check counts before each pass is at least what the pass makes: a limit below the
// system a solve ends with stops it; one well above lets it through to the same bits.
TEST_P(RefinementMemory, CheckCountsAtLeastWhatRefinementMakes) {
    Scene scene = test::cornell_box(0.5);
    scene.solver.epsilon = 1e-2;
    scene.solver.clustering = GetParam();
    const RadiosityMesh mesh = mesher::build_mesh(scene, test::quiet_context());
    const raytrace::EmbreeScene embree(mesh);
    auto build = [&](std::uint64_t limit) {
        Context ctx = test::quiet_context();
        ctx.max_memory_bytes = limit;
        ProgressStage progress(ctx, "hierarchical");
        solver::SweepLog log{mesh, nullptr, nullptr};
        return solver::build_hierarchical(scene, mesh, embree, ctx, progress, log, nullptr);
    };
    const std::unique_ptr<HierarchicalSystem> free = build(0);
    const solver::LinkStore& links = free->links;
    const double bytes =
        solver::system_bytes({free->h.size(), links.links().size(), links.cluster_links().size(),
                              links.light_links().size()});
    ASSERT_GT(free->h.size(), free->h.root_count); // refined
    EXPECT_THROW(build(std::uint64_t(0.9 * bytes)), ConfigError);
    const std::unique_ptr<HierarchicalSystem> limited = build(std::uint64_t(4 * bytes));
    ASSERT_EQ(limited->values.b.size(), free->values.b.size());
    EXPECT_EQ(std::memcmp(limited->values.b.data(), free->values.b.data(),
                          free->values.b.size() * sizeof(Rgb)),
              0);
}

INSTANTIATE_TEST_SUITE_P(Clusterings, RefinementMemory,
                         ::testing::Values(Clustering::off, Clustering::on),
                         [](const auto& info) { return std::string(enum_name(info.param)); });

} // namespace
} // namespace penumbra
