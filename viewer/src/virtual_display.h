#pragma once
// A private X server (Xvfb) for machines without a display: Debian's VTK renders only
// through X (no EGL or OSMesa build), so `penumbra view` and its tests start one themselves.

#include <sys/types.h>

#include <optional>
#include <string>

namespace penumbra::viewer {

/// \brief Starts `Xvfb -displayfd` (Xvfb picks a free display number and reports it) and sets
///        DISPLAY for this process; the destructor stops the server and restores DISPLAY.
///        The server also dies with this process (PR_SET_PDEATHSIG), so a crash leaves nothing
///        running. Move-only in spirit: neither copyable nor movable.
class VirtualDisplay {
public:
    /// \brief Starts a server whose screen is at least \p width × \p height (24-bit).
    /// \throws ConfigError if Xvfb is not installed, ExternalError if it fails to start.
    VirtualDisplay(int width, int height);
    ~VirtualDisplay();
    VirtualDisplay(const VirtualDisplay&) = delete;
    VirtualDisplay& operator=(const VirtualDisplay&) = delete;

    const std::string& display() const { return display_; }

private:
    pid_t pid_ = -1;
    std::string display_;
    std::optional<std::string> previous_display_;
};

/// \brief True if DISPLAY is set and not empty.
bool has_display();

} // namespace penumbra::viewer
