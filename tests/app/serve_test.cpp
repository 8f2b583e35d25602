// `penumbra serve`'s request paths (issue #29): `/`, /client/ and /bake/ map to files inside
// their roots; `..`, escapes of it, other prefixes, folders and symbolic links out of a root
// give nothing (404); a busy port is a one-line error. The server's answers are exercised by the
// browser test (client/test/).

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

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

// A port another server listens on is a one-line error (exit 4), even when that server allows
// SO_REUSEPORT: a second `penumbra serve` must not share its connections. Were it to bind, it
// would serve until killed: the run is bounded (exit 124), and the test fails rather than hangs.
TEST(ServeCli, BusyPortIsOneLineError) {
    const int holder = ::socket(AF_INET, SOCK_STREAM, 0);
    ASSERT_GE(holder, 0);
    const int on = 1;
    ::setsockopt(holder, SOL_SOCKET, SO_REUSEPORT, &on, sizeof on);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ASSERT_EQ(::bind(holder, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
    ASSERT_EQ(::listen(holder, 1), 0);
    socklen_t size = sizeof address;
    ::getsockname(holder, reinterpret_cast<sockaddr*>(&address), &size);
    const int port = ntohs(address.sin_port);

    // A bake and a client folder that pass serve's checks (no warning), so that it goes on to bind.
    const fs::path dir = test::temp_dir("serve-busy");
    fs::create_directories(dir / "client/node_modules/three/build");
    for (const fs::path& f : {dir / "scene.gltf", dir / "client/index.html",
                              dir / "client/node_modules/three/build/three.module.js"})
        std::ofstream(f) << "x";
    const test::RunResult busy =
        test::run_cli("serve " + dir.string() + " --client " + (dir / "client").string() +
                          " --port " + std::to_string(port),
                      60);
    ::close(holder);
    EXPECT_EQ(busy.exit_code, 4);
    EXPECT_NE(busy.err.find("cannot listen on 127.0.0.1:" + std::to_string(port)),
              std::string::npos)
        << busy.err;
    EXPECT_NE(busy.err.find("(--port)"), std::string::npos) << busy.err;
    EXPECT_EQ(std::count(busy.err.begin(), busy.err.end(), '\n'), 1) << busy.err;
    fs::remove_all(dir);
}

} // namespace
} // namespace penumbra
