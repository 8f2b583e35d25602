// `penumbra serve`: cpp-httplib's server on 127.0.0.1, enough for a browser to load the client
// page and a bake. resolve_request picks the file from the raw request target (so its rules on
// escapes and symbolic links hold), files are streamed from disk, nothing is cached (a re-bake
// shows on reload).

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <system_error>

#include <fmt/format.h>
#include <httplib.h>
#include <sys/socket.h>

#include "app/serve.h"
#include "core/error.h"

namespace penumbra::app {

namespace {

namespace fs = std::filesystem;

constexpr std::size_t k_chunk_bytes = 64 * 1024;

void check_roots(const ServeRoots& roots) {
    std::error_code ec;
    if (!fs::is_directory(roots.bake, ec))
        throw ConfigError(fmt::format("serve: '{}' is not a folder", roots.bake.string()));
    if (!fs::exists(roots.client / "index.html", ec))
        throw ConfigError(fmt::format("serve: the client page '{}' is missing (--client)",
                                      (roots.client / "index.html").string()));
    if (!fs::exists(roots.client / "node_modules/three/build/three.module.js", ec))
        throw ConfigError(fmt::format("serve: three.js is not installed in '{}': run "
                                      "scripts/setup.sh --deps (npm ci in client/)",
                                      roots.client.string()));
}

// cpp-httplib's default sets SO_REUSEPORT, with which a second server on a busy port would
// bind too and share its connections; SO_REUSEADDR alone only allows a restart.
void reuse_address_only(int socket) {
    const int on = 1;
    ::setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
}

// Binds 127.0.0.1:port (0: any free port); returns the bound port.
int bind_to_localhost(httplib::Server& server, int port) {
    errno = 0;
    int bound = port;
    if (port == 0)
        bound = server.bind_to_any_port("127.0.0.1");
    else if (!server.bind_to_port("127.0.0.1", port))
        bound = -1;
    if (bound < 0) {
        // httplib reports no reason; errno is bind's or listen's (the calls after them keep it).
        const char* reason = errno != 0 ? std::strerror(errno) : "cannot bind";
        throw ExternalError(
            fmt::format("serve: cannot listen on 127.0.0.1:{}: {} (--port)", port, reason));
    }
    return bound;
}

// The file as the response's body, read in chunks as httplib sends it (HEAD reads nothing).
void send_file(const fs::path& file, httplib::Response& response) {
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(file, ec);
    auto in = std::make_shared<std::ifstream>(file, std::ios::binary);
    if (ec || !*in) {
        response.status = 404;
        return;
    }
    response.set_header("Cache-Control", "no-store");
    // httplib treats a provider of length 0 as one of unknown length (chunked).
    if (size == 0) {
        response.set_content("", content_type(file));
        return;
    }
    response.set_content_provider(
        std::size_t(size), content_type(file),
        [in](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
            std::array<char, k_chunk_bytes> buffer{};
            in->seekg(std::streamoff(offset));
            in->read(buffer.data(), std::streamsize(std::min(length, buffer.size())));
            const std::streamsize got = in->gcount();
            // A file that shrank while being sent ends the connection.
            return got > 0 && sink.write(buffer.data(), std::size_t(got));
        });
}

} // namespace

void serve(const ServeOptions& options, const Context& ctx,
           const std::function<void(int port)>& listening) {
    check_roots(options.roots);
    // Not an error: ?gltf=PATH shows a glTF elsewhere under the folder (the browser test's).
    if (std::error_code ec; !fs::exists(options.roots.bake / "scene.gltf", ec))
        ctx.warn("serve: '{}' holds no scene.gltf (bake one with `penumbra lightmap SCENE -o "
                 "{}`); the page at / will say so",
                 options.roots.bake.string(), options.roots.bake.string());
    httplib::Server server;
    server.set_socket_options(reuse_address_only);
    server.set_pre_routing_handler(
        [](const httplib::Request& request, httplib::Response& response) {
            if (request.method == "GET" || request.method == "HEAD")
                return httplib::Server::HandlerResponse::Unhandled;
            response.status = 405;
            response.set_header("Allow", "GET, HEAD");
            return httplib::Server::HandlerResponse::Handled;
        });
    server.Get(".*", [&](const httplib::Request& request, httplib::Response& response) {
        // request.target is the target as sent: resolve_request decodes it once, itself.
        const std::optional<fs::path> file = resolve_request(options.roots, request.target);
        ctx.debug("serve: {} {} -> {}", request.method, request.target,
                  file ? file->string() : "404");
        if (!file) {
            response.status = 404;
            return;
        }
        send_file(*file, response);
    });
    const int port = bind_to_localhost(server, options.port);
    listening(port);
    if (!server.listen_after_bind())
        throw ExternalError(fmt::format("serve: 127.0.0.1:{} stopped accepting connections: {}",
                                        port, std::strerror(errno)));
}

} // namespace penumbra::app
