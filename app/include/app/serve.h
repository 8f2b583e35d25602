#pragma once
// `penumbra serve` (issue #29): a small HTTP server on localhost that shows a lightmap bake in
// the browser client (client/index.html). It serves files only, read-only, from two folders.

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "core/context.h"

namespace penumbra::app {

/// \brief The two folders a server reads: the client page's and the bake's.
struct ServeRoots {
    std::filesystem::path client; ///< client/: index.html, src/, node_modules/three/
    std::filesystem::path bake;   ///< a `penumbra lightmap` output folder
};

/// \brief The file a request target names, or nothing (then the answer is 404): `/` is the
///        client's index.html, `/client/P` the client's file P, `/bake/P` the bake's file P.
///        The query is ignored. Percent escapes are decoded; a path with an empty, `.` or `..`
///        segment, a backslash or a NUL is refused, and so is a file that is not a regular file
///        inside its root once symbolic links are resolved.
std::optional<std::filesystem::path> resolve_request(const ServeRoots& roots,
                                                     std::string_view target);

/// \brief The Content-Type of a file by its extension (application/octet-stream when unknown).
std::string content_type(const std::filesystem::path& file);

/// \brief Settings of serve().
struct ServeOptions {
    ServeRoots roots;
    int port = 8000; ///< 0: a free port chosen by the system
};

/// \brief Serves GET and HEAD requests on 127.0.0.1 until the process is stopped (cpp-httplib's
///        server: a pool of threads, keep-alive connections; other methods get 405). Calls
///        \p listening with the port once it accepts connections.
/// \throws ConfigError when a root is missing or the client's three.js is not installed (a
///         bake folder without scene.gltf is a warning),
///         ExternalError when the port cannot be bound or the server stops accepting.
void serve(const ServeOptions& options, const Context& ctx,
           const std::function<void(int port)>& listening);

} // namespace penumbra::app
