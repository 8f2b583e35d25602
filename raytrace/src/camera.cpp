#include "camera.h"

#include "core/error.h"

#include <fmt/format.h>

#include <cstdint>

namespace penumbra::raytrace {

PinholeCamera make_camera(const Camera& c) {
    if (c.width <= 0 || c.height <= 0)
        throw ConfigError(
            fmt::format("camera: image size {}x{} must be positive", c.width, c.height));
    if (!(c.fov_deg > 0 && c.fov_deg < 180))
        throw ConfigError(fmt::format("camera: fov {} degrees must lie in (0, 180)", c.fov_deg));
    if (c.samples_per_pixel < 1)
        throw ConfigError(
            fmt::format("camera: samples_per_pixel {} must be at least 1", c.samples_per_pixel));
    const Vec3 forward = normalize(c.look_at - c.eye);
    const Vec3 right = normalize(cross(forward, c.up));
    if (!(length(forward) > 0) || !(length(right) > 0) || !is_finite(right))
        throw ConfigError("camera: eye, look_at and up must span a frame (eye differs from "
                          "look_at, up not parallel to the view direction)");
    const Vec3 up = cross(right, forward);

    const double tan_half = std::tan(c.fov_deg * k_pi / 360.0);
    const double aspect = double(c.width) / double(c.height);
    const double half_w = c.fov_axis_x ? tan_half : tan_half * aspect;
    const double half_h = c.fov_axis_x ? tan_half / aspect : tan_half;
    return {c.eye, forward, right * half_w, up * half_h, c.width, c.height};
}

int strata_per_axis(int samples) {
    int n = 1;
    while (std::int64_t(n) * n < samples)
        ++n;
    return n;
}

ThinLensCamera make_thin_lens(const Camera& c) {
    ThinLensCamera lens{make_camera(c), c.aperture_radius_m,
                        c.focus_distance_m.value_or(length(c.look_at - c.eye))};
    if (!(lens.aperture >= 0) || !std::isfinite(lens.aperture))
        throw ConfigError(fmt::format("camera: aperture radius {} m must be >= 0", lens.aperture));
    if (!(lens.focus > 0) || !std::isfinite(lens.focus))
        throw ConfigError(fmt::format("camera: focus distance {} m must be > 0", lens.focus));
    return lens;
}

} // namespace penumbra::raytrace
