// Camera view of a radiosity solution. A pinhole camera traces one ray per stratified sample;
// the radiance of a hit is L = B/π with B interpolated linearly from the vertex radiosity of
// the element hit (the side facing the camera). Samples are averaged with a box filter.
// Each pixel draws from its own content-named stream (pbrt-v4's StartPixelSample pattern:
// advance by sample index × 2^16), and each pixel is written only by the task that owns its
// row, so the image is bitwise identical for any thread count or schedule.

#include "raytrace/raytrace.h"

#include "core/error.h"
#include "core/parallel.h"
#include "core/rng.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra::raytrace {

namespace {

/// Camera frame with the right and up axes scaled to the half extents of the image plane at
/// distance 1 from the eye.
struct PinholeCamera {
    Vec3 eye, forward, right, up;
    int width = 0, height = 0;

    /// Unit direction through the continuous pixel position (px, py), (0, 0) = top-left.
    Vec3f direction(double px, double py) const {
        double sx = 2.0 * px / width - 1.0;
        double sy = 1.0 - 2.0 * py / height;
        return Vec3f(normalize(forward + right * sx + up * sy));
    }
};

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

/// Smallest n with n² ≥ samples.
int strata_per_axis(int samples) {
    int n = 1;
    while (std::int64_t(n) * n < samples)
        ++n;
    return n;
}

struct PixelRenderer {
    const EmbreeScene& scene;
    const std::vector<Rgb>& vertex_radiosity;
    PinholeCamera camera;
    int strata = 1;
    std::uint64_t seed = 0;

    /// Radiosity B seen along the ray; black for misses and backs of one-sided surfaces.
    Rgb radiosity_along(const Vec3f& dir) const {
        auto hit =
            scene.intersect(Vec3f(camera.eye), dir, 0.0f, std::numeric_limits<float>::infinity());
        if (hit.element < 0)
            return {};
        const auto& t = scene.mesh().triangles[std::uint32_t(hit.element)];
        const Rgb& b0 = vertex_radiosity[t[0]];
        // Written as offsets from vertex 0 so that a constant field is reproduced exactly.
        return b0 + (vertex_radiosity[t[1]] - b0) * hit.u + (vertex_radiosity[t[2]] - b0) * hit.v;
    }

    Rgb pixel(int x, int y) const {
        const Pcg32 stream = Pcg32::for_stream(RngPurpose::pixel_sample, std::uint64_t(x),
                                               std::uint64_t(y), 0, seed);
        RgbD sum;
        for (int sy = 0; sy < strata; ++sy) {
            for (int sx = 0; sx < strata; ++sx) {
                Pcg32 rng = stream;
                rng.advance(std::int64_t(sy * strata + sx) << 16);
                double jx = (sx + double(rng.next_float())) / strata;
                double jy = (sy + double(rng.next_float())) / strata;
                sum += RgbD(radiosity_along(camera.direction(x + jx, y + jy)));
            }
        }
        // Float samples summed in double lose nothing (below 2^29 samples), so a constant B
        // gives exactly B/π.
        const double count = double(strata) * double(strata);
        return {float(sum.r / count * k_inv_pi), float(sum.g / count * k_inv_pi),
                float(sum.b / count * k_inv_pi)};
    }
};

} // namespace

Image render_solution(const EmbreeScene& scene, const Solution& solution, const Camera& camera,
                      const Context& ctx) {
    if (solution.vertex_radiosity.size() != scene.mesh().vertex_count())
        throw InternalError(fmt::format("render_solution: {} vertex radiosities for {} vertices",
                                        solution.vertex_radiosity.size(),
                                        scene.mesh().vertex_count()));
    const PixelRenderer renderer{scene, solution.vertex_radiosity, make_camera(camera),
                                 strata_per_axis(camera.samples_per_pixel), ctx.seed};
    Image image(camera.width, camera.height);
    ProgressStage stage(ctx, "render");
    const std::uint64_t rays_before = scene.rays_traced();

    run_in_arena(ctx, [&] {
        // Row blocks run one after another so that progress is reported from this thread only.
        const int rows_per_block = std::max(8, 4 * thread_count(ctx));
        for (int y0 = 0; y0 < image.height; y0 += rows_per_block) {
            const int y1 = std::min(image.height, y0 + rows_per_block);
            parallel_for(blocked_range<int>(y0, y1, 1), [&](const blocked_range<int>& rows) {
                for (int y = rows.begin(); y != rows.end(); ++y)
                    for (int x = 0; x < image.width; ++x)
                        image.at(x, y) = renderer.pixel(x, y);
            });
            stage.update(double(y1) / image.height);
        }
    });
    ctx.debug("render: {}x{} pixels, {} samples each, {} rays", image.width, image.height,
              renderer.strata * renderer.strata, scene.rays_traced() - rays_before);
    return image;
}

} // namespace penumbra::raytrace
