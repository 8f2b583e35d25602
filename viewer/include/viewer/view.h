#pragma once
// `penumbra view`: the radiosity mesh in an interactive VTK window, or the same picture
// rendered off-screen to a PNG. Reads only files (mesh.vtu, series.pvd, sensors.vtp,
// discontinuities.vtp); Debian's VTK renders only through X, so without DISPLAY a private
// Xvfb server is started for the duration of the call.

#include <string>
#include <vector>

#include "core/context.h"

namespace penumbra::viewer {

/// The pseudo-array that shows radiosity as display colour (radiance B/π, automatic exposure,
/// sRGB) instead of false colour.
inline constexpr const char* k_true_colour = "true_colour";

struct ViewOptions {
    /// An output folder (its series.pvd if present, else its mesh.vtu), or a .vtu, .vtp or
    /// .pvd file.
    std::string input;
    std::string png; ///< when set, write this PNG off-screen instead of opening a window
    int width = 0;   ///< pixels; 0 = the scene camera's image size (else 800 × 800)
    int height = 0;
    std::string array; ///< shown array; empty = true_colour if radiosity exists, else the first
    bool log_scale = false;
    bool edges = false;           ///< draw element edges
    bool sensors = false;         ///< draw the folder's sensors.vtp points
    bool discontinuities = false; ///< draw the folder's discontinuities.vtp lines
    int step = -1; ///< series step, counted from 0; -1 = the last (the final solution)
    /// Events played one every 50 ms once the window shows (tests): a key ("a", "A", "Escape")
    /// or a left click "pick:X:Y" (pixels from the bottom left).
    std::vector<std::string> script;
};

/// \brief Parses "WxH" (each 16 … 8192) into \p width and \p height; throws ConfigError naming
///        the --size flag otherwise.
void parse_image_size(const std::string& text, int& width, int& height);

/// \brief Opens the interactive window until the user quits, or writes options.png.
///        Picked values and status go to ctx's logger (info).
/// \throws InputError for a missing or unreadable input, ConfigError for a bad option (unknown
///         array, step out of range, no X display and no Xvfb), ExternalError when VTK or
///         OpenGL fail.
void view(const ViewOptions& options, const Context& ctx);

/// \brief The window's key and mouse bindings, one per line, for `--help` and the README.
const char* view_controls_help();

} // namespace penumbra::viewer
