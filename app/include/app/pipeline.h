#pragma once
// The bake pipeline (mesh → solve → sensors → render → files), shared by the CLI, the viewer
// and the tests. main() only parses flags and maps errors to exit codes.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/context.h"
#include "core/image.h"
#include "core/mesh.h"
#include "core/scene.h"
#include "raytrace/raytrace.h"
#include "solver/solver.h"

namespace penumbra::app {

struct StageTime {
    std::string stage;
    double seconds = 0;
};

struct BakeResult {
    RadiosityMesh mesh;
    Solution solution;
    solver::SolveStats stats;
    std::vector<solver::SensorReading> sensors;
    std::optional<Image> render;            ///< when the scene has a camera and rendering is on
    raytrace::RenderOptions render_options; ///< how render was made
    std::uint64_t render_rays = 0;          ///< rays the render traced
    std::vector<StageTime> times;
    std::uint64_t rays = 0;
    std::string series_dir; ///< where the solve's series was written (empty if none)
    std::size_t series_steps = 0;
    /// Hierarchical: the hierarchy, links and radiosities, for a later re-solve.
    std::shared_ptr<const solver::HierarchicalState> solver_state;
    /// Hierarchical, with BakeOptions::keep_input_mesh: the mesher's mesh that refinement
    /// started from (mesh is the leaf mesh): its emitters are the same surfaces in fewer
    /// elements, for gathers whose cost grows with the emitting elements (lightmap texels).
    std::optional<RadiosityMesh> input_mesh;
};

struct BakeOptions {
    bool render = true;
    /// How to render; unset: default_render_options() of the scene.
    std::optional<raytrace::RenderOptions> render_options;
    /// When > 0, the solve writes a VTK snapshot every this many shots, and the final solution
    /// as the last step, to series_dir/series/ and series_dir/series.pvd (viewer::SeriesWriter).
    std::int64_t series_every_shots = 0;
    std::string series_dir;
    /// Hierarchical: re-solve from this saved state (same geometry; reflectances and
    /// emissions from the scene).
    const solver::HierarchicalState* reuse = nullptr;
    /// Hierarchical: keep the solver state (every link) in the result, to write
    /// solver_state.bin; without it the links are freed once the solve is done, before the
    /// sensors and the render (most of a big scene's memory).
    bool keep_state = true;
    /// Hierarchical: keep the mesher's mesh in BakeResult::input_mesh.
    bool keep_input_mesh = false;
    /// False: mesh and render only, no solve and no sensors (`penumbra render --gather none`,
    /// whose path tracer reads no solution, so that equal-time comparisons are fair).
    bool solve = true;
};

/// \brief The render `bake` makes without options: the final gather at the camera's samples
///        per pixel when some material has a non-diffuse lobe (the radiosity view cannot show
///        it), else the radiosity view (GatherMode::radiosity), which is fast and enough for a
///        diffuse scene's preview; `penumbra render` gives the final gather for any scene.
raytrace::RenderOptions default_render_options(const Scene& scene);

/// \brief Runs mesher, solver, sensors and renderer on \p scene.
BakeResult bake(const Scene& scene, const BakeOptions& options, const Context& ctx);

/// \brief Writes the bake's outputs into \p dir through the list of writers of
///        app/src/outputs.cpp (mesh.vtu, discontinuities.vtp, sensors.vtp, render.exr/png,
///        sensors.csv, solver_state.bin when \p save_state, summary.json; each file
///        atomically), and removes those of an earlier bake in \p dir that this one does not
///        write (a series included). Throws ExternalError/ConfigError.
void write_outputs(const std::string& dir, const Scene& scene, const BakeResult& result,
                   bool save_state = true);

/// \brief Writes `penumbra render`'s outputs into \p dir: render.exr (linear), render.png
///        (tone-mapped as the bake's) and render.json (render_json()). Throws
///        ExternalError/ConfigError.
void write_render_outputs(const std::string& dir, const Scene& scene, const BakeResult& result);

/// \brief render.json text: the gather mode, samples, image size, seconds per stage, the
///        render's rays and rays per second.
std::string render_json(const Scene& scene, const BakeResult& result);

/// The solver state file a bake writes into its output folder.
inline constexpr const char* k_solver_state_file = "solver_state.bin";

/// \brief The options of `penumbra view` as the CLI gives them (see viewer/view.h, which
///        this library wraps so that the CLI links the pipeline only).
struct ViewRequest {
    std::string input; ///< output folder or .vtu/.vtp/.pvd file
    std::string png;   ///< empty = interactive window
    std::string size;  ///< "WxH" or empty
    std::string array; ///< empty = true colour
    bool log_scale = false;
    bool edges = false;
    bool sensors = false;
    bool discontinuities = false;
    int step = -1;      ///< -1 = last
    std::string script; ///< comma-separated scripted events (tests)
};

/// \brief Runs `penumbra view`: the window, or the PNG. Throws ConfigError for bad options.
void view(const ViewRequest& request, const Context& ctx);

/// \brief The window's controls, for `penumbra view --help`.
std::string view_controls_help();

/// \brief summary.json text: element count, rays, time per stage, power balance.
std::string summary_json(const Scene& scene, const BakeResult& result);

/// \brief sensors.csv text.
std::string sensors_csv(const Scene& scene, const BakeResult& result);

} // namespace penumbra::app
