#pragma once
// Output files are written to a temporary name beside the target, then renamed, so that an
// error never leaves a half-written file.

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

/// \brief Throws ConfigError if \p path exists and is not a regular file: renaming onto a
///        device, folder or fifo would replace it. Lets a slow writer refuse before its work.
void check_replaceable(const std::string& path);

/// \brief Calls \p write with a temporary path in the target's folder, then renames it to
///        \p path. Removes the temporary file if \p write throws. Throws ConfigError if
///        \p path exists and is not a regular file (a device, folder or fifo is never
///        replaced), ExternalError with the system's reason if the rename fails. The temporary
///        file is registered while it exists, for remove_temp_files_on_signal().
void write_atomically(const std::string& path,
                      const std::function<void(const std::string& temp_path)>& write);

/// \brief Writes \p text (any bytes) to \p path atomically.
void write_text_file(const std::string& path, std::string_view text);

/// \brief A new file written through a buffer with POSIX calls, so that a failure names the
///        failing call's reason ("No space left on device", "File too large"): ExternalError
///        "cannot write 'NAME': reason", NAME being the output the temporary file stands for.
///        Once a call failed, every later call (and close()) fails with the same reason, so a
///        caller that swallows one (a library's destructor) cannot miss it.
class FileWriter {
public:
    /// Creates (or truncates) \p temp_path; errors name \p name.
    FileWriter(const std::string& temp_path, std::string name);
    /// Closes without reporting: a writer still open here is abandoned after an error.
    ~FileWriter();
    FileWriter(const FileWriter&) = delete;
    FileWriter& operator=(const FileWriter&) = delete;

    void write(const void* data, std::size_t size);
    /// Where the next write goes, from the file's start.
    std::uint64_t position() const { return file_position_ + buffer_.size(); }
    /// Moves to \p position (OpenEXR and VTK go back to fill in offsets).
    void seek(std::uint64_t position);
    /// Writes what is buffered and closes the file, reporting any error.
    void close();
    /// The errno of the first failure, 0 if none.
    int error() const { return error_; }
    /// Throws the ExternalError of error(), which must be set.
    [[noreturn]] void rethrow() const;

private:
    void flush();
    [[noreturn]] void fail(int error);

    int fd_ = -1;
    std::string name_;
    std::string buffer_;
    std::uint64_t file_position_ = 0; ///< of buffer_'s first byte
    int error_ = 0;
};

/// \brief Removes every temporary file write_atomically() is writing now. Async-signal-safe
///        (only unlink(2) on paths copied beforehand): for SIGINT and SIGTERM handlers.
void remove_temp_files_on_signal() noexcept;

/// \brief Removes from \p dir the temporary files write_atomically() left for the files
///        \p names (".NAME.tmpPID") when process PID is no longer alive (killed before it
///        could clean up). Returns how many it removed.
std::size_t remove_stale_temp_files(const std::string& dir, const std::vector<std::string>& names);

/// \brief Reads a whole file; throws InputError naming \p path if it cannot.
std::string read_text_file(const std::string& path);

/// \brief Makes sure \p dir exists (creating parents) and that a file can be written there.
///        Throws ConfigError naming the folder. Leaves nothing behind if it created nothing.
void check_output_dir(const std::string& dir);

} // namespace penumbra
