#pragma once
// Terminal sinks of the CLI: spdlog-backed logging to stderr and a progress bar that appears
// only on a terminal and only for stages that last longer than a second.

#include <memory>

#include "core/context.h"

namespace penumbra::app {

std::shared_ptr<LogSink> make_stderr_log_sink();
std::shared_ptr<ProgressSink> make_terminal_progress();

} // namespace penumbra::app
