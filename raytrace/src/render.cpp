// Camera view of a radiosity solution. A pinhole camera traces one ray per stratified sample;
// the radiance of a hit is L = B/π with B interpolated linearly from the vertex radiosity of
// the element hit (the side facing the camera). Samples are averaged with a box filter.
// Each pixel draws from its own content-named stream (pbrt-v4's StartPixelSample pattern:
// advance by sample index × 2^16), and each pixel is written only by the task that owns its
// row, so the image is bitwise identical for any thread count or schedule. render_hits shares
// the camera, sampling and rows, with the radiance of a hit given by its caller.

#include "raytrace/raytrace.h"

#include "camera.h"
#include "edge_refinement.h"

#include "core/error.h"
#include "core/parallel.h"
#include "core/rng.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace penumbra::raytrace {

namespace {

struct SampledPixel {
    RgbD mean;
    double range = 0; ///< the largest channel's max − min over the samples
};

// Averages along(direction) over a pixel's stratified samples. Each pixel draws from its own
// content-named stream.
template <typename Along> struct PixelSampler {
    PinholeCamera camera;
    int strata = 1;
    std::uint64_t seed = 0;
    Along along; ///< Rgb along(const Vec3f& unit_direction)

    RgbD mean(int x, int y) const {
        return mean_visiting(x, y, [](const Rgb&) {});
    }

    /// mean(), and the largest channel range of its samples.
    SampledPixel mean_and_range(int x, int y) const {
        constexpr float inf = std::numeric_limits<float>::infinity();
        Rgb low{inf, inf, inf}, high{-inf, -inf, -inf};
        const RgbD m = mean_visiting(x, y, [&](const Rgb& v) {
            for (int c = 0; c < 3; ++c) {
                low[c] = std::min(low[c], v[c]);
                high[c] = std::max(high[c], v[c]);
            }
        });
        return {m,
                std::max({double(high.r - low.r), double(high.g - low.g), double(high.b - low.b)})};
    }

    /// mean(), handing each sample's value to \p visit.
    template <typename Visit> RgbD mean_visiting(int x, int y, Visit&& visit) const {
        const Pcg32 stream = Pcg32::for_stream(RngPurpose::pixel_sample, std::uint64_t(x),
                                               std::uint64_t(y), 0, seed);
        RgbD sum;
        for (int sy = 0; sy < strata; ++sy) {
            for (int sx = 0; sx < strata; ++sx) {
                Pcg32 rng = stream;
                rng.advance(std::int64_t(sy * strata + sx) << 16);
                double jx = (sx + double(rng.next_float())) / strata;
                double jy = (sy + double(rng.next_float())) / strata;
                const Rgb v = along(camera.direction(x + jx, y + jy));
                visit(v);
                sum += RgbD(v);
            }
        }
        // Float samples summed in double lose nothing (below 2^29 samples), so a constant
        // value is reproduced exactly.
        const double count = double(strata) * double(strata);
        return {sum.r / count, sum.g / count, sum.b / count};
    }

    /// The mean of n² multi-jittered samples of pixel (x, y), from its own stream.
    RgbD multi_jittered_mean(int x, int y, int n) const {
        Pcg32 rng = Pcg32::for_stream(RngPurpose::pixel_sample, std::uint64_t(x), std::uint64_t(y),
                                      1, seed);
        RgbD sum;
        for (const Vec2& p : multi_jittered(n, rng))
            sum += RgbD(along(camera.direction(x + p.x, y + p.y)));
        const double count = double(n) * double(n);
        return {sum.r / count, sum.g / count, sum.b / count};
    }
};

template <typename Along>
PixelSampler<Along> make_sampler(const Camera& camera, const Context& ctx, Along along) {
    return {make_camera(camera), strata_per_axis(camera.samples_per_pixel), ctx.seed,
            std::move(along)};
}

// Fills \p image with pixel(x, y), rows in parallel; each pixel written by the task owning its
// row, so the image does not depend on the thread count or schedule.
template <typename Pixel>
void render_rows(Image& image, const Context& ctx, const char* stage_name, const Pixel& pixel) {
    ProgressStage stage(ctx, stage_name);
    run_in_arena(ctx, [&] {
        // Row blocks run one after another so that progress is reported from this thread only.
        const int rows_per_block = std::max(8, 4 * thread_count(ctx));
        for (int y0 = 0; y0 < image.height; y0 += rows_per_block) {
            const int y1 = std::min(image.height, y0 + rows_per_block);
            parallel_for(blocked_range<int>(y0, y1, 1), [&](const blocked_range<int>& rows) {
                for (int y = rows.begin(); y != rows.end(); ++y)
                    for (int x = 0; x < image.width; ++x)
                        image.at(x, y) = pixel(x, y);
            });
            stage.update(double(y1) / image.height);
        }
    });
}

} // namespace

