#pragma once
// Checks of the CLI's numeric flags: finite numbers only (NaN and infinities pass CLI11's own
// range checks, and a NaN setting was silently ignored), with short messages that print the
// bounds as written rather than CLI11's 300-digit DBL_MAX.

#include <CLI/CLI.hpp>

namespace penumbra::app {

/// \brief A finite number > 0.
CLI::Validator positive_number();

/// \brief A finite number in [\p lo, \p hi].
CLI::Validator number_in(double lo, double hi);

/// \brief A memory size as core/memory.h's parse_memory_size() reads it ("4G", "500M").
CLI::Validator memory_size();

/// \brief The one line `penumbra: error: …` a command-line mistake prints.
std::string cli_error_line(const CLI::ParseError& error);

} // namespace penumbra::app
