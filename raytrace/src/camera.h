#pragma once
// The camera model both renderers share: a pinhole frame, and a thin lens for depth of field
// (the final gather). Internal to raytrace/.

#include "core/scene.h"
#include "core/vec.h"

#include <cmath>

namespace penumbra::raytrace {

/// Camera frame with the right and up axes scaled to the half extents of the image plane at
/// distance 1 from the eye.
struct PinholeCamera {
    Vec3 eye, forward, right, up;
    int width = 0, height = 0;

    /// Direction (not unit) through the continuous pixel position (px, py), (0, 0) = top-left;
    /// its component along forward is 1.
    Vec3 image_plane(double px, double py) const {
        const double sx = 2.0 * px / width - 1.0;
        const double sy = 1.0 - 2.0 * py / height;
        return forward + right * sx + up * sy;
    }
    /// Unit direction through the continuous pixel position (px, py).
    Vec3f direction(double px, double py) const { return Vec3f(normalize(image_plane(px, py))); }
};

/// \throws ConfigError for an image size, field of view or frame that makes no camera.
PinholeCamera make_camera(const Camera& c);

/// Smallest n with n² ≥ samples.
int strata_per_axis(int samples);

/// A ray leaving the camera.
struct CameraRay {
    Vec3 origin, direction; ///< direction unit
};

/// A thin lens (pbrt's PerspectiveCamera): rays through a disc of radius aperture around the
/// eye, in the plane perpendicular to the view axis, converge on the plane in focus.
struct ThinLensCamera {
    PinholeCamera pinhole;
    double aperture = 0; ///< lens radius, metres; 0 = pinhole
    double focus = 1;    ///< distance of the plane in focus along the view axis, metres

    /// The ray through pixel position (px, py) and the lens point of (lu, lv) ∈ [0, 1)².
    CameraRay ray(double px, double py, double lu, double lv) const {
        const Vec3 through = pinhole.image_plane(px, py);
        if (aperture <= 0)
            return {pinhole.eye, normalize(through)};
        // Uniform on the disc (polar map: stratification need not survive the warp here).
        const double r = aperture * std::sqrt(lu), phi = 2.0 * k_pi * lv;
        const Vec3 lens = normalize(pinhole.right) * (r * std::cos(phi)) +
                          normalize(pinhole.up) * (r * std::sin(phi));
        const Vec3 in_focus = pinhole.eye + through * focus;
        return {pinhole.eye + lens, normalize(in_focus - (pinhole.eye + lens))};
    }
};

/// \throws ConfigError as make_camera().
ThinLensCamera make_thin_lens(const Camera& c);

} // namespace penumbra::raytrace
