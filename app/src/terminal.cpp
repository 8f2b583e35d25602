#include "terminal.h"

#include "progress_line.h"

#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

namespace penumbra::app {

namespace {

class TerminalProgress;
/// The progress bar on the terminal, if one is drawn: log lines clear its line first and
/// redraw it after, so that messages never land on the bar's line.
std::weak_ptr<TerminalProgress> g_bar;

void clear_bar();
void redraw_bar();

class SpdlogSink final : public LogSink {
public:
    SpdlogSink() : logger_(spdlog::stderr_color_mt("penumbra")) {
        logger_->set_pattern("%^%l%$: %v");
        logger_->set_level(spdlog::level::trace);
    }
    ~SpdlogSink() override { spdlog::drop("penumbra"); }
    void write(LogLevel level, std::string_view message) override {
        clear_bar();
        logger_->log(to_spdlog(level), "{}", message);
        logger_->flush();
        redraw_bar();
    }

private:
    static spdlog::level::level_enum to_spdlog(LogLevel level) {
        switch (level) {
        case LogLevel::trace:
            return spdlog::level::trace;
        case LogLevel::debug:
            return spdlog::level::debug;
        case LogLevel::info:
            return spdlog::level::info;
        case LogLevel::warn:
            return spdlog::level::warn;
        case LogLevel::error:
            return spdlog::level::err;
        }
        return spdlog::level::info;
    }
    std::shared_ptr<spdlog::logger> logger_;
};

class TerminalProgress final : public ProgressSink {
public:
    void begin(std::string_view stage) override {
        std::lock_guard lock(mutex_);
        if (shown_) // a stage within a stage: the new bar takes the line
            std::fputs("\r\033[K", stderr);
        stage_ = stage;
        start_ = clock::now();
        last_draw_ = start_;
        shown_ = false;
    }
    bool update(double fraction) override {
        std::lock_guard lock(mutex_);
        auto now = clock::now();
        if (now - start_ < std::chrono::seconds(1) ||
            now - last_draw_ < std::chrono::milliseconds(100))
            return true;
        draw(fraction, now);
        return true;
    }
    void end() override {
        std::lock_guard lock(mutex_);
        if (shown_) {
            draw(1.0, clock::now());
            std::fputc('\n', stderr);
        }
        shown_ = false;
    }

    /// Erases the bar's line (a log line follows).
    void clear() {
        std::lock_guard lock(mutex_);
        if (shown_) {
            std::fputs("\r\033[K", stderr);
            std::fflush(stderr);
        }
    }
    /// Draws the bar again where it was, after a log line.
    void redraw() {
        std::lock_guard lock(mutex_);
        if (shown_)
            draw(fraction_, clock::now());
    }

private:
    using clock = std::chrono::steady_clock;
    void draw(double fraction, clock::time_point now) {
        fraction_ = fraction;
        const double elapsed = std::chrono::duration<double>(now - start_).count();
        // Cleared to the line's end: the time left may print shorter than the line before.
        std::fprintf(stderr, "\r%s\033[K", progress_line(stage_, fraction, elapsed).c_str());
        std::fflush(stderr);
        last_draw_ = now;
        shown_ = true;
    }
    std::mutex mutex_;
    std::string stage_;
    clock::time_point start_, last_draw_;
    double fraction_ = 0;
    bool shown_ = false;
};

void clear_bar() {
    if (auto bar = g_bar.lock())
        bar->clear();
}

void redraw_bar() {
    if (auto bar = g_bar.lock())
        bar->redraw();
}

} // namespace

std::shared_ptr<LogSink> make_stderr_log_sink() {
    return std::make_shared<SpdlogSink>();
}

std::shared_ptr<ProgressSink> make_terminal_progress() {
    if (!::isatty(STDERR_FILENO))
        return nullptr;
    auto bar = std::make_shared<TerminalProgress>();
    g_bar = bar;
    return bar;
}

} // namespace penumbra::app
