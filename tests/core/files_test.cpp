// Output files (issue #32): a failed write says why and leaves nothing, a target that is not a
// regular file is never replaced, and the temporary files being written are known to the
// signal handlers.

#include <csignal>
#include <cstring>
#include <filesystem>
#include <string>

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "core/error.h"
#include "core/files.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

// A write that the system refuses (here: over a file-size limit, EFBIG, as a full disk gives
// ENOSPC) names the system's reason and leaves neither the target nor a temporary file. Run
// in a child process, so that its limit does not reach the other tests.
TEST(Files, FailedWriteSaysWhyAndLeavesNothing) {
    const fs::path dir = test::temp_dir("files_efbig");
    const fs::path target = dir / "big.txt";
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        std::signal(SIGXFSZ, SIG_IGN);
        const rlimit limit{1000, 1000};
        ::setrlimit(RLIMIT_FSIZE, &limit);
        try {
            write_text_file(target.string(), std::string(100000, 'x'));
        } catch (const ExternalError& e) {
            ::_exit(std::string(e.what()).find(std::strerror(EFBIG)) != std::string::npos ? 0 : 2);
        }
        ::_exit(1);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0) << "1: no error, 2: the message lacks the reason";
    EXPECT_TRUE(fs::is_empty(dir));
}

TEST(Files, NeverReplacesAFolderOrADevice) {
    const fs::path dir = test::temp_dir("files_not_regular");
    fs::create_directories(dir / "folder.txt");
    EXPECT_THROW(write_text_file((dir / "folder.txt").string(), "x"), ConfigError);
    EXPECT_TRUE(fs::is_directory(dir / "folder.txt"));
    // A fifo of the test's own, not /dev/null: a broken check must not replace a real device.
    const fs::path fifo = dir / "device.txt";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0666), 0);
    EXPECT_THROW(write_text_file(fifo.string(), "x"), ConfigError);
    EXPECT_TRUE(fs::is_fifo(fifo));
}

// What a SIGINT or SIGTERM handler calls removes the temporary file being written.
TEST(Files, SignalCleanupRemovesTheTemporaryFileBeingWritten) {
    const fs::path dir = test::temp_dir("files_signal");
    std::string seen;
    EXPECT_THROW(write_atomically((dir / "out.txt").string(),
                                  [&](const std::string& temp) {
                                      write_text_file(temp, "partial");
                                      seen = temp;
                                      remove_temp_files_on_signal();
                                      throw ExternalError("interrupted");
                                  }),
                 ExternalError);
    ASSERT_FALSE(seen.empty());
    EXPECT_FALSE(fs::exists(seen));
    EXPECT_TRUE(fs::is_empty(dir));
}

} // namespace
} // namespace penumbra
