#pragma once
// The bake pipeline (mesh → solve → sensors → render → files), shared by the CLI, the viewer
// and the tests. main() only parses flags and maps errors to exit codes.

#include <optional>
#include <string>
#include <vector>

#include "core/context.h"
#include "core/image.h"
#include "core/mesh.h"
#include "core/scene.h"
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
    std::optional<Image> render; ///< when the scene has a camera and rendering is on
    std::vector<StageTime> times;
    std::uint64_t rays = 0;
};

struct BakeOptions {
    bool render = true;
};

/// \brief Runs mesher, solver, sensors and renderer on \p scene.
BakeResult bake(const Scene& scene, const BakeOptions& options, const Context& ctx);

/// \brief Writes mesh.vtu, render.exr/png, sensors.csv and summary.json into \p dir (each
///        file atomically). Throws ExternalError/ConfigError.
void write_outputs(const std::string& dir, const Scene& scene, const BakeResult& result);

/// \brief summary.json text: element count, rays, time per stage, power balance.
std::string summary_json(const Scene& scene, const BakeResult& result);

/// \brief sensors.csv text.
std::string sensors_csv(const Scene& scene, const BakeResult& result);

} // namespace penumbra::app
