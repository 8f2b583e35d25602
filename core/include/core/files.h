#pragma once
// Output files are written to a temporary name beside the target, then renamed, so that an
// error never leaves a half-written file.

#include <functional>
#include <string>

namespace penumbra {

/// \brief Calls \p write with a temporary path in the target's folder, then renames it to
///        \p path. Removes the temporary file if \p write throws. Throws ExternalError.
void write_atomically(const std::string& path,
                      const std::function<void(const std::string& temp_path)>& write);

/// \brief Writes \p text to \p path atomically.
void write_text_file(const std::string& path, const std::string& text);

/// \brief Reads a whole file; throws InputError naming \p path if it cannot.
std::string read_text_file(const std::string& path);

/// \brief Makes sure \p dir exists (creating parents) and that a file can be written there.
///        Throws ConfigError naming the folder. Leaves nothing behind if it created nothing.
void check_output_dir(const std::string& dir);

} // namespace penumbra
