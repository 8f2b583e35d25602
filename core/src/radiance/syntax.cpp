// Radiance's scene syntax, as its readers (readobj.c, fgetword) take it: words separated by
// white space, a primitive's arguments free to span lines, comments and commands only where a
// primitive may begin.

#include "syntax.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include <fmt/format.h>

#include "core/error.h"

namespace penumbra::radiance {

namespace {

/// At most this many characters of a bad word are quoted in a message.
constexpr std::size_t k_quoted_chars = 40;

/// Most arguments one primitive may have: a polygon of a million vertices has three million;
/// a count beyond this is a corrupt file, not a primitive to allocate for.
constexpr long k_max_arguments = 1L << 26;

class Cursor {
public:
    Cursor(const std::string& text, const std::string& file) : text_(text), file_(file) {}

    /// Skips white space; true at the end of the text.
    bool at_end() {
        while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) {
            if (text_[pos_] == '\n')
                ++line_;
            ++pos_;
        }
        return pos_ >= text_.size();
    }
    char peek() const { return text_[pos_]; }
    int line() const { return line_; }

    /// The rest of the line after the current character; `\` before a newline continues it.
    std::string rest_of_line() {
        std::string line;
        for (++pos_; pos_ < text_.size() && text_[pos_] != '\n'; ++pos_) {
            if (text_[pos_] == '\\' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '\n') {
                ++line_;
                ++pos_;
                line += ' ';
                continue;
            }
            line += text_[pos_];
        }
        return line;
    }

    /// The primitive being read begins here: an early end of the file is reported at its line.
    void mark() { primitive_line_ = line_; }

    /// The next word; \p what names it in the error at the end of the file.
    std::string word(const std::string& what) {
        if (at_end())
            throw InputError(file_, "", fmt::format("the file ends where {} was expected", what),
                             primitive_line_);
        const std::size_t start = pos_;
        while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_])))
            ++pos_;
        return text_.substr(start, pos_ - start);
    }

    [[noreturn]] void fail(const std::string& what) const {
        throw InputError(file_, "", what, line_);
    }

private:
    const std::string& text_;
    const std::string& file_;
    std::size_t pos_ = 0;
    int line_ = 1;
    int primitive_line_ = 1;
};

long parse_count(Cursor& in, const std::string& what) {
    const std::string word = in.word(what);
    char* end = nullptr;
    errno = 0;
    const long n = std::strtol(word.c_str(), &end, 10);
    if (*end != '\0' || errno != 0 || n < 0 || n > k_max_arguments)
        in.fail(fmt::format("expected {} (a count in [0, {}]), got '{}'", what, k_max_arguments,
                            excerpt(word, k_quoted_chars)));
    return n;
}

double parse_real(Cursor& in, const std::string& what) {
    const std::string word = in.word(what);
    char* end = nullptr;
    const double v = std::strtod(word.c_str(), &end);
    if (*end != '\0' || word.empty() || !std::isfinite(v))
        in.fail(fmt::format("expected {} (a finite number), got '{}'", what,
                            excerpt(word, k_quoted_chars)));
    return v;
}

Primitive parse_primitive(Cursor& in, const std::string& file) {
    Primitive p;
    in.mark();
    p.where = {file, in.line()};
    p.modifier = in.word("a primitive");
    p.type = in.word("the primitive's type");
    p.id = in.word("the primitive's identifier");
    const std::string of = fmt::format(" of primitive '{}' ({})", p.id, p.type);
    const long strings = parse_count(in, "the number of string arguments" + of);
    for (long i = 0; i < strings; ++i)
        p.strings.push_back(in.word(fmt::format("string argument {}{}", i + 1, of)));
    const long integers = parse_count(in, "the number of integer arguments" + of);
    for (long i = 0; i < integers; ++i) {
        const std::string what = fmt::format("integer argument {}{}", i + 1, of);
        const double v = parse_real(in, what);
        if (v != std::floor(v) || std::abs(v) > double(k_max_arguments))
            in.fail(fmt::format("expected {} (an integer), got {}", what, v));
        p.integers.push_back(long(v));
    }
    const long reals = parse_count(in, "the number of real arguments" + of);
    for (long i = 0; i < reals; ++i)
        p.reals.push_back(parse_real(in, fmt::format("real argument {}{}", i + 1, of)));
    return p;
}

std::vector<std::string> split_words(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> words;
    for (std::string word; in >> word;)
        words.push_back(word);
    return words;
}

} // namespace

std::vector<Statement> parse_statements(const std::string& text, const std::string& file) {
    Cursor in(text, file);
    std::vector<Statement> statements;
    while (!in.at_end()) {
        if (in.peek() == '#') {
            in.rest_of_line();
        } else if (in.peek() == '!') {
            const int line = in.line();
            statements.push_back(Command{split_words(in.rest_of_line()), {file, line}});
        } else {
            statements.push_back(parse_primitive(in, file));
        }
    }
    return statements;
}

std::string describe(const SourceLine& where) {
    return fmt::format("{}:{}", where.file, where.line);
}

void fail(const SourceLine& where, const std::string& what) {
    throw InputError(where.file, "", what, where.line);
}

} // namespace penumbra::radiance
