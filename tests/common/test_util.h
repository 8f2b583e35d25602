#pragma once
// Helpers shared by the test suites.

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "core/context.h"

namespace penumbra::test {

/// Absolute path of a file in the source tree (e.g. "data/cornell/scene.json").
/// \brief A test-case name for a parameter labelled \p label (for INSTANTIATE_TEST_SUITE_P's
///        name generators): its letters and digits, every other character as '_'.
std::string case_name(std::string_view label);

std::string source_path(const std::string& relative);

/// A fresh empty temporary folder, unique per call.
std::string temp_dir(const std::string& tag);

/// A context that logs warnings and errors to stderr only, with the given thread count.
Context quiet_context(int threads = 0);

/// A progress sink that records its stages, its fractions and the stage of each (an index
/// into stages), and cancels at the cancel_after-th update.
class RecordingProgress final : public ProgressSink {
public:
    void begin(std::string_view stage) override { stages.emplace_back(stage); }
    bool update(double fraction) override {
        fractions.push_back(fraction);
        stage_of.push_back(stages.size() - 1);
        return fractions.size() < cancel_after;
    }
    void end() override { ++ended; }

    std::vector<std::string> stages;
    std::vector<double> fractions;
    std::vector<std::size_t> stage_of;
    std::size_t cancel_after = 1000000;
    int ended = 0;
};

} // namespace penumbra::test

#include "core/scene.h"

namespace penumbra::test {

/// Exit code and standard error of one run of the penumbra CLI.
struct RunResult {
    int exit_code = -1;
    std::string err;
};

/// \brief Runs the built penumbra CLI with \p args (standard output discarded). With
///        \p time_limit_s > 0 the run is killed after that many seconds (exit code 124), so a
///        command that should fail at once cannot hang the test instead.
RunResult run_cli(const std::string& args, int time_limit_s = 0);

/// \brief Runs the built penumbra CLI with \p args (one per word, standard output discarded)
///        in a process whose files may not grow past \p max_bytes: RLIMIT_FSIZE with SIGXFSZ
///        ignored, so that write(2) fails with EFBIG as a full disk fails with ENOSPC.
RunResult run_cli_with_file_limit(const std::vector<std::string>& args, std::uint64_t max_bytes);

/// \brief Runs \p write in a child process under the file size limit of
///        run_cli_with_file_limit(). Returns the message of the ExternalError it threw; ""
///        if it returned normally; "other: …" for any other exception or ending.
std::string external_error_with_file_limit(std::uint64_t max_bytes,
                                           const std::function<void()>& write);

/// Adds a material; returns its index.
std::uint32_t add_material(Scene& scene, const std::string& name, Rgb reflectance,
                           Rgb emission = {}, bool two_sided = true);
/// Adds a one-sided material of \p lobe alone (its diffuse part black); returns its index.
std::uint32_t add_lobe_material(Scene& scene, const std::string& name, const Lobe& lobe);

/// Adds the parallelogram origin, origin + u, origin + u + v, origin + v; its front faces
/// along u × v.
void add_rect(Scene& scene, const std::string& name, std::uint32_t material, const Vec3& origin,
              const Vec3& u, const Vec3& v);

/// A pinhole camera at \p eye looking at \p look_at (\p up), \p fov_deg wide, of size × size
/// pixels.
Camera square_camera(const Vec3& eye, const Vec3& look_at, const Vec3& up, double fov_deg,
                     int size);

/// Adds an axis-aligned box room [lo, hi] whose six walls face inwards.
void add_room(Scene& scene, const Vec3& lo, const Vec3& hi, std::uint32_t material);

/// \brief A closed 1 × 0.7 × 0.5 m room (not a cube: any shape works) whose every wall emits
///        \p exitance (W/m²) and reflects \p rho, so that B = E / (1 − ρ) everywhere; 0.2 m
///        elements, progressive shooting to a residual of 10⁻⁵ (hierarchical radiosity would
///        refine every wall, all emitters, far down for no change in a uniform solution).
Scene furnace_room(float rho, float exitance);

/// Adds the floor and four walls (facing inwards) of CIE 171's 4 × 4 × 3 m test room, x and y
/// in [0, 4], z in [0, 3]; the tests add their own ceilings.
void add_cie171_room_without_ceiling(Scene& scene, std::uint32_t material);

/// \brief Adds the sensors of CIE 171 test case 5.9 (8 on the floor along y, then 6 on the
///        wall y = 0 down from the top) to a room of add_cie171_room_without_ceiling; returns
///        their closed-form sky components (%), in the same order
///        (/work/shared/validation/README.md §3, docs/validation.md).
std::vector<double> add_cie171_59_sensors(Scene& scene);

/// \brief Adds Radiance's clear glass as a thin_glass material (transmissivity 0.762842 at
///        normal incidence, n = 1.52: 0.620 hemispherically, no diffuse part); returns its
///        index.
std::uint32_t add_clear_glass(Scene& scene, const std::string& name = "glass");

/// \brief Adds a 4 × 3 × 2.5 m room (walls facing inwards) with a window in its wall y = 0:
///        x from \p window_x0 to \p window_x1, z from 0.8 to 1.8 m, filled by a polygon of
///        material \p pane.
void add_side_lit_room(Scene& scene, std::uint32_t walls, std::uint32_t pane, double window_x0,
                       double window_x1);

/// \brief Runs \p load and expects an InputError whose message is one line holding each of
///        \p parts; returns the error's line (0 if none was thrown). \p what names the input
///        in failure messages.
int expect_one_line_input_error(const std::function<void()>& load,
                                const std::vector<std::string>& parts, const std::string& what);

} // namespace penumbra::test
