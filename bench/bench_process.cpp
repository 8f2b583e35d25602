#include "bench_process.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <thread>

#include "core/error.h"

namespace penumbra::bench {

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

std::int64_t parse_size(const std::string& text) {
    const auto suffix = text.find_first_of("kM");
    const double scale = suffix == std::string::npos ? 1 : text[suffix] == 'k' ? 1e3 : 1e6;
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + std::min(suffix, text.size()) ||
        (suffix != std::string::npos && suffix + 1 != text.size()) || !(value >= 1))
        throw ConfigError("size '" + text +
                          "': expected a number of triangles such as 2000, 32k or 1M");
    return std::int64_t(value * scale);
}

double peak_rss_mib() {
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("VmHWM:", 0) == 0)
            return std::stod(line.substr(6)) / 1024.0; // kB
    return 0;
}

std::string ChildRun::failure() const {
    if (WIFSIGNALED(status))
        return "signal " + std::to_string(WTERMSIG(status));
    if (WEXITSTATUS(status) != 0)
        return "exit code " + std::to_string(WEXITSTATUS(status));
    return "";
}

ChildRun run_self(std::vector<std::string> args, double max_seconds, bool capture) {
    std::vector<char*> argv;
    for (std::string& a : args)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    int fds[2] = {-1, -1};
    if (capture && ::pipe(fds) != 0)
        throw ExternalError(args[0] + ": pipe failed");
    const pid_t pid = ::fork();
    if (pid < 0)
        throw ExternalError(args[0] + ": fork failed");
    if (pid == 0) {
        if (capture) {
            ::dup2(fds[1], STDOUT_FILENO);
            ::close(fds[0]);
            ::close(fds[1]);
        }
        ::execv("/proc/self/exe", argv.data());
        ::_exit(127);
    }
    if (capture)
        ::close(fds[1]);
    ChildRun run;
    const Clock::time_point start = Clock::now();
    while (::waitpid(pid, &run.status, WNOHANG) == 0) {
        if (seconds_since(start) > max_seconds) {
            ::kill(pid, SIGKILL);
            ::waitpid(pid, &run.status, 0);
            run.stopped = true;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (capture) {
        char buffer[512];
        for (ssize_t n; !run.stopped && (n = ::read(fds[0], buffer, sizeof buffer)) > 0;)
            run.out.append(buffer, std::size_t(n));
        ::close(fds[0]);
    }
    return run;
}

} // namespace penumbra::bench
