// Xvfb as a child process. `-displayfd FD` makes the server choose a free display number and
// write it to FD once it accepts connections, so there is no guessing of numbers and no race
// with other servers (parallel tests). fork + execv rather than posix_spawn, because the child
// must ask for PR_SET_PDEATHSIG before it becomes Xvfb.

#include "virtual_display.h"

#include "core/error.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace penumbra::viewer {

namespace {

constexpr int k_start_timeout_ms = 20000;

const char* k_missing_xvfb =
    "penumbra view needs an X display; install xvfb (scripts/setup.sh does) or set DISPLAY";

/// Xvfb's path from PATH, looked up before fork (execvp is not async-signal-safe).
std::string find_xvfb() {
    const char* path = std::getenv("PATH");
    std::string dirs = path && *path ? path : "/usr/local/bin:/usr/bin:/bin";
    std::size_t start = 0;
    while (start <= dirs.size()) {
        std::size_t end = dirs.find(':', start);
        if (end == std::string::npos)
            end = dirs.size();
        const std::string candidate = dirs.substr(start, end - start) + "/Xvfb";
        if (end > start && ::access(candidate.c_str(), X_OK) == 0)
            return candidate;
        start = end + 1;
    }
    throw ConfigError(k_missing_xvfb);
}

/// Runs in the forked child: only async-signal-safe calls, then exec.
[[noreturn]] void exec_xvfb(const std::string& xvfb, char* const* argv, pid_t parent) {
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent)
        ::_exit(127);
    const int null_fd = ::open("/dev/null", O_RDWR);
    if (null_fd >= 0) { // Xvfb's start-up chatter (XKB, fonts) is not ours to show
        ::dup2(null_fd, STDIN_FILENO);
        ::dup2(null_fd, STDOUT_FILENO);
        ::dup2(null_fd, STDERR_FILENO);
    }
    ::execv(xvfb.c_str(), argv);
    ::_exit(127);
}

/// Reads the display number Xvfb writes to \p fd ("12\n"); empty on timeout or exit.
std::string read_display_number(int fd) {
    std::string text;
    int waited_ms = 0;
    while (waited_ms < k_start_timeout_ms) {
        pollfd p{fd, POLLIN, 0};
        const int ready = ::poll(&p, 1, 100);
        waited_ms += 100;
        if (ready < 0 && errno == EINTR)
            continue;
        if (ready <= 0)
            continue;
        char buf[32];
        const ssize_t n = ::read(fd, buf, sizeof buf);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return {}; // the server exited before reporting
        text.append(buf, std::size_t(n));
        if (text.find('\n') != std::string::npos)
            return text.substr(0, text.find('\n'));
    }
    return {};
}

void stop(pid_t pid) {
    ::kill(pid, SIGTERM);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
}

} // namespace

bool has_display() {
    const char* d = std::getenv("DISPLAY");
    return d && *d;
}

VirtualDisplay::VirtualDisplay(int width, int height) {
    const std::string xvfb = find_xvfb();
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0)
        throw ExternalError(fmt::format("cannot start Xvfb: pipe: {}", std::strerror(errno)));
    // The write end must survive exec in the child: a duplicate without O_CLOEXEC.
    const int child_fd = ::fcntl(fds[1], F_DUPFD, 3);
    const std::string screen =
        fmt::format("{}x{}x24", std::max(width, 1280), std::max(height, 1024));
    const std::string fd_text = std::to_string(child_fd);
    std::vector<std::string> args = {"Xvfb", "-displayfd", fd_text, "-screen", "0",
                                     screen, "-nolisten",  "tcp",   "-noreset"};
    std::vector<char*> argv;
    for (std::string& a : args)
        argv.push_back(a.data());
    argv.push_back(nullptr);

    const pid_t parent = ::getpid();
    pid_ = ::fork();
    if (pid_ == 0)
        exec_xvfb(xvfb, argv.data(), parent);
    const int fork_errno = errno;
    ::close(child_fd);
    ::close(fds[1]);
    if (pid_ < 0) {
        ::close(fds[0]);
        throw ExternalError(fmt::format("cannot start Xvfb: fork: {}", std::strerror(fork_errno)));
    }
    const std::string number = read_display_number(fds[0]);
    ::close(fds[0]);
    if (number.empty()) {
        stop(pid_);
        throw ExternalError(fmt::format("{} did not start within {} s (run it by hand to see why)",
                                        xvfb, k_start_timeout_ms / 1000));
    }
    display_ = ":" + number;
    if (const char* old = std::getenv("DISPLAY"))
        previous_display_ = old;
    ::setenv("DISPLAY", display_.c_str(), 1);
}

VirtualDisplay::~VirtualDisplay() {
    stop(pid_);
    if (previous_display_)
        ::setenv("DISPLAY", previous_display_->c_str(), 1);
    else
        ::unsetenv("DISPLAY");
}

} // namespace penumbra::viewer
