#include "core/files.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <unistd.h>

#include "core/error.h"

namespace penumbra {

namespace fs = std::filesystem;

namespace {
std::string temp_name_for(const std::string& path) {
    fs::path p(path);
    std::string name = "." + p.filename().string() + ".tmp" + std::to_string(::getpid());
    return (p.parent_path() / name).string();
}
} // namespace

void write_atomically(const std::string& path,
                      const std::function<void(const std::string& temp_path)>& write) {
    const std::string temp = temp_name_for(path);
    try {
        write(temp);
    } catch (...) {
        std::error_code ec;
        fs::remove(temp, ec);
        throw;
    }
    std::error_code ec;
    fs::rename(temp, path, ec);
    if (ec) {
        fs::remove(temp, ec);
        throw ExternalError(fmt::format("cannot write '{}': {}", path, ec.message()));
    }
}

void write_text_file(const std::string& path, const std::string& text) {
    write_atomically(path, [&](const std::string& temp) {
        std::ofstream out(temp, std::ios::binary);
        out << text;
        out.close();
        if (!out)
            throw ExternalError(fmt::format("cannot write '{}': {}", path, std::strerror(errno)));
    });
}

std::string read_text_file(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec))
        throw InputError(path, "", "file not found");
    if (fs::is_directory(path, ec))
        throw InputError(path, "", "is a folder, not a file");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw InputError(path, "", std::string("cannot open: ") + std::strerror(errno));
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

void check_output_dir(const std::string& dir) {
    std::error_code ec;
    fs::path p(dir);
    fs::path first_created; // the highest folder this call creates, to undo
    for (fs::path probe = fs::absolute(p, ec); !probe.empty() && !fs::exists(probe, ec);
         probe = probe.parent_path()) {
        first_created = probe;
        if (probe == probe.parent_path())
            break;
    }
    if (fs::exists(p, ec) && !fs::is_directory(p, ec))
        throw ConfigError(fmt::format("output folder '{}' is a file", dir));
    fs::create_directories(p, ec);
    if (ec)
        throw ConfigError(fmt::format("cannot create output folder '{}': {}", dir, ec.message()));
    const fs::path probe_file = p / (".penumbra-write-test" + std::to_string(::getpid()));
    std::ofstream out(probe_file);
    const bool ok = bool(out);
    out.close();
    fs::remove(probe_file, ec);
    if (!first_created.empty())
        fs::remove_all(first_created, ec); // created again when the outputs are written
    if (!ok)
        throw ConfigError(fmt::format("output folder '{}' is not writable", dir));
}

} // namespace penumbra
