#include "cli_checks.h"

#include <charconv>
#include <cmath>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "core/error.h"
#include "core/memory.h"

namespace penumbra::app {

namespace {

/// The whole of \p text as a finite number, or nothing.
std::optional<double> finite_number(const std::string& text) {
    double v = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, v);
    if (ec != std::errc() || ptr != end || !std::isfinite(v))
        return std::nullopt;
    return v;
}

/// At most this many characters of what the user typed are echoed in a message.
constexpr std::size_t k_echo_chars = 40;

} // namespace

CLI::Validator positive_number() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            const std::optional<double> v = finite_number(text);
            if (v && *v > 0)
                return {};
            return fmt::format("expected a finite number > 0, got '{}'",
                               excerpt(text, k_echo_chars));
        },
        "NUMBER > 0");
}

CLI::Validator number_in(double lo, double hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) -> std::string {
            const std::optional<double> v = finite_number(text);
            if (v && *v >= lo && *v <= hi)
                return {};
            return fmt::format("expected a number in [{:g}, {:g}], got '{}'", lo, hi,
                               excerpt(text, k_echo_chars));
        },
        fmt::format("NUMBER in [{:g}, {:g}]", lo, hi));
}

CLI::Validator memory_size() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            if (parse_memory_size(text))
                return {};
            return fmt::format("expected a size such as 4G, 500M or 0 (no limit), got '{}'",
                               excerpt(text, k_echo_chars));
        },
        "SIZE");
}

std::string cli_error_line(const CLI::ParseError& error) {
    std::string what = error.what();
    for (char& c : what)
        if (c == '\n')
            c = ' ';
    return "penumbra: error: " + what + " (see --help)";
}

} // namespace penumbra::app
