// Camera view of a radiosity solution. A pinhole camera traces one ray per stratified sample;
// the radiance of a hit is L = B/π with B interpolated linearly from the vertex radiosity of
// the element hit (the side facing the camera). Samples are averaged with a box filter.
// Each pixel draws from its own content-named stream (pbrt-v4's StartPixelSample pattern:
// advance by sample index × 2^16), and each pixel is written only by the task that owns its
// row, so the image is bitwise identical for any thread count or schedule.

#include "raytrace/raytrace.h"

#include "camera.h"

#include "core/error.h"
#include "core/parallel.h"
#include "core/rng.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra::raytrace {

namespace {

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
