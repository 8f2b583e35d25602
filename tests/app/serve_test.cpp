// `penumbra serve`'s request paths (issue #29): `/`, /client/ and /bake/ map to files inside
// their roots; `..`, escapes of it, other prefixes, folders and symbolic links out of a root
// give nothing (404). The server itself is exercised by the browser test (client/test/).

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "app/serve.h"
#include "common/test_util.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

struct ServeRootsFixture : ::testing::Test {
    fs::path dir = test::temp_dir("serve-paths");
    app::ServeRoots roots{dir / "client", dir / "bake"};

    void SetUp() override {
        for (const fs::path& d : {roots.client / "src", roots.bake / "sub"})
            fs::create_directories(d);
        for (const fs::path& f :
             {roots.client / "index.html", roots.client / "src" / "main.js",
              roots.bake / "scene.gltf", roots.bake / "sub" / "a b.png", dir / "secret.txt"})
            std::ofstream(f) << "x";
        fs::create_symlink(dir / "secret.txt", roots.bake / "link.txt");
    }
    void TearDown() override { fs::remove_all(dir); }

    fs::path canonical(const fs::path& p) const { return fs::canonical(p); }
};

TEST_F(ServeRootsFixture, MapsTheRootAndBothFolders) {
    EXPECT_EQ(app::resolve_request(roots, "/"), canonical(roots.client / "index.html"));
    EXPECT_EQ(app::resolve_request(roots, "/?gltf=sub/scene.gltf"),
              canonical(roots.client / "index.html"));
    EXPECT_EQ(app::resolve_request(roots, "/client/src/main.js"),
              canonical(roots.client / "src" / "main.js"));
    EXPECT_EQ(app::resolve_request(roots, "/bake/scene.gltf?x=1"),
              canonical(roots.bake / "scene.gltf"));
    EXPECT_EQ(app::resolve_request(roots, "/bake/sub/a%20b.png"),
              canonical(roots.bake / "sub" / "a b.png"));
}

TEST_F(ServeRootsFixture, RefusesEverythingOutsideTheRoots) {
    for (const char* target :
         {"/bake/../secret.txt", "/bake/%2e%2e/secret.txt", "/bake/%2E%2E%2Fsecret.txt",
          "/bake/sub/../../secret.txt", "/bake/./scene.gltf", "/bake//scene.gltf",
          "/bake/..%5csecret.txt", "/bake/scene.gltf%00", "/bake/%zz", "/bake/%2", "/secret.txt",
          "/other/scene.gltf", "/bake", "/bake/", "/bake/sub", "/bake/link.txt", "bake/scene.gltf",
          "", "/bake/missing.png"})
        EXPECT_FALSE(app::resolve_request(roots, target).has_value()) << target;
}

TEST(ServeContentType, ByExtension) {
    EXPECT_EQ(app::content_type("a/scene.gltf"), "model/gltf+json");
    EXPECT_EQ(app::content_type("main.js"), "text/javascript; charset=utf-8");
    EXPECT_EQ(app::content_type("lightmap_0.png"), "image/png");
    EXPECT_EQ(app::content_type("scene.bin"), "application/octet-stream");
    EXPECT_EQ(app::content_type("README"), "application/octet-stream");
}

// Bad arguments end at once with one line naming the problem (exit 3), before any socket.
TEST(ServeCli, BadArgumentsAreOneLineErrors) {
    const fs::path dir = test::temp_dir("serve-cli");
    const test::RunResult missing = test::run_cli("serve " + (dir / "missing").string());
    EXPECT_EQ(missing.exit_code, 3);
    EXPECT_NE(missing.err.find("is not a folder"), std::string::npos) << missing.err;
    const test::RunResult no_client =
        test::run_cli("serve " + dir.string() + " --client " + (dir / "nothing").string());
    EXPECT_EQ(no_client.exit_code, 3);
    EXPECT_NE(no_client.err.find("client page"), std::string::npos) << no_client.err;
    const test::RunResult port = test::run_cli("serve " + dir.string() + " --port 70000");
    EXPECT_EQ(port.exit_code, 3);
    EXPECT_NE(port.err.find("--port"), std::string::npos) << port.err;
    fs::remove_all(dir);
}

} // namespace
} // namespace penumbra
