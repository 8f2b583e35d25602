#pragma once
// Shared by the fuzz targets (README.md, "Fuzzing"): a private folder for the files a target
// writes, and the rule that a parser rejects bad input only with Penumbra's documented errors.

#include <string>
#include <string_view>

#include "core/error.h"

namespace penumbra::fuzz {

/// \brief Writes \p bytes to the file \p name in a temporary folder of this process's own
///        (removed at exit), so that targets stay hermetic; returns the file's path.
std::string write_scratch_file(const std::string& name, std::string_view bytes);

/// \brief Runs \p parse and swallows InputError and ConfigError, the documented rejections of
///        bad input; any other exception escapes and is reported as a finding.
template <typename Parse> void accept_input_errors(Parse&& parse) {
    try {
        parse();
    } catch (const InputError&) {
    } catch (const ConfigError&) {
    }
}

} // namespace penumbra::fuzz
