#pragma once
// Output files are written to a temporary name beside the target, then renamed, so that an
// error never leaves a half-written file.

#include <functional>
#include <string>
#include <vector>

namespace penumbra {

/// \brief Calls \p write with a temporary path in the target's folder, then renames it to
///        \p path. Removes the temporary file if \p write throws. Throws ConfigError if
///        \p path exists and is not a regular file (a device, folder or fifo is never
///        replaced), ExternalError with the system's reason if the rename fails. The temporary
///        file is registered while it exists, for remove_temp_files_on_signal().
void write_atomically(const std::string& path,
                      const std::function<void(const std::string& temp_path)>& write);

/// \brief Writes \p text to \p path atomically.
void write_text_file(const std::string& path, const std::string& text);

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
