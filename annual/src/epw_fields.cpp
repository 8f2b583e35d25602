#include "epw_fields.h"

#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"

namespace penumbra::annual {

namespace {

/// At most this many characters of a bad field are quoted in a message.
constexpr std::size_t k_quoted_chars = 40;

std::string field_key(std::size_t number, const char* name) {
    return fmt::format("field {} ({})", number, name);
}

} // namespace

std::vector<std::string_view> split_fields(std::string_view line) {
    if (!line.empty() && line.back() == '\r')
        line.remove_suffix(1);
    std::vector<std::string_view> fields;
    for (;;) {
        const std::size_t comma = line.find(',');
        fields.push_back(line.substr(0, comma));
        if (comma == std::string_view::npos)
            return fields;
        line.remove_prefix(comma + 1);
    }
}

std::string_view trim(std::string_view field) {
    const std::size_t first = field.find_first_not_of(" \t");
    if (first == std::string_view::npos)
        return {};
    const std::size_t last = field.find_last_not_of(" \t");
    return field.substr(first, last - first + 1);
}

std::optional<double> parse_number(std::string_view field) {
    field = trim(field);
    if (!field.empty() && field.front() == '+') // from_chars refuses the sign strtod accepts
        field.remove_prefix(1);
    double value = 0;
    const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
    if (field.empty() || error != std::errc() || end != field.data() + field.size() ||
        !std::isfinite(value))
        return std::nullopt;
    return value;
}

double EpwLine::number(std::size_t number, const char* name) const {
    const std::optional<double> value = parse_number(field(number));
    if (!value)
        fail(number, name,
             fmt::format("'{}' is not a number",
                         excerpt(std::string(field(number)), k_quoted_chars)));
    return *value;
}

int EpwLine::integer(std::size_t number, const char* name, int lo, int hi) const {
    const double value = this->number(number, name);
    if (value != std::floor(value) || value < lo || value > hi)
        fail(number, name, fmt::format("{} is not a whole number in [{}, {}]", value, lo, hi));
    return int(value);
}

std::optional<double> EpwLine::measurement(std::size_t number, const char* name,
                                           double missing_from) const {
    if (trim(field(number)).empty())
        return std::nullopt;
    const double value = this->number(number, name);
    if (value >= missing_from)
        return std::nullopt;
    if (value < 0)
        fail(number, name, fmt::format("{} is negative", value));
    return value;
}

void EpwLine::fail(std::size_t number, const char* name, const std::string& what) const {
    throw InputError(file_, field_key(number, name), what, line_);
}

void EpwLine::fail(const std::string& what) const {
    throw InputError(file_, "", what, line_);
}

} // namespace penumbra::annual
