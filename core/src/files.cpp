#include "core/files.h"

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include "core/error.h"

namespace penumbra {

namespace fs = std::filesystem;

namespace {

constexpr const char* k_temp_infix = ".tmp";

std::string temp_name_for(const std::string& path) {
    fs::path p(path);
    std::string name = "." + p.filename().string() + k_temp_infix + std::to_string(::getpid());
    return (p.parent_path() / name).string();
}

// The temporary files being written, as C strings in fixed slots, so that a signal handler can
// read them without locking or allocating. A slot is published (in_use set) only once its
// path is complete; registration and release take the mutex among themselves.
constexpr std::size_t k_temp_slots = 64;
constexpr std::size_t k_temp_path_max = 4096;
struct TempSlot {
    std::atomic<bool> in_use{false};
    char path[k_temp_path_max] = {};
};
std::array<TempSlot, k_temp_slots> g_temp_slots;
std::mutex g_temp_mutex;

/// Registers a temporary path for the lifetime of the object; a path too long for a slot, or
/// one beyond the slots, is written but not registered (only its clean-up on a signal is lost).
class TempRegistration {
public:
    explicit TempRegistration(const std::string& path) {
        if (path.size() >= k_temp_path_max)
            return;
        const std::lock_guard lock(g_temp_mutex);
        for (TempSlot& s : g_temp_slots)
            if (!s.in_use.load(std::memory_order_relaxed)) {
                std::memcpy(s.path, path.c_str(), path.size() + 1);
                s.in_use.store(true, std::memory_order_release);
                slot_ = &s;
                return;
            }
    }
    ~TempRegistration() {
        if (!slot_)
            return;
        const std::lock_guard lock(g_temp_mutex);
        slot_->in_use.store(false, std::memory_order_release);
    }
    TempRegistration(const TempRegistration&) = delete;
    TempRegistration& operator=(const TempRegistration&) = delete;

private:
    TempSlot* slot_ = nullptr;
};

/// The PID of a temporary name ".NAME.tmpPID" for \p name, or 0 if \p file is not one.
pid_t temp_pid(const std::string& file, const std::string& name) {
    const std::string prefix = "." + name + k_temp_infix;
    if (file.size() <= prefix.size() || file.compare(0, prefix.size(), prefix) != 0)
        return 0;
    const std::string digits = file.substr(prefix.size());
    if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos)
        return 0;
    return pid_t(std::stol(digits));
}

bool process_alive(pid_t pid) {
    return ::kill(pid, 0) == 0 || errno != ESRCH;
}

} // namespace

void check_replaceable(const std::string& path) {
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (fs::exists(status) && !fs::is_regular_file(status))
        throw ConfigError(fmt::format("'{}' is not a regular file", path));
}

void write_atomically(const std::string& path,
                      const std::function<void(const std::string& temp_path)>& write) {
    check_replaceable(path);
    const std::string temp = temp_name_for(path);
    const TempRegistration registration(temp);
    try {
        write(temp);
    } catch (...) {
        std::error_code ec;
        fs::remove(temp, ec);
        throw;
    }
    std::error_code ec;
    fs::rename(temp, path, ec);
    if (ec) {
        const std::string reason = ec.message();
        fs::remove(temp, ec);
        throw ExternalError(fmt::format("cannot write '{}': {}", path, reason));
    }
}

void write_text_file(const std::string& path, std::string_view text) {
    write_atomically(path, [&](const std::string& temp) {
        FileWriter file(temp, path);
        file.write(text.data(), text.size());
        file.close();
    });
}

namespace {
// Gathers small pieces (VTK's XML text, the state file's counts) into few system calls;
// blocks at least this large go out directly.
constexpr std::size_t k_file_buffer_bytes = std::size_t(1) << 20;
} // namespace

FileWriter::FileWriter(const std::string& temp_path, std::string name) : name_(std::move(name)) {
    fd_ = ::open(temp_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd_ < 0)
        fail(errno);
    buffer_.reserve(k_file_buffer_bytes);
}

FileWriter::~FileWriter() {
    if (fd_ >= 0)
        ::close(fd_);
}

void FileWriter::write(const void* data, std::size_t size) {
    if (error_)
        rethrow();
    const char* bytes = static_cast<const char*>(data);
    if (buffer_.size() + size > k_file_buffer_bytes)
        flush();
    if (size < k_file_buffer_bytes) {
        buffer_.append(bytes, size);
        return;
    }
    // A large block goes out directly, not through the buffer.
    for (std::size_t at = 0; at < size;) {
        const ssize_t n = ::write(fd_, bytes + at, size - at);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            fail(n < 0 ? errno : EIO);
        at += std::size_t(n);
        file_position_ += std::uint64_t(n);
    }
}

void FileWriter::flush() {
    for (std::size_t at = 0; at < buffer_.size();) {
        const ssize_t n = ::write(fd_, buffer_.data() + at, buffer_.size() - at);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            fail(n < 0 ? errno : EIO);
        at += std::size_t(n);
    }
    file_position_ += buffer_.size();
    buffer_.clear();
}

void FileWriter::seek(std::uint64_t position) {
    if (error_)
        rethrow();
    flush();
    if (::lseek(fd_, off_t(position), SEEK_SET) < 0)
        fail(errno);
    file_position_ = position;
}

void FileWriter::close() {
    if (error_)
        rethrow();
    flush();
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0)
        fail(errno);
}

void FileWriter::rethrow() const {
    throw ExternalError(fmt::format("cannot write '{}': {}", name_, std::strerror(error_)));
}

void FileWriter::fail(int error) {
    error_ = error;
    rethrow();
}

void remove_temp_files_on_signal() noexcept {
    for (TempSlot& s : g_temp_slots)
        if (s.in_use.load(std::memory_order_acquire))
            ::unlink(s.path);
}

std::size_t remove_stale_temp_files(const std::string& dir, const std::vector<std::string>& names) {
    std::error_code ec;
    std::size_t removed = 0;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string file = it->path().filename().string();
        for (const std::string& name : names) {
            const pid_t pid = temp_pid(file, name);
            if (pid > 0 && pid != ::getpid() && !process_alive(pid) && it->is_regular_file(ec) &&
                fs::remove(it->path(), ec))
                ++removed;
        }
    }
    return removed;
}

std::string read_text_file(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec))
        throw InputError(path, "", "file not found");
    if (fs::is_directory(path, ec))
        throw InputError(path, "", "is a folder, not a file");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw InputError(path, "", std::string("cannot open: ") + std::strerror(errno));
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

void check_output_dir(const std::string& dir) {
    std::error_code ec;
    fs::path p(dir);
    fs::path first_created; // the highest folder this call creates, to undo
    for (fs::path probe = fs::absolute(p, ec); !probe.empty() && !fs::exists(probe, ec);
         probe = probe.parent_path()) {
        first_created = probe;
        if (probe == probe.parent_path())
            break;
    }
    if (fs::exists(p, ec) && !fs::is_directory(p, ec))
        throw ConfigError(fmt::format("output folder '{}' is a file", dir));
    fs::create_directories(p, ec);
    if (ec)
        throw ConfigError(fmt::format("cannot create output folder '{}': {}", dir, ec.message()));
    const fs::path probe_file = p / (".penumbra-write-test" + std::to_string(::getpid()));
    std::ofstream out(probe_file);
    const bool ok = bool(out);
    out.close();
    fs::remove(probe_file, ec);
    if (!first_created.empty())
        fs::remove_all(first_created, ec); // created again when the outputs are written
    if (!ok)
        throw ConfigError(fmt::format("output folder '{}' is not writable", dir));
}

} // namespace penumbra
