#pragma once
// The pieces of an EPW line: comma-separated fields, numbers in them, and errors that name the
// file, the line and the field (1-based, as the EnergyPlus data dictionary counts them).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra::annual {

/// \brief The comma-separated fields of \p line (a trailing '\r' removed), as views into it.
std::vector<std::string_view> split_fields(std::string_view line);

/// \brief \p field without leading and trailing blanks.
std::string_view trim(std::string_view field);

/// \brief The decimal number \p field holds (blanks around it allowed); unset if it is empty,
///        not a number or not finite.
std::optional<double> parse_number(std::string_view field);

/// \brief One line of an EPW file being read: throws InputError naming the file, the line and a
///        field.
class EpwLine {
public:
    EpwLine(const std::string& file, int line, std::string_view text)
        : file_(file), line_(line), fields_(split_fields(text)) {}

    int line() const { return line_; }
    std::size_t field_count() const { return fields_.size(); }
    std::string_view field(std::size_t number) const { return fields_[number - 1]; }

    /// \brief Field \p number (1-based) as a number; throws if it is not one.
    double number(std::size_t number, const char* name) const;
    /// \brief Field \p number as a whole number in [lo, hi]; throws otherwise.
    int integer(std::size_t number, const char* name, int lo, int hi) const;
    /// \brief Field \p number as a value >= 0, unset when blank or at least \p missing_from
    ///        (EPW's missing-value codes); throws for anything else.
    std::optional<double> measurement(std::size_t number, const char* name,
                                      double missing_from) const;

    /// \brief Throws InputError for field \p number.
    [[noreturn]] void fail(std::size_t number, const char* name, const std::string& what) const;
    /// \brief Throws InputError for the whole line.
    [[noreturn]] void fail(const std::string& what) const;

private:
    const std::string& file_;
    int line_;
    std::vector<std::string_view> fields_;
};

} // namespace penumbra::annual