Image render_solution(const EmbreeScene& scene, const Solution& solution, const Camera& camera,
                      const Context& ctx) {
    if (solution.vertex_radiosity.size() != scene.mesh().vertex_count())
        throw InternalError(fmt::format("render_solution: {} vertex radiosities for {} vertices",
                                        solution.vertex_radiosity.size(),
                                        scene.mesh().vertex_count()));
    const Vec3f eye(make_camera(camera).eye);
    const std::vector<Rgb>& vertex_radiosity = solution.vertex_radiosity;
    // Radiosity B seen along the ray; black for misses and backs of one-sided surfaces.
    const auto sampler = make_sampler(camera, ctx, [&](const Vec3f& dir) -> Rgb {
        auto hit = scene.intersect(eye, dir, 0.0f, std::numeric_limits<float>::infinity());
        if (hit.element < 0)
            return {};
        const auto& t = scene.mesh().triangles[std::uint32_t(hit.element)];
        const Rgb& b0 = vertex_radiosity[t[0]];
        // Written as offsets from vertex 0 so that a constant field is reproduced exactly.
        return b0 + (vertex_radiosity[t[1]] - b0) * hit.u + (vertex_radiosity[t[2]] - b0) * hit.v;
    });
    Image image(camera.width, camera.height);
    const std::uint64_t rays_before = scene.rays_traced();
    render_rows(image, ctx, "render", [&](int x, int y) {
        const RgbD b = sampler.mean(x, y);
        return Rgb{float(b.r * k_inv_pi), float(b.g * k_inv_pi), float(b.b * k_inv_pi)};
    });
    ctx.debug("render: {}x{} pixels, {} samples each, {} rays", image.width, image.height,
              sampler.strata * sampler.strata, scene.rays_traced() - rays_before);
    return image;
}

Image render_hits(const EmbreeScene& scene, const Camera& camera, const HitShader& shade,
                  const Context& ctx) {
    return render_hits(scene, camera, shade, EdgeRefinement{}, ctx);
}

Image render_hits(const EmbreeScene& scene, const Camera& camera, const HitShader& shade,
                  const EdgeRefinement& refine, const Context& ctx) {
    const Vec3f eye(make_camera(camera).eye);
    const auto sampler = make_sampler(camera, ctx, [&](const Vec3f& dir) -> Rgb {
        return shade(scene.intersect(eye, dir, 0.0f, std::numeric_limits<float>::infinity()));
    });
    Image image(camera.width, camera.height);
    std::vector<double> range(image.pixels.size(), 0.0);
    render_rows(image, ctx, "preview", [&](int x, int y) {
        const SampledPixel first = sampler.mean_and_range(x, y);
        range[std::size_t(y) * std::size_t(image.width) + std::size_t(x)] = first.range;
        return Rgb{float(first.mean.r), float(first.mean.g), float(first.mean.b)};
    });
    if (!(refine.tolerance > 0))
        return image;
    const Image first = image;
    render_rows(image, ctx, "preview edges", [&](int x, int y) {
        const double around = largest_around(range, image.width, image.height, x, y);
        const int n = refined_strata(around, refine);
        if (n <= sampler.strata)
            return first.at(x, y);
        const RgbD m = sampler.multi_jittered_mean(x, y, n);
        return Rgb{float(m.r), float(m.g), float(m.b)};
    });
    return image;
}

} // namespace penumbra::raytrace
