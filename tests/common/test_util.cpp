#include "common/test_util.h"

#include <cctype>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>

#include "core/error.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace penumbra::test {

namespace fs = std::filesystem;

std::string case_name(std::string_view label) {
    std::string out(label);
    for (char& c : out)
        if (!std::isalnum(static_cast<unsigned char>(c)))
            c = '_';
    return out;
}

std::string source_path(const std::string& relative) {
    return (fs::path(PENUMBRA_SOURCE_DIR) / relative).string();
}

std::string temp_dir(const std::string& tag) {
    static std::atomic<int> counter{0};
    fs::path dir =
        fs::temp_directory_path() / ("penumbra-test-" + tag + "-" + std::to_string(::getpid()) +
                                     "-" + std::to_string(counter++));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir.string();
}

namespace {
class StderrSink final : public LogSink {
public:
    void write(LogLevel level, std::string_view message) override {
        if (level >= LogLevel::warn)
            std::fprintf(stderr, "%.*s\n", int(message.size()), message.data());
    }
};
} // namespace

Context quiet_context(int threads) {
    Context ctx;
    ctx.log = std::make_shared<StderrSink>();
    ctx.threads = threads;
    ctx.min_level = LogLevel::warn;
    return ctx;
}

RunResult run_cli(const std::string& args, int time_limit_s) {
    const std::string limit =
        time_limit_s > 0 ? "timeout -k 5 " + std::to_string(time_limit_s) + " " : "";
    const std::string cmd = limit + PENUMBRA_CLI + " " + args + " 2>&1 1>/dev/null";
    RunResult r;
    FILE* pipe = ::popen(cmd.c_str(), "r");
    if (!pipe)
        return r;
    std::array<char, 4096> buf{};
    while (std::fgets(buf.data(), int(buf.size()), pipe))
        r.err += buf.data();
    const int status = ::pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

namespace {

/// What the child wrote to \p fd until it closed it.
std::string read_all(int fd) {
    std::string text;
    std::array<char, 4096> buf{};
    for (ssize_t n; (n = ::read(fd, buf.data(), buf.size())) != 0;) {
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0)
            break;
        text.append(buf.data(), std::size_t(n));
    }
    return text;
}

/// In a child: file sizes limited to \p max_bytes, and a write past it fails with EFBIG
/// instead of killing the process.
void limit_file_size(std::uint64_t max_bytes) {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{rlim_t(max_bytes), rlim_t(max_bytes)};
    ::setrlimit(RLIMIT_FSIZE, &limit);
}

} // namespace

RunResult run_cli_with_file_limit(const std::vector<std::string>& args, std::uint64_t max_bytes) {
    int err[2];
    RunResult r;
    if (::pipe(err) != 0)
        return r;
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::dup2(err[1], STDERR_FILENO);
        ::close(err[0]);
        ::close(err[1]);
        std::freopen("/dev/null", "w", stdout);
        limit_file_size(max_bytes);
        std::vector<char*> argv{const_cast<char*>(PENUMBRA_CLI)};
        for (const std::string& a : args)
            argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execv(PENUMBRA_CLI, argv.data());
        ::_exit(127);
    }
    ::close(err[1]);
    r.err = read_all(err[0]);
    ::close(err[0]);
    int status = 0;
    ::waitpid(pid, &status, 0);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

std::string external_error_with_file_limit(std::uint64_t max_bytes,
                                           const std::function<void()>& write) {
    int out[2];
    if (::pipe(out) != 0)
        return "other: no pipe";
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::close(out[0]);
        limit_file_size(max_bytes);
        std::string message;
        try {
            write();
        } catch (const ExternalError& e) {
            message = e.what();
        } catch (const std::exception& e) {
            message = std::string("other: ") + e.what();
        }
        [[maybe_unused]] const ssize_t n = ::write(out[1], message.data(), message.size());
        ::_exit(0);
    }
    ::close(out[1]);
    std::string message = read_all(out[0]);
    ::close(out[0]);
    int status = 0;
    ::waitpid(pid, &status, 0);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return "other: the child did not exit normally";
    return message;
}

std::uint32_t add_material(Scene& scene, const std::string& name, Rgb reflectance, Rgb emission,
                           bool two_sided) {
    Material m;
    m.name = name;
    m.reflectance = reflectance;
    m.emission = emission;
    m.two_sided = two_sided;
    scene.materials.push_back(m);
    return std::uint32_t(scene.materials.size() - 1);
}

std::uint32_t add_lobe_material(Scene& scene, const std::string& name, const Lobe& lobe) {
    const std::uint32_t index = add_material(scene, name, Rgb(0.0f), {}, false);
    scene.materials[index].lobe = lobe;
    return index;
}

void add_rect(Scene& scene, const std::string& name, std::uint32_t material, const Vec3& origin,
              const Vec3& u, const Vec3& v) {
    Polygon p;
    p.name = name;
    p.source = "test:" + name;
    p.material = material;
    p.vertices = {origin, origin + u, origin + u + v, origin + v};
    scene.polygons.push_back(p);
}

