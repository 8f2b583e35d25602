// Arguments of the `!` command lines Penumbra interprets.

#include "command_words.h"

#include <cmath>
#include <cstdlib>
#include <utility>

#include <fmt/format.h>

namespace penumbra::radiance {

CommandWords::CommandWords(const Command& command, std::string usage)
    : command_(command), usage_(std::move(usage)), program_(usage_.substr(0, usage_.find(' '))) {}

void CommandWords::fail_with(const std::string& message) const {
    fail(command_.where, fmt::format("!{}: {}", program_, message));
}

const std::string& CommandWords::take() {
    if (!more())
        fail_with(fmt::format("too few arguments ({})", usage_));
    return command_.words[next_++];
}

double CommandWords::number(const std::string& what) {
    const std::string& word = take();
    char* end = nullptr;
    const double v = std::strtod(word.c_str(), &end);
    if (*end != '\0' || word.empty() || !std::isfinite(v))
        fail_with(fmt::format("{} must be a number, got '{}'", what, word));
    return v;
}

int CommandWords::integer(const std::string& what, int lo, int hi) {
    const double v = number(what);
    if (v != std::floor(v) || v < lo || v > hi)
        fail_with(fmt::format("{} must be an integer in [{}, {}], got {}", what, lo, hi, v));
    return int(v);
}

CommandHour parse_command_hour(const std::string& word, const CommandWords& in) {
    CommandHour out;
    std::string text = word;
    out.solar_time = text.starts_with('+');
    if (out.solar_time)
        text.erase(0, 1);
    const std::size_t colon = text.find(':');
    const std::string hours = text.substr(0, colon); // named: `end` points into it
    char* end = nullptr;
    double hour = std::strtod(hours.c_str(), &end);
    bool ok = *end == '\0' && !hours.empty();
    if (colon != std::string::npos) {
        const double minutes = std::strtod(text.c_str() + colon + 1, &end);
        ok = ok && *end == '\0' && minutes >= 0 && minutes < 60;
        hour += minutes / 60.0;
    }
    if (!ok || !(hour >= 0 && hour <= 24))
        in.fail_with(fmt::format("the hour must be [+]H, [+]H.h or [+]H:MM in [0, 24] "
                                 "(time-zone names are not supported), got '{}'",
                                 word));
    out.hour = hour;
    return out;
}

} // namespace penumbra::radiance
