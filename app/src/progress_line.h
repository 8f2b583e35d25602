#pragma once
// The text of the terminal's progress bar (terminal.cpp), apart from the terminal so that
// tests can read it.

#include <optional>
#include <string>
#include <string_view>

namespace penumbra::app {

/// \brief The seconds a stage \p fraction done after \p elapsed_s has left, if the rest goes
///        at the pace so far; none before 2 % (too early to tell) and at the end.
std::optional<double> seconds_left(double fraction, double elapsed_s);

/// \brief A duration for people: "42 s", "3 min 05 s", "1 h 02 min".
std::string readable_duration(double seconds);

/// \brief One line of the bar: the stage, 40 cells, the percentage, the seconds so far and,
///        where seconds_left() tells, the time left: "render  [##########..]  25%  10.0 s,
///        30 s left".
std::string progress_line(std::string_view stage, double fraction, double elapsed_s);

} // namespace penumbra::app
