#include "fuzz_support.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace penumbra::fuzz {

namespace {

namespace fs = std::filesystem;

/// A folder made once per process; its destructor removes it when the process exits.
class ScratchDir {
public:
    ScratchDir() {
        std::string pattern = (fs::temp_directory_path() / "penumbra-fuzz-XXXXXX").string();
        if (!mkdtemp(pattern.data()))
            throw std::runtime_error("cannot make a temporary folder in " + pattern);
        path_ = pattern;
    }
    ~ScratchDir() {
        std::error_code ignored; // nothing can be done about a failure at exit
        fs::remove_all(path_, ignored);
    }
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

} // namespace

std::string write_scratch_file(const std::string& name, std::string_view bytes) {
    static const ScratchDir dir;
    const fs::path path = dir.path() / name;
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(bytes.data(), std::streamsize(bytes.size()));
    return path.string();
}

} // namespace penumbra::fuzz
