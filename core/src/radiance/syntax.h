#pragma once
// Private to penumbra_core: the syntax of a Radiance scene file (issue #30). A file is a
// sequence of primitives "modifier type identifier", then counted string, integer and real
// arguments, with `#` comments and `!` commands (to the end of the line, `\` continues it)
// where a primitive may begin. Meaning is given by scene_builder.h.

#include <string>
#include <variant>
#include <vector>

namespace penumbra::radiance {

/// \brief Where a statement was read: the file as the scene names it, and its first line.
struct SourceLine {
    std::string file;
    int line = 0;
};

/// \brief One primitive with its arguments as written.
struct Primitive {
    std::string modifier; ///< "void" or the identifier of an earlier primitive
    std::string type;     ///< "polygon", "plastic", ...
    std::string id;
    std::vector<std::string> strings;
    std::vector<long> integers;
    std::vector<double> reals;
    SourceLine where;
};

/// \brief A `!` command line, split into words (no shell quoting).
struct Command {
    std::vector<std::string> words;
    SourceLine where;
};

using Statement = std::variant<Primitive, Command>;

/// \brief Splits \p text (the file \p file) into statements. Throws InputError naming the file
///        and line of a malformed primitive (a missing or non-numeric count or argument).
std::vector<Statement> parse_statements(const std::string& text, const std::string& file);

/// \brief "file:line" of \p where, for messages that name a second place.
std::string describe(const SourceLine& where);

/// \brief Throws the InputError \p what at \p where.
[[noreturn]] void fail(const SourceLine& where, const std::string& what);

} // namespace penumbra::radiance
