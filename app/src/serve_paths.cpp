// Which file a request of `penumbra serve` names. The server answers only with regular files
// inside its two roots: the checks run on the decoded path's segments and again on the file's
// canonical path, so neither `..` nor a symbolic link leads outside.

#include <algorithm>
#include <cctype>
#include <string>
#include <system_error>
#include <vector>

#include "app/serve.h"

namespace penumbra::app {

namespace {

namespace fs = std::filesystem;

int hex_value(char c) {
    if (c >= '0' && c <= '9')
        return c - '0';
    const char lower = char(std::tolower(static_cast<unsigned char>(c)));
    return lower >= 'a' && lower <= 'f' ? lower - 'a' + 10 : -1;
}

// The path with its %XX escapes decoded; nothing for a broken escape.
std::optional<std::string> percent_decode(std::string_view path) {
    std::string out;
    for (std::size_t i = 0; i < path.size(); ++i) {
        if (path[i] != '%') {
            out += path[i];
            continue;
        }
        if (i + 2 >= path.size())
            return std::nullopt;
        const int hi = hex_value(path[i + 1]), lo = hex_value(path[i + 2]);
        if (hi < 0 || lo < 0)
            return std::nullopt;
        out += char(hi * 16 + lo);
        i += 2;
    }
    return out;
}

// The '/'-separated segments of \p path (after its leading '/'); nothing when one is empty,
// "." or "..", or holds a backslash or a NUL.
std::optional<std::vector<std::string>> safe_segments(const std::string& path) {
    std::vector<std::string> out;
    std::size_t start = 1;
    while (start <= path.size()) {
        const std::size_t end = std::min(path.find('/', start), path.size());
        const std::string segment = path.substr(start, end - start);
        if (segment.empty() || segment == "." || segment == ".." ||
            segment.find_first_of(std::string("\\\0", 2)) != std::string::npos)
            return std::nullopt;
        out.push_back(segment);
        start = end + 1;
    }
    return out;
}

// root/segments… when that is a regular file whose canonical path lies inside root's.
std::optional<fs::path> file_inside(const fs::path& root,
                                    const std::vector<std::string>& segments) {
    fs::path file = root;
    for (const std::string& s : segments)
        file /= s;
    std::error_code ec;
    const fs::path canonical_root = fs::canonical(root, ec);
    if (ec)
        return std::nullopt;
    const fs::path canonical_file = fs::canonical(file, ec);
    if (ec || !fs::is_regular_file(canonical_file, ec))
        return std::nullopt;
    const auto root_end = std::mismatch(canonical_root.begin(), canonical_root.end(),
                                        canonical_file.begin(), canonical_file.end())
                              .first;
    if (root_end != canonical_root.end())
        return std::nullopt;
    return canonical_file;
}

} // namespace

std::optional<fs::path> resolve_request(const ServeRoots& roots, std::string_view target) {
    target = target.substr(0, target.find('?'));
    if (target.empty() || target.front() != '/')
        return std::nullopt;
    if (target == "/")
        return file_inside(roots.client, {"index.html"});
    const std::optional<std::string> path = percent_decode(target);
    if (!path)
        return std::nullopt;
    const auto segments = safe_segments(*path);
    if (!segments || segments->size() < 2)
        return std::nullopt;
    const std::string& root = segments->front();
    const std::vector<std::string> rest(segments->begin() + 1, segments->end());
    if (root == "client")
        return file_inside(roots.client, rest);
    if (root == "bake")
        return file_inside(roots.bake, rest);
    return std::nullopt;
}

std::string content_type(const fs::path& file) {
    static constexpr std::pair<const char*, const char*> k_types[] = {
        {".html", "text/html; charset=utf-8"},
        {".js", "text/javascript; charset=utf-8"},
        {".mjs", "text/javascript; charset=utf-8"},
        {".css", "text/css; charset=utf-8"},
        {".json", "application/json"},
        {".gltf", "model/gltf+json"},
        {".glb", "model/gltf-binary"},
        {".bin", "application/octet-stream"},
        {".png", "image/png"},
        {".jpg", "image/jpeg"},
        {".exr", "image/x-exr"},
        {".vtu", "application/xml"},
        {".txt", "text/plain; charset=utf-8"},
        {".csv", "text/csv; charset=utf-8"},
    };
    const std::string extension = file.extension().string();
    for (const auto& [ext, type] : k_types)
        if (extension == ext)
            return type;
    return "application/octet-stream";
}

} // namespace penumbra::app
