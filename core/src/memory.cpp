#include "core/memory.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string>

#include <fmt/format.h>

#include "core/error.h"

namespace penumbra {

namespace {

// The first line of \p path as a byte count; nothing if absent or "max" (no limit).
std::optional<std::uint64_t> limit_in_file(const char* path) {
    std::ifstream in(path);
    std::string line;
    if (!in || !std::getline(in, line))
        return std::nullopt;
    std::uint64_t v = 0;
    const auto [ptr, ec] = std::from_chars(line.data(), line.data() + line.size(), v);
    if (ec != std::errc() || ptr == line.data())
        return std::nullopt;
    return v;
}

// The cgroup's memory limit as a container sees its own cgroup (the namespace's root): v2
// memory.max, or v1 memory.limit_in_bytes (a huge number when unlimited).
std::optional<std::uint64_t> cgroup_limit() {
    std::optional<std::uint64_t> least;
    for (const char* path :
         {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
        const std::optional<std::uint64_t> v = limit_in_file(path);
        if (v && (!least || *v < *least))
            least = v;
    }
    return least;
}

std::uint64_t physical_memory_bytes() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
    return pages > 0 && page > 0 ? std::uint64_t(pages) * std::uint64_t(page) : 0;
}

// The power of 1024 a unit letter stands for, or -1.
int unit_power(char c) {
    constexpr std::string_view units = "KMGT";
    const std::size_t i = units.find(char(std::toupper(static_cast<unsigned char>(c))));
    return i == std::string_view::npos ? -1 : int(i) + 1;
}

bool equal_ignoring_case(std::string_view a, std::string_view b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) ==
                      std::tolower(static_cast<unsigned char>(y));
           });
}

} // namespace

std::uint64_t available_memory_bytes() {
    const std::uint64_t physical = physical_memory_bytes();
    const std::optional<std::uint64_t> cgroup = cgroup_limit();
    return cgroup && *cgroup < physical ? *cgroup : physical;
}

std::uint64_t default_memory_limit_bytes() {
    return std::uint64_t(k_default_memory_fraction * double(available_memory_bytes()));
}

std::optional<std::uint64_t> parse_memory_size(std::string_view text) {
    double number = 0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), number);
    if (ec != std::errc() || !std::isfinite(number))
        return std::nullopt;
    std::string_view unit = text.substr(std::size_t(ptr - text.data()));
    int power = 0;
    if (!unit.empty() && unit_power(unit[0]) > 0) {
        power = unit_power(unit[0]);
        unit.remove_prefix(1);
    }
    if (!unit.empty() && !equal_ignoring_case(unit, "b") &&
        !(power > 0 && equal_ignoring_case(unit, "ib")))
        return std::nullopt;
    const double bytes = number * std::pow(1024.0, power);
    if (bytes == 0)
        return 0; // no limit
    // 2^62 bytes (4 EiB) is beyond any machine: larger is a typo.
    if (!(bytes >= 1.0) || bytes > std::ldexp(1.0, 62))
        return std::nullopt;
    return std::uint64_t(bytes);
}

std::string format_bytes(double bytes) {
    constexpr std::array<const char*, 5> units = {"bytes", "KiB", "MiB", "GiB", "TiB"};
    std::size_t u = 0;
    while (u + 1 < units.size() && bytes >= 1024.0) {
        bytes /= 1024.0;
        ++u;
    }
    return u == 0 ? fmt::format("{:.0f} bytes", bytes) : fmt::format("{:.3g} {}", bytes, units[u]);
}

void check_memory(std::uint64_t limit_bytes, std::string_view what, double estimate_bytes,
                  std::string_view advice) {
    if (limit_bytes == 0 || estimate_bytes <= double(limit_bytes))
        return;
    throw ConfigError(fmt::format("{} needs about {}, over the memory limit of {} (--max-memory): "
                                  "{}, or raise --max-memory",
                                  what, format_bytes(estimate_bytes),
                                  format_bytes(double(limit_bytes)), advice));
}

} // namespace penumbra
