// The Cornell box's camera view against an independent path-traced reference: Blender Cycles,
// 4 096 spp, rendered by scripts/reference/render_cycles.py (data/reference/cornell/README.md).
// Issue #27: the image was darker than both walls in lines along the wall junctions, where
// the vertices on the contact lines gathered their direct light from the line itself, and too
// bright in the dim corners at the junctions' ends, where leaves took their ancestors'
// reflected light by form factors that did not count what each far end sends.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "app/pipeline.h"
#include "common/test_util.h"
#include "core/image.h"
#include "core/scene_io.h"

namespace penumbra {
namespace {

// Luminance with the project's weights, in radiance units (W/(sr·m²) of white light).
double luminance(const Rgb& c) {
    return to_photometric(c) / k_luminous_efficacy_lm_per_w;
}

// Continuous pixel position of \p p, (0, 0) = the image's top-left corner: the pinhole of
// raytrace/src/render.cpp written out again.
struct Projector {
    explicit Projector(const Camera& c) : camera(c) {
        forward = normalize(c.look_at - c.eye);
        right = normalize(cross(forward, c.up));
        up = cross(right, forward);
        const double tan_half = std::tan(c.fov_deg * k_pi / 360.0);
        const double aspect = double(c.width) / double(c.height);
        half_w = c.fov_axis_x ? tan_half : tan_half * aspect;
        half_h = c.fov_axis_x ? tan_half / aspect : tan_half;
    }
    double x(const Vec3& p) const {
        const Vec3 d = p - camera.eye;
        return (dot(d, right) / (dot(d, forward) * half_w) + 1) / 2 * camera.width;
    }
    double y(const Vec3& p) const {
        const Vec3 d = p - camera.eye;
        return (1 - dot(d, up) / (dot(d, forward) * half_h)) / 2 * camera.height;
    }
    Camera camera;
    Vec3 forward, right, up;
    double half_w = 0, half_h = 0;
};

struct Pixel {
    int x, y;
};

// A 5-pixel-wide band centred on the image of the edge a–b, from the row below its upper end's
// to the row above its lower end's (off the floor and ceiling junctions).
std::vector<Pixel> band(const Projector& camera, const Vec3& a, const Vec3& b) {
    const double xa = camera.x(a), ya = camera.y(a), xb = camera.x(b), yb = camera.y(b);
    std::vector<Pixel> pixels;
    const int first = int(std::ceil(std::min(ya, yb))) + 1;
    const int last = int(std::floor(std::max(ya, yb))) - 2;
    for (int row = first; row <= last; ++row) {
        const double centre = xa + (row + 0.5 - ya) / (yb - ya) * (xb - xa);
        for (int dx = -2; dx <= 2; ++dx)
            pixels.push_back({int(std::floor(centre)) + dx, row});
    }
    return pixels;
}

struct BandError {
    double relative = 0;   ///< mean |L − L_ref| / L_ref
    double ref_noise = 0;  ///< mean standard error of L_ref / L_ref
    std::size_t count = 0; ///< pixels used
};

BandError band_error(const std::vector<Pixel>& pixels, const Image& image, const Image& ref,
                     const Image& ref_stderr) {
    BandError e;
    for (const Pixel& p : pixels) {
        const double l_ref = luminance(ref.at(p.x, p.y));
        if (l_ref < 1e-3)
            continue;
        e.relative += std::abs(luminance(image.at(p.x, p.y)) - l_ref) / l_ref;
        e.ref_noise += luminance(ref_stderr.at(p.x, p.y)) / l_ref;
        ++e.count;
    }
    e.relative /= double(e.count);
    e.ref_noise /= double(e.count);
    return e;
}

// RGB root-mean-square error over the pixels that do not show the light.
double rmse_without_light(const Image& image, const Image& ref, double light_luminance) {
    double sum = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < ref.pixels.size(); ++i) {
        if (luminance(ref.pixels[i]) > 0.9 * light_luminance)
            continue;
        const Rgb d = image.pixels[i] - ref.pixels[i];
        sum += double(d.r) * d.r + double(d.g) * d.g + double(d.b) * d.b;
        count += 3;
    }
    return std::sqrt(sum / double(count));
}

const Polygon& polygon_named(const Scene& scene, const std::string& name) {
    const auto it = std::find_if(scene.polygons.begin(), scene.polygons.end(),
                                 [&](const Polygon& p) { return p.name == name; });
    if (it == scene.polygons.end())
        throw std::runtime_error("the Cornell box has no polygon '" + name + "'");
    return *it;
}

TEST(CornellReference, WallJunctionBandsMatchCycles) {
    Scene scene = load_scene(test::source_path("data/cornell/scene.json"));
    scene.camera->samples_per_pixel = 256; // anti-aliasing noise well below the tolerance
    const Image ref = read_exr(test::source_path("data/reference/cornell/cycles_4096spp.exr"));
    const Image ref_stderr =
        read_exr(test::source_path("data/reference/cornell/cycles_4096spp_stderr.exr"));
    ASSERT_EQ(ref.width, scene.camera->width);
    ASSERT_EQ(ref.height, scene.camera->height);

    app::BakeOptions options;
    options.keep_state = false;
    const app::BakeResult result = app::bake(scene, options, test::quiet_context());
    ASSERT_TRUE(result.render);
    const Image& image = *result.render;

    // The back wall's vertical edges (cornell.obj): 0–3 meets the red wall, 1–2 the green.
    const std::vector<Vec3>& back = polygon_named(scene, "back_wall").vertices;
    const Projector camera(*scene.camera);
    const BandError red = band_error(band(camera, back[0], back[3]), image, ref, ref_stderr);
    const BandError green = band_error(band(camera, back[1], back[2]), image, ref, ref_stderr);
    const double light =
        luminance(scene.materials[polygon_named(scene, "light").material].emission);
    std::printf("junction bands: red %.2f %% (%zu px), green %.2f %% (%zu px); the reference's "
                "own noise there %.2f %%, %.2f %%; image RMSE without the light %.5f\n",
                100 * red.relative, red.count, 100 * green.relative, green.count,
                100 * red.ref_noise, 100 * green.ref_noise, rmse_without_light(image, ref, light));
    EXPECT_GT(red.count, 500u);
    EXPECT_GT(green.count, 500u);
    // Issue #27 asks for <= 2.5 %. Gathering the junction vertices' direct light inside their
    // elements took the bands from 9.78 % (red) and 9.13 % (green) to 2.72 % and 3.28 %;
    // weighing the leaves' reflected light by what each far end sends (hierarchy/
    // leaf_weights.h) mended the dim corners at the bands' ends (ceiling, and the tall block's
    // shadow by the floor: 5-60 % too bright) and took them to 2.04 % and 1.50 %.
    constexpr double k_issue_bound = 0.025;
    EXPECT_LE(red.relative, k_issue_bound);
    EXPECT_LE(green.relative, k_issue_bound);
}

} // namespace
} // namespace penumbra
