// Replays a fuzz target's corpus without libFuzzer (the default build): every file of the
// folders given is fed to LLVMFuzzerTestOneInput once, so the ordinary test run guards the
// seeds and every reproducer of a past finding.

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace fs = std::filesystem;

namespace {

std::vector<fs::path> corpus_files(const fs::path& folder) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(folder))
        if (entry.is_regular_file())
            files.push_back(entry.path());
    std::sort(files.begin(), files.end()); // the same order on every machine
    return files;
}

/// Feeds \p file to the target; false (with a message naming it) if the target threw.
bool replay(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), {}};
    try {
        LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
        return true;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: uncaught exception: %s\n", file.c_str(), e.what());
        return false;
    }
}

} // namespace

int main(int argc, char** argv) {
    std::size_t replayed = 0, failed = 0;
    for (int i = 1; i < argc; ++i)
        for (const fs::path& file : corpus_files(argv[i])) {
            ++replayed;
            failed += replay(file) ? 0 : 1;
        }
    std::printf("replayed %zu inputs, %zu failed\n", replayed, failed);
    return replayed == 0 || failed > 0 ? 1 : 0; // an empty corpus guards nothing
}
