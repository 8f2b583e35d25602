#include "outputs.h"

#include <filesystem>

#include "core/files.h"
#include "core/image.h"
#include "viewer/vtk_output.h"

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