void add_room(Scene& scene, const Vec3& lo, const Vec3& hi, std::uint32_t material) {
    const Vec3 d = hi - lo;
    const Vec3 ex(d.x, 0, 0), ey(0, d.y, 0), ez(0, 0, d.z);
    add_rect(scene, "floor", material, lo, ex, ey);        // faces +z
    add_rect(scene, "ceiling", material, lo + ez, ey, ex); // faces -z
    add_rect(scene, "wall_y0", material, lo, ez, ex);      // faces +y
    add_rect(scene, "wall_y1", material, lo + ey, ex, ez); // faces -y
    add_rect(scene, "wall_x0", material, lo, ey, ez);      // faces +x
    add_rect(scene, "wall_x1", material, lo + ex, ez, ey); // faces -x
}

Camera square_camera(const Vec3& eye, const Vec3& look_at, const Vec3& up, double fov_deg,
                     int size) {
    Camera camera;
    camera.eye = eye;
    camera.look_at = look_at;
    camera.up = up;
    camera.fov_deg = fov_deg;
    camera.width = camera.height = size;
    return camera;
}

Scene furnace_room(float rho, float exitance) {
    Scene scene;
    const auto m = add_material(scene, "furnace", Rgb(rho), Rgb(float(exitance / k_pi)));
    add_room(scene, {0, 0, 0}, {1.0, 0.7, 0.5}, m);
    scene.mesher.max_edge_length = 0.2;
    scene.solver.residual = 1e-5;
    scene.solver.method = SolverMethod::shooting;
    return scene;
}

void add_cie171_room_without_ceiling(Scene& scene, std::uint32_t material) {
    const double h = 3;
    add_rect(scene, "floor", material, {0, 0, 0}, {4, 0, 0}, {0, 4, 0});
    add_rect(scene, "wall_y0", material, {0, 0, 0}, {0, 0, h}, {4, 0, 0});
    add_rect(scene, "wall_y4", material, {0, 4, 0}, {4, 0, 0}, {0, 0, h});
    add_rect(scene, "wall_x0", material, {0, 0, 0}, {0, 4, 0}, {0, 0, h});
    add_rect(scene, "wall_x4", material, {4, 0, 0}, {0, 0, h}, {0, 4, 0});
}

std::vector<double> add_cie171_59_sensors(Scene& scene) {
    const double floor_y[] = {0.25, 0.75, 1.25, 1.75, 2.25, 2.75, 3.25, 3.75};
    const double floor_sc[] = {2.289, 3.074, 3.823, 4.294, 4.294, 3.823, 3.074, 2.289};
    const double wall_z[] = {2.75, 2.25, 1.75, 1.25, 0.75, 0.25};
    const double wall_sc[] = {0.564, 1.783, 2.318, 2.198, 1.821, 1.427};
    std::vector<double> sky_component_pct;
    for (std::size_t i = 0; i < std::size(floor_y); ++i) {
        scene.sensors.push_back({"floor", {2, floor_y[i], 0}, {0, 0, 1}});
        sky_component_pct.push_back(floor_sc[i]);
    }
    for (std::size_t i = 0; i < std::size(wall_z); ++i) {
        scene.sensors.push_back({"wall", {2, 0, wall_z[i]}, {0, 1, 0}});
        sky_component_pct.push_back(wall_sc[i]);
    }
    return sky_component_pct;
}

std::uint32_t add_clear_glass(Scene& scene, const std::string& name) {
    Material glass;
    glass.name = name;
    glass.reflectance = Rgb(0);
    glass.lobe = ThinGlass{Rgb(0.762842f), 1.52};
    scene.materials.push_back(glass);
    return std::uint32_t(scene.materials.size() - 1);
}

void add_side_lit_room(Scene& scene, std::uint32_t walls, std::uint32_t pane, double window_x0,
                       double window_x1) {
    add_rect(scene, "floor", walls, {0, 0, 0}, {4, 0, 0}, {0, 3, 0});
    add_rect(scene, "ceiling", walls, {0, 0, 2.5}, {0, 3, 0}, {4, 0, 0});
    add_rect(scene, "wall_x0", walls, {0, 0, 0}, {0, 3, 0}, {0, 0, 2.5});
    add_rect(scene, "wall_x4", walls, {4, 0, 0}, {0, 0, 2.5}, {0, 3, 0});
    add_rect(scene, "wall_y3", walls, {0, 3, 0}, {4, 0, 0}, {0, 0, 2.5});
    add_rect(scene, "sill", walls, {0, 0, 0}, {0, 0, 0.8}, {4, 0, 0});
    add_rect(scene, "lintel", walls, {0, 0, 1.8}, {0, 0, 0.7}, {4, 0, 0});
    add_rect(scene, "jamb_w", walls, {0, 0, 0.8}, {0, 0, 1}, {window_x0, 0, 0});
    add_rect(scene, "jamb_e", walls, {window_x1, 0, 0.8}, {0, 0, 1}, {4 - window_x1, 0, 0});
    add_rect(scene, "pane", pane, {window_x0, 0, 0.8}, {0, 0, 1}, {window_x1 - window_x0, 0, 0});
}

int expect_one_line_input_error(const std::function<void()>& load,
                                const std::vector<std::string>& parts, const std::string& what) {
    try {
        load();
        ADD_FAILURE() << "no InputError for " << what;
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        for (const std::string& part : parts)
            EXPECT_NE(message.find(part), std::string::npos)
                << "'" << part << "' missing from: " << message;
        return e.line();
    }
    return 0;
}

} // namespace penumbra::test
