#include "core/error.h"

namespace penumbra {

namespace {
std::string format_input_error(const std::string& file, const std::string& key,
                               const std::string& what, int line) {
    std::string where = file;
    if (line > 0)
        where += ":" + std::to_string(line);
    if (!key.empty())
        where += (where.empty() ? "" : ": ") + std::string("'") + key + "'";
    return where.empty() ? what : where + ": " + what;
}
} // namespace

InputError::InputError(const std::string& file, const std::string& key, const std::string& what,
                       int line)
    : std::runtime_error(format_input_error(file, key, what, line)), file_(file), key_(key),
      line_(line) {}

} // namespace penumbra
