#pragma once
// The VTK scene of `penumbra view`: the mesh coloured by one array (true colour, or false
// colour with a scalar bar, linear or log), element edges, sensor and discontinuity overlays,
// a status line, camera presets and picking. The window and the off-screen PNG share it.

#include "core/context.h"

#include "view_data.h"
#include "vtk_util.h"

#include <vtkActor.h>
#include <vtkDataSetMapper.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkSmartPointer.h>
#include <vtkTextActor.h>

#include <cstddef>
#include <string>
#include <vector>

namespace penumbra::viewer {

struct ViewState {
    std::size_t array = 0; ///< index into ViewData::arrays()
    std::size_t step = 0;
    bool log_scale = false;
    bool edges = false;
    bool sensors = false;
    bool discontinuities = false;
};

class ViewScene {
public:
    /// \brief Builds the scene in a window of \p width × \p height; \p offscreen for PNGs.
    ///        \p data must outlive the scene.
    ViewScene(const ViewData& data, const ViewState& state, int width, int height, bool offscreen,
              const Context& ctx);

    vtkRenderWindow* window() { return window_; }
    vtkRenderer* renderer() { return renderer_; }
    const ViewState& state() const { return state_; }

    void cycle_array(int delta);
    void toggle_log();
    void toggle_edges();
    void toggle_sensors();
    void toggle_discontinuities();
    void change_step(int delta);
    /// \brief The scene camera stored in the file; without one, the same as fit_camera().
    void scene_camera();
    void fit_camera();
    /// \brief Picks at display pixel (x, y) from the bottom left; logs and shows the value.
    void pick(int x, int y);
    /// \brief Shows the status line and key help (the window; PNGs show neither).
    void show_text(bool on);

    /// \brief Renders; throws ExternalError if VTK reported an error.
    void render();
    /// \brief Renders and writes the picture to \p path (PNG, atomically).
    void write_png(const std::string& path);

private:
    void load_step();
    void apply_array();
    void add_overlays();
    void update_status();
    std::string describe_surface_pick(vtkIdType cell, const double pcoords[3], int sub_id);

    const ViewData& data_;
    ViewState state_;
    const Context& ctx_;
    vtkSmartPointer<vtkDataSet> current_;
    std::string picked_;

    vtkNew<vtkRenderWindow> window_;
    vtkNew<vtkRenderer> renderer_;
    vtkNew<vtkDataSetMapper> mapper_;
    vtkNew<vtkActor> actor_;
    vtkNew<vtkLookupTable> lut_;
    vtkNew<vtkScalarBarActor> scalar_bar_;
    vtkNew<vtkTextActor> bar_title_; ///< the bar's own title is centred and runs off the edge
    vtkNew<vtkTextActor> status_;
    vtkNew<vtkTextActor> help_;
    vtkNew<vtkActor> sensors_;
    vtkNew<vtkActor> discontinuities_;
    vtkNew<ErrorCapture> errors_;
};

/// \brief Shows \p scene in its window and handles keys and clicks until the user quits.
///        \p script events (ViewOptions::script) are played one every 50 ms after the first
///        frame, through the interactor as real key and mouse events.
void run_window(ViewScene& scene, const std::vector<std::string>& script, const Context& ctx);

} // namespace penumbra::viewer
