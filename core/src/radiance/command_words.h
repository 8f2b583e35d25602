#pragma once
// Private to penumbra_core: reading the arguments of a Radiance `!` command line that Penumbra
// interprets itself (gensky, gendaylit), each error naming the file and line.

#include <string>

#include "syntax.h"

namespace penumbra::radiance {

/// \brief The words of \p command after its program name, taken one at a time.
class CommandWords {
public:
    /// \p usage is quoted when the arguments run out ("gensky month day hour [options]"); its
    /// first word is the program's name in messages.
    CommandWords(const Command& command, std::string usage);
    bool more() const { return next_ < command_.words.size(); }
    const std::string& take();
    /// The next word as a finite number; \p what names it in the error.
    double number(const std::string& what);
    /// The next word as an integer in [lo, hi].
    int integer(const std::string& what, int lo, int hi);
    const SourceLine& where() const { return command_.where; }
    /// \brief Fails at the command's line with "!program: message".
    [[noreturn]] void fail_with(const std::string& message) const;

private:
    const Command& command_;
    std::string usage_, program_;
    std::size_t next_ = 1; // after the program name
};

/// \brief An hour of the day as gensky and gendaylit take it.
struct CommandHour {
    double hour = 12;        ///< decimal hours, [0, 24]
    bool solar_time = false; ///< a leading '+': local solar time
};

/// \brief "[+]H", "[+]H.h" or "[+]H:MM" (time-zone names are errors).
CommandHour parse_command_hour(const std::string& word, const CommandWords& in);

} // namespace penumbra::radiance
