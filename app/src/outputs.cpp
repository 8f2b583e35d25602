#include "outputs.h"

#include <algorithm>
#include <filesystem>
#include <optional>

#include "core/error.h"
#include "core/files.h"
#include "core/image.h"
#include "viewer/vtk_output.h"

#include "daylight.h"
#include "grid_plan.h"

namespace penumbra::app {

namespace fs = std::filesystem;

namespace {

bool same_folder(const std::string& a, const std::string& b) {
    std::error_code ec;
    return !a.empty() && fs::equivalent(a, b, ec);
}

bool always(const OutputTarget&) {
    return true;
}

bool has_sensors(const OutputTarget& t) {
    return !t.scene.sensors.empty();
}

void write_render(const OutputTarget& t) {
    const Image& image = *t.result.render;
    write_exr(t.path("render.exr"), image);
    const double exposure =
        t.scene.camera->exposure > 0 ? t.scene.camera->exposure : auto_exposure(image);
    write_png(t.path("render.png"), image, exposure);
}

} // namespace

void write_render_outputs(const std::string& dir, const Scene& scene, const BakeResult& result) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec)
        throw ConfigError(fmt::format("cannot create output folder '{}': {}", dir, ec.message()));
    const OutputTarget target{scene, result, dir, false};
    write_render(target);
    write_text_file(target.path("render.json"), render_json(scene, result));
}

namespace {

bool has_grids(const OutputTarget& t) {
    return !t.scene.grids.empty();
}

/// grid_NAME.png and grid_NAME.vtp of every grid.
std::vector<std::string> grid_file_names(const OutputTarget& t) {
    std::vector<std::string> names;
    for (const SensorGrid& grid : t.scene.grids)
        for (const char* extension : {".png", ".vtp"})
            names.push_back("grid_" + grid.name + extension);
    return names;
}

/// Removes the grid_*.png and grid_*.vtp files of the output folder not in \p keep: those of
/// grids an earlier bake had.
void remove_grid_files(const std::string& dir, const std::vector<std::string>& keep) {
    std::error_code ec;
    std::vector<fs::path> stale;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        const std::string extension = it->path().extension().string();
        if (name.starts_with("grid_") && (extension == ".png" || extension == ".vtp") &&
            it->is_regular_file(ec) && std::find(keep.begin(), keep.end(), name) == keep.end())
            stale.push_back(it->path());
    }
    for (const fs::path& path : stale)
        fs::remove(path, ec);
}

void write_grid_files(const OutputTarget& t) {
    remove_grid_files(t.dir, grid_file_names(t));
    const std::optional<double> reference_lx = daylight_reference_lx(t.scene);
    const PlanQuantity quantity = plan_quantity(reference_lx);
    for (const SensorGrid& grid : t.scene.grids) {
        std::vector<double> values = grid_illuminance_lx(grid, t.result.sensors);
        for (double& value : values)
            value *= quantity.per_lx;
        draw_grid_plan(grid, values, quantity).write_png(t.path("grid_" + grid.name + ".png"));
        viewer::write_grid_vtp(t.path("grid_" + grid.name + ".vtp"), t.scene, grid,
                               t.result.sensors, reference_lx);
    }
}

std::vector<OutputWriter> make_bake_writers() {
    std::vector<OutputWriter> w;
    w.push_back({"mesh", {"mesh.vtu"}, always, [](const OutputTarget& t) {
                     viewer::write_vtu(t.path("mesh.vtu"), t.scene, t.result.mesh,
                                       t.result.solution);
                 }});
    w.push_back({"discontinuities",
                 {"discontinuities.vtp"},
                 [](const OutputTarget& t) { return !t.result.mesh.discontinuities.empty(); },
                 [](const OutputTarget& t) {
                     viewer::write_discontinuities_vtp(t.path("discontinuities.vtp"),
                                                       t.result.mesh);
                 }});
    w.push_back({"sensor points", {"sensors.vtp"}, has_sensors, [](const OutputTarget& t) {
                     viewer::write_sensors_vtp(t.path("sensors.vtp"), t.scene, t.result.sensors);
                 }});
    // Written during the solve (SeriesWriter): only kept or removed here.
    w.push_back({"series",
                 {"series.pvd", "series"},
                 [](const OutputTarget& t) {
                     return t.result.series_steps > 0 && same_folder(t.result.series_dir, t.dir);
                 },
                 [](const OutputTarget&) {},
                 // Only the series' own files: a user's file in series/ stays.
                 [](const OutputTarget& t) { viewer::remove_series(t.dir); }});
    w.push_back({"render",
                 {"render.exr", "render.png"},
                 [](const OutputTarget& t) { return t.result.render.has_value(); },
                 write_render});
    w.push_back({"sensor values", {"sensors.csv"}, has_sensors, [](const OutputTarget& t) {
                     write_text_file(t.path("sensors.csv"), sensors_csv(t.scene, t.result));
                 }});
    w.push_back({"grid statistics", {"grids.csv"}, has_grids, [](const OutputTarget& t) {
                     write_text_file(t.path("grids.csv"), grids_csv(t.scene, t.result));
                 }});
    w.push_back({"grid plans",
                 {},
                 has_grids,
                 write_grid_files,
                 [](const OutputTarget& t) { remove_grid_files(t.dir, {}); },
                 grid_file_names});
    w.push_back({"solver state",
                 {k_solver_state_file},
                 [](const OutputTarget& t) { return t.result.solver_state && t.save_state; },
                 [](const OutputTarget& t) {
                     solver::write_hierarchical_state(*t.result.solver_state,
                                                      t.path(k_solver_state_file));
                 }});
    w.push_back({"summary", {"summary.json"}, always, [](const OutputTarget& t) {
                     write_text_file(t.path("summary.json"), summary_json(t.scene, t.result));
                 }});
    return w;
}

} // namespace

std::string OutputTarget::path(const std::string& name) const {
    return (fs::path(dir) / name).string();
}

const std::vector<OutputWriter>& bake_writers() {
    static const std::vector<OutputWriter> writers = make_bake_writers();
    return writers;
}

void remove_output(const OutputWriter& writer, const OutputTarget& target) {
    if (writer.remove) {
        writer.remove(target);
        return;
    }
    std::error_code ec;
    for (const std::string& name : writer.files)
        fs::remove(target.path(name), ec);
}

} // namespace penumbra::app
