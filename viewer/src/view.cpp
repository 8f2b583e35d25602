// `penumbra view`: checks the options against the data, makes sure there is an X display
// (a private Xvfb when DISPLAY is unset), then shows the window or writes the PNG.

#include "viewer/view.h"

#include "core/error.h"
#include "core/files.h"

#include "view_data.h"
#include "view_scene.h"
#include "virtual_display.h"

#include <X11/Xlib.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>

namespace penumbra::viewer {

namespace {

namespace fs = std::filesystem;

constexpr int k_min_size = 16, k_max_size = 8192;

/// True if the DISPLAY we were given accepts connections (VTK aborts the process if not).
bool display_works() {
    Display* display = XOpenDisplay(nullptr);
    if (!display)
        return false;
    XCloseDisplay(display);
    return true;
}

ViewState initial_state(const ViewOptions& options, const ViewData& data) {
    ViewState state;
    state.log_scale = options.log_scale;
    state.edges = options.edges;
    state.sensors = options.sensors;
    state.discontinuities = options.discontinuities;
    if (!options.array.empty()) {
        const ArrayInfo* info = data.find(options.array);
        if (!info)
            throw ConfigError(fmt::format("--array '{}': no such array in {} (known: {})",
                                          options.array, data.source(), data.array_names()));
        state.array = std::size_t(info - data.arrays().data());
    }
    const int steps = int(data.steps().size());
    if (options.step >= steps || options.step < -1)
        throw ConfigError(fmt::format("--step {}: {} has {} step{} (0 to {})", options.step,
                                      data.source(), steps, steps == 1 ? "" : "s", steps - 1));
    state.step = std::size_t(options.step < 0 ? steps - 1 : options.step);
    return state;
}

/// The picture size: --size, else the scene camera's image size; a window at least 800 pixels
/// on its longer side.
void picture_size(const ViewOptions& options, const ViewData& data, int& width, int& height) {
    width = options.width;
    height = options.height;
    if (width > 0 && height > 0)
        return;
    const auto& camera = data.camera();
    width = camera && camera->width > 0 ? camera->width : 800;
    height = camera && camera->height > 0 ? camera->height : 800;
    if (options.png.empty() && std::max(width, height) < 800) {
        const double scale = 800.0 / std::max(width, height);
        width = int(width * scale + 0.5);
        height = int(height * scale + 0.5);
    }
}

void check_png_path(const std::string& png) {
    const fs::path folder = fs::absolute(png).parent_path();
    std::error_code ec;
    if (!fs::is_directory(folder, ec))
        throw ConfigError(
            fmt::format("--png '{}': folder '{}' does not exist", png, folder.string()));
    // Refused before VTK renders, not when the picture is written: that took 40 s under load.
    check_replaceable(png);
}

} // namespace

void parse_image_size(const std::string& text, int& width, int& height) {
    int w = 0, h = 0;
    char tail = 0;
    if (std::sscanf(text.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < k_min_size ||
        h < k_min_size || w > k_max_size || h > k_max_size)
        throw ConfigError(fmt::format("--size '{}': expected WIDTHxHEIGHT in pixels, each {} to "
                                      "{}, e.g. 800x600",
                                      text, k_min_size, k_max_size));
    width = w;
    height = h;
}

const char* view_controls_help() {
    return "mouse  left drag: rotate, middle drag: pan, right drag or wheel: zoom,\n"
           "       left click: show the value of the shown array under the cursor\n"
           "a / A  next / previous array (true_colour, then the file's arrays)\n"
           "l      linear / log colour scale\n"
           "e      element edges on / off\n"
           "n / p  next / previous step of a series (.pvd)\n"
           "c      scene camera;  r  fit the whole mesh\n"
           "s      sensors on / off;  d  discontinuity lines on / off\n"
           "q, Esc quit\n";
}

void view(const ViewOptions& options, const Context& ctx) {
    const bool to_png = !options.png.empty();
    if (to_png)
        check_png_path(options.png);
    const ViewData data(options.input);
    const ViewState state = initial_state(options, data);
    int width = 0, height = 0;
    picture_size(options, data, width, height);

    // A window on a private server is invisible: only pictures and scripted tests use one.
    std::optional<VirtualDisplay> display;
    if (!has_display() || !display_works()) {
        if (!to_png && options.script.empty())
            throw ConfigError(has_display() ? "cannot open the X display (DISPLAY is set but does "
                                              "not answer); use --png FILE to render off-screen"
                                            : "no X display for the window (DISPLAY is not set); "
                                              "use --png FILE to render off-screen");
        display.emplace(width, height);
        ctx.debug("view: started Xvfb on display {}", display->display());
    }
    ViewScene scene(data, state, width, height, to_png, ctx);
    if (to_png) {
        scene.write_png(options.png);
        ctx.info("wrote {} ({}x{}, {})", options.png, width, height,
                 data.arrays()[state.array].name);
        return;
    }
    run_window(scene, options.script, ctx);
}

} // namespace penumbra::viewer
