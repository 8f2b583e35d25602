#pragma once
// The error hierarchy, thrown at module boundaries and in setup code (never per sample or per
// link), caught once in the CLI's main. Messages are one line: what failed, where, and what
// to try.

#include <cstddef>
#include <stdexcept>
#include <string>

namespace penumbra {

/// \brief \p text as a message quotes it: whole up to \p max_chars, else its first
///        \p max_chars and "…" (a bad line of a 10 MB file stays one readable line).
std::string excerpt(const std::string& text, std::size_t max_chars);

/// Scene or asset problems; carries the file, line (0 if unknown) and key.
class InputError : public std::runtime_error {
public:
    InputError(const std::string& file, const std::string& key, const std::string& what,
               int line = 0);
    const std::string& file() const { return file_; }
    const std::string& key() const { return key_; }
    int line() const { return line_; }

private:
    std::string file_, key_;
    int line_;
};

/// Bad options or combinations of options.
class ConfigError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Failures reported by a third-party library or the operating system.
class ExternalError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Broken invariants: bugs.
class InternalError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

} // namespace penumbra
