// `penumbra serve`: HTTP/1.1 over POSIX sockets on 127.0.0.1, enough for a browser to load the
// client page and a bake. One detached thread per connection (a browser opens several at once
// and may hold one open without a request), one request per connection, files streamed from
// disk, nothing cached (a re-bake shows on reload).

#include <array>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <string>
#include <system_error>
#include <thread>

#include <arpa/inet.h>
#include <fmt/format.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include "app/serve.h"
#include "core/error.h"

namespace penumbra::app {

namespace {

namespace fs = std::filesystem;

constexpr std::size_t k_max_request_bytes = 16 * 1024;
constexpr int k_socket_timeout_s = 10;

// Closes a socket when it goes out of scope.
struct Socket {
    int fd = -1;
    explicit Socket(int f) : fd(f) {}
    Socket(const Socket&) = delete;
    Socket& operator=(const Socket&) = delete;
    ~Socket() {
        if (fd >= 0)
            ::close(fd);
    }
};

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

// A socket listening on 127.0.0.1:port (0: any free port).
int listen_on_localhost(int port) {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0)
        throw ExternalError(fmt::format("serve: socket: {}", std::strerror(errno)));
    const int on = 1;
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(std::uint16_t(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0 ||
        ::listen(fd, 64) != 0) {
        const int error = errno;
        ::close(fd);
        throw ExternalError(fmt::format("serve: cannot listen on 127.0.0.1:{}: {} (--port)", port,
                                        std::strerror(error)));
    }
    return fd;
}

int bound_port(int fd) {
    sockaddr_in address{};
    socklen_t size = sizeof address;
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size);
    return ntohs(address.sin_port);
}

bool send_all(int fd, const char* data, std::size_t size) {
    while (size > 0) {
        const ssize_t sent = ::send(fd, data, size, MSG_NOSIGNAL);
        if (sent < 0 && errno == EINTR)
            continue;
        if (sent <= 0)
            return false;
        data += sent;
        size -= std::size_t(sent);
    }
    return true;
}

// The request's head (up to the blank line), or what came before the peer stopped.
std::string read_head(int fd) {
    std::string head;
    std::array<char, 4096> buffer{};
    while (head.find("\r\n\r\n") == std::string::npos && head.size() < k_max_request_bytes) {
        const ssize_t got = ::recv(fd, buffer.data(), buffer.size(), 0);
        if (got < 0 && errno == EINTR)
            continue;
        if (got <= 0)
            break;
        head.append(buffer.data(), std::size_t(got));
    }
    return head;
}

void send_status(int fd, int code, const char* reason) {
    const std::string body = fmt::format("{} {}\n", code, reason);
    const std::string response =
        fmt::format("HTTP/1.1 {} {}\r\nContent-Type: text/plain; charset=utf-8\r\n"
                    "Content-Length: {}\r\nConnection: close\r\n\r\n{}",
                    code, reason, body.size(), body);
    send_all(fd, response.data(), response.size());
}

void send_file(int fd, const fs::path& file, bool with_body) {
    std::ifstream in(file, std::ios::binary);
    std::error_code ec;
    const auto size = fs::file_size(file, ec);
    if (!in || ec) {
        send_status(fd, 404, "Not Found");
        return;
    }
    const std::string head = fmt::format("HTTP/1.1 200 OK\r\nContent-Type: {}\r\n"
                                         "Content-Length: {}\r\nCache-Control: no-store\r\n"
                                         "Connection: close\r\n\r\n",
                                         content_type(file), size);
    if (!send_all(fd, head.data(), head.size()) || !with_body)
        return;
    std::array<char, 64 * 1024> buffer{};
    while (in.read(buffer.data(), buffer.size()) || in.gcount() > 0)
        if (!send_all(fd, buffer.data(), std::size_t(in.gcount())))
            return;
}

// Answers one request on \p fd.
void answer(const ServeRoots& roots, int fd, const Context& ctx) {
    const timeval timeout{k_socket_timeout_s, 0};
    ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof timeout);
    const std::string head = read_head(fd);
    if (head.empty())
        return; // a connection opened ahead of need and closed unused
    const std::string line = head.substr(0, head.find("\r\n"));
    const std::size_t space1 = line.find(' '), space2 = line.rfind(' ');
    if (space1 == std::string::npos || space2 <= space1 || line.compare(space2, 6, " HTTP/") != 0)
        return send_status(fd, 400, "Bad Request");
    const std::string method = line.substr(0, space1);
    const std::string target = line.substr(space1 + 1, space2 - space1 - 1);
    if (method != "GET" && method != "HEAD")
        return send_status(fd, 405, "Method Not Allowed");
    const std::optional<fs::path> file = resolve_request(roots, target);
    ctx.debug("serve: {} {} -> {}", method, target, file ? file->string() : "404");
    if (!file)
        return send_status(fd, 404, "Not Found");
    send_file(fd, *file, method == "GET");
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
    const Socket listener(listen_on_localhost(options.port));
    listening(bound_port(listener.fd));
    for (;;) {
        const int fd = ::accept4(listener.fd, nullptr, nullptr, SOCK_CLOEXEC);
        if (fd < 0) {
            if (errno == EINTR || errno == ECONNABORTED)
                continue;
            // Out of descriptors: the open connections close within their timeout.
            if (errno == EMFILE || errno == ENFILE) {
                std::this_thread::sleep_for(std::chrono::milliseconds(50));
                continue;
            }
            throw ExternalError(fmt::format("serve: accept: {}", std::strerror(errno)));
        }
        std::thread([roots = options.roots, fd, ctx] {
            const Socket connection(fd);
            answer(roots, connection.fd, ctx);
        }).detach();
    }
}

} // namespace penumbra::app
