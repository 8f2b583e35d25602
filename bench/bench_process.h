#pragma once
// What the size-scaling benchmarks (hr_bench, mesh_bench) share: sizes such as "32k", the
// process's peak memory, wall time, and running one size in a child process of its own so that
// a size's peak memory is its own and a size that runs too long can be stopped.

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace penumbra::bench {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start);

/// "32k" → 32 000, "1M" → 1 000 000; throws ConfigError for anything else.
std::int64_t parse_size(const std::string& text);

/// Peak resident set size of this process so far (VmHWM), MiB.
double peak_rss_mib();

struct ChildRun {
    bool stopped = false; ///< killed after max_seconds
    int status = 0;       ///< as waitpid reports it
    std::string out;      ///< the child's standard output, when captured
    /// "" for a clean exit, else "signal N" or "exit code N".
    std::string failure() const;
};

/// \brief Runs this program again (/proc/self/exe) with \p args (args[0] its name) in a child
///        process and waits for it, killing it after \p max_seconds. With \p capture, the
///        child's standard output is collected into ChildRun::out rather than shared.
ChildRun run_self(std::vector<std::string> args, double max_seconds, bool capture);

} // namespace penumbra::bench
