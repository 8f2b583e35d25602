// Output files (issue #32): a failed write says why and leaves nothing, a target that is not a
// regular file is never replaced, and the temporary files being written are known to the
// signal handlers.

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>
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
    const std::string message = test::external_error_with_file_limit(
        1000, [&] { write_text_file(target.string(), std::string(100000, 'x')); });
    EXPECT_NE(
        message.find(fmt::format("cannot write '{}': {}", target.string(), std::strerror(EFBIG))),
        std::string::npos)
        << message;
    EXPECT_TRUE(fs::is_empty(dir));
}

// FileWriter's buffer, its direct path for blocks beyond the buffer and its seek (OpenEXR and
// VTK go back to fill in offsets) give the bytes written, in order.
TEST(Files, FileWriterWritesSmallAndLargeBlocksAndSeeks) {
    const fs::path path = fs::path(test::temp_dir("files_writer")) / "out.bin";
    std::string expected = "head";
    const std::string large(3 << 20, 'L'); // beyond the 1 MiB buffer
    {
        FileWriter file(path.string(), "out.bin");
        file.write("head", 4);
        file.write(large.data(), large.size());
        expected += large;
        EXPECT_EQ(file.position(), expected.size());
        file.write("tail", 4);
        expected += "tail";
        file.seek(1);
        file.write("EA", 2);
        expected.replace(1, 2, "EA");
        file.seek(expected.size());
        file.write("!", 1);
        expected += "!";
        file.close();
    }
    EXPECT_EQ(read_text_file(path.string()), expected);
}

// A failure is kept: a caller that swallowed it (OpenEXR's destructor does) still sees it at
// close(), with the system's reason.
TEST(Files, FileWriterKeepsItsFirstFailure) {
    const fs::path dir = test::temp_dir("files_writer_fail");
    const std::string message = test::external_error_with_file_limit(1000, [&] {
        FileWriter file((dir / "out.bin").string(), "out.bin");
        try {
            file.write(std::string(5000, 'x').data(), 5000);
        } catch (const ExternalError&) {
        }
        file.close();
    });
    EXPECT_EQ(message, fmt::format("cannot write 'out.bin': {}", std::strerror(EFBIG)));
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
