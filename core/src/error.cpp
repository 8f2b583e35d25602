#include "core/error.h"

#include <fmt/format.h>

namespace penumbra {

namespace {
// "file:line: 'key': what", leaving out the parts that are unknown.
std::string format_input_error(const std::string& file, const std::string& key,
                               const std::string& what, int line) {
    std::string where = line > 0 ? fmt::format("{}:{}", file, line) : file;
    if (!key.empty())
        where = where.empty() ? fmt::format("'{}'", key) : fmt::format("{}: '{}'", where, key);
    return where.empty() ? what : fmt::format("{}: {}", where, what);
}
} // namespace

InputError::InputError(const std::string& file, const std::string& key, const std::string& what,
                       int line)
    : std::runtime_error(format_input_error(file, key, what, line)), file_(file), key_(key),
      line_(line) {}

std::string excerpt(const std::string& text, std::size_t max_chars) {
    return text.size() <= max_chars ? text : text.substr(0, max_chars) + "…";
}

} // namespace penumbra
