// `penumbra view` when the build has no window (PENUMBRA_BUILD_VIEWER_WINDOW=OFF): writing
// VTK files still works, showing them does not.

#include "viewer/view.h"

#include "core/error.h"

#include <fmt/format.h>

#include <cstdio>

namespace penumbra::viewer {

void parse_image_size(const std::string& text, int& width, int& height) {
    char tail = 0;
    if (std::sscanf(text.c_str(), "%dx%d%c", &width, &height, &tail) != 2)
        throw ConfigError(fmt::format("--size '{}': expected WIDTHxHEIGHT, e.g. 800x600", text));
}

const char* view_controls_help() {
    return "(this build has no viewer window)\n";
}

void view(const ViewOptions&, const Context&) {
    throw ConfigError("penumbra was built without the viewer window "
                      "(-DPENUMBRA_BUILD_VIEWER_WINDOW=OFF); open the .vtu/.pvd files in "
                      "ParaView");
}

} // namespace penumbra::viewer
