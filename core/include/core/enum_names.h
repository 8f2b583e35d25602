#pragma once
// One name table per settings enum: the scene parser, the CLI, summary.json and the docs test
// read the same table, so a value has one spelling everywhere (and an alias, where an old
// spelling stays accepted, is written once).

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

/// \brief One spelling of an enum value. A value may have several (aliases); its first entry
///        in the table is the name it is written with.
template <class E> struct EnumName {
    std::string_view name;
    E value;
};

/// \brief The name table of enum \p E: specialised next to each enum.
template <class E> inline constexpr std::span<const EnumName<E>> k_enum_names{};

/// \brief The value spelled \p name, or nothing.
template <class E> std::optional<E> parse_enum(std::string_view name) {
    for (const EnumName<E>& n : k_enum_names<E>)
        if (n.name == name)
            return n.value;
    return std::nullopt;
}

/// \brief The name \p value is written with (its first entry in the table).
template <class E> std::string_view enum_name(E value) {
    for (const EnumName<E>& n : k_enum_names<E>)
        if (n.value == value)
            return n.name;
    return "?";
}

/// \brief Every accepted spelling, in table order (for the CLI's choices).
template <class E> std::vector<std::string> enum_names() {
    std::vector<std::string> out;
    for (const EnumName<E>& n : k_enum_names<E>)
        out.emplace_back(n.name);
    return out;
}

/// \brief Every accepted spelling as "a, b, c", for messages.
template <class E> std::string enum_name_list() {
    std::string out;
    for (const EnumName<E>& n : k_enum_names<E>)
        out += (out.empty() ? "" : ", ") + std::string(n.name);
    return out;
}

} // namespace penumbra
