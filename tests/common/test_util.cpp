#include "common/test_util.h"

#include <atomic>
#include <cstdio>
#include <filesystem>

#include <unistd.h>

namespace penumbra::test {

namespace fs = std::filesystem;

std::string source_path(const std::string& relative) {
    return (fs::path(PENUMBRA_SOURCE_DIR) / relative).string();
}

std::string temp_dir(const std::string& tag) {
    static std::atomic<int> counter{0};
    fs::path dir = fs::temp_directory_path() /
                   ("penumbra-test-" + tag + "-" + std::to_string(::getpid()) + "-" +
                    std::to_string(counter++));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir.string();
}

namespace {
class StderrSink final : public LogSink {
public:
    void write(LogLevel level, std::string_view message) override {
        if (level >= LogLevel::warn)
            std::fprintf(stderr, "%.*s\n", int(message.size()), message.data());
    }
};
} // namespace

Context quiet_context(int threads) {
    Context ctx;
    ctx.log = std::make_shared<StderrSink>();
    ctx.threads = threads;
    ctx.min_level = LogLevel::warn;
    return ctx;
}

} // namespace penumbra::test
