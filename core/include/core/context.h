#pragma once
// The context every module entry point takes: logger sink, progress/cancel callback, thread
// count and master seed. It replaces globals: library code logs through it, never to stdout.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include <fmt/format.h>

namespace penumbra {

enum class LogLevel { trace, debug, info, warn, error };

/// \brief Receives log lines. Implementations must be thread-safe.
class LogSink {
public:
    virtual ~LogSink() = default;
    virtual void write(LogLevel level, std::string_view message) = 0;
};

/// \brief Receives progress of long stages. begin() once per stage, update() with the fraction
///        done in [0, 1] (called from one thread at a time), end() when the stage is over.
///        update() returns false to request cancellation.
class ProgressSink {
public:
    virtual ~ProgressSink() = default;
    virtual void begin(std::string_view stage) = 0;
    virtual bool update(double fraction) = 0;
    virtual void end() = 0;
};

/// Thrown when a ProgressSink asked to cancel.
class Cancelled : public std::exception {
public:
    const char* what() const noexcept override { return "cancelled"; }
};

struct Context {
    std::shared_ptr<LogSink> log;           ///< may be null: messages are dropped
    std::shared_ptr<ProgressSink> progress; ///< may be null
    int threads = 0;                        ///< 0 = all hardware threads
    std::uint64_t seed = 0;                 ///< master seed of every random stream
    LogLevel min_level = LogLevel::info;
    /// The most the stages' memory estimates may reach (core/memory.h), bytes; 0 = no limit.
    std::uint64_t max_memory_bytes = 0;

    template <typename... Args>
    void log_at(LogLevel level, fmt::format_string<Args...> f, Args&&... args) const {
        if (log && level >= min_level)
            log->write(level, fmt::format(f, std::forward<Args>(args)...));
    }
    template <typename... Args> void info(fmt::format_string<Args...> f, Args&&... args) const {
        log_at(LogLevel::info, f, std::forward<Args>(args)...);
    }
    template <typename... Args> void warn(fmt::format_string<Args...> f, Args&&... args) const {
        log_at(LogLevel::warn, f, std::forward<Args>(args)...);
    }
    template <typename... Args> void debug(fmt::format_string<Args...> f, Args&&... args) const {
        log_at(LogLevel::debug, f, std::forward<Args>(args)...);
    }
};

/// \brief RAII progress stage: begin() on construction, end() on destruction. update() throws
///        Cancelled when the sink asks to stop. Not thread-safe: call update() from one thread.
class ProgressStage {
public:
    ProgressStage(const Context& ctx, std::string_view stage);
    ~ProgressStage();
    ProgressStage(const ProgressStage&) = delete;
    ProgressStage& operator=(const ProgressStage&) = delete;
    void update(double fraction);

private:
    ProgressSink* sink_;
};

} // namespace penumbra
