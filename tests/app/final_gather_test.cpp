// The final gather (issue #28) against analytic values and against itself in its other mode:
// the white furnace, thin-lens blur circles, the final gather against the pure path tracer on
// the Cornell box per tile, thread-count independence, and bad input.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "app/pipeline.h"
#include "common/bake_util.h"
#include "common/reference_tiles.h"
#include "common/test_util.h"
#include "core/error.h"
#include "core/image.h"
#include "core/scene_io.h"
#include "raytrace/raytrace.h"

namespace penumbra {
namespace {

using raytrace::GatherMode;
using raytrace::RenderOptions;

Image render(const app::BakeResult& baked, const Scene& scene, const RenderOptions& options,
             const Context& ctx) {
    const raytrace::EmbreeScene rt(baked.mesh);
    return raytrace::render_final_gather(rt, scene, baked.solution, *scene.camera, options, ctx);
}

// ---- White furnace: a closed room emitting E (radiosity) with reflectance ρ everywhere ----

Scene furnace(double rho, double exitance) {
    Scene scene;
    const auto m =
        test::add_material(scene, "furnace", Rgb(float(rho)), Rgb(float(exitance / k_pi)));
    test::add_room(scene, {0, 0, 0}, {1, 1.5, 0.8}, m);
    scene.mesher.max_edge_length = 0.1;
    scene.solver.method = SolverMethod::shooting; // a furnace converges slowly otherwise
    scene.solver.residual = 1e-5;
    scene.render.max_bounces = 64; // ρ^65 of the answer left out: below 1e-19
    // A corner: three walls, two edges.
    scene.camera = test::square_camera({0.3, 0.4, 0.3}, {0.9, 1.2, 0.5}, {0, 0, 1}, 70, 24);
    return scene;
}

/// Every pixel reads L = E / (π (1 − ρ)): the image mean within 4 of its standard errors (the
/// pixels' own scatter, as all share that expectation), and the mean of every 4 × 4 tile within
/// 6 of the standard errors its own pixels' scatter gives: the pixels by the corner scatter
/// more than the rest (their gather paths continue, and a pixel's samples share the gather
/// strata elsewhere), so each region is judged by its own noise.
void expect_furnace(const Image& image, double expected) {
    const test::ImageMoments m = test::green_moments(image);
    const double standard_error = m.sd / std::sqrt(double(image.pixels.size()));
    EXPECT_NEAR(m.mean, expected, 4 * standard_error + 1e-6 * expected)
        << "sd " << m.sd << " over " << image.pixels.size() << " pixels";
    constexpr int tile = 4;
    for (int ty = 0; ty + tile <= image.height; ty += tile)
        for (int tx = 0; tx + tile <= image.width; tx += tile) {
            double sum = 0, sum2 = 0;
            for (int y = ty; y < ty + tile; ++y)
                for (int x = tx; x < tx + tile; ++x) {
                    const double g = image.at(x, y).g;
                    sum += g;
                    sum2 += g * g;
                }
            const double n = tile * tile, mean = sum / n;
            const double sd = std::sqrt(std::max(0.0, (sum2 - n * mean * mean) / (n - 1)));
            EXPECT_NEAR(mean, expected, 6 * sd / std::sqrt(n) + 1e-6 * expected)
                << "tile at (" << tx << ", " << ty << ")";
        }
    EXPECT_LT(m.sd, 0.2 * expected); // the estimator is not degenerate
}

TEST(FinalGatherFurnace, PathTracerReadsTheGeometricSeries) {
    const double rho = 0.5, exitance = 1.0;
    const Scene scene = furnace(rho, exitance);
    const app::BakeResult baked = test::bake(scene);
    RenderOptions options;
    options.spp = 16;
    options.gather = GatherMode::none;
    expect_furnace(render(baked, scene, options, test::quiet_context()),
                   exitance / (k_pi * (1 - rho)));
}

TEST(FinalGatherFurnace, FinalGatherReadsTheGeometricSeries) {
    // The solution holds B = E / (1 − ρ) within the solver's residual (1e-5); the gather adds
    // emitted, direct and (B − E)/π one bounce away, which sum to the same.
    const double rho = 0.7, exitance = 2.0;
    const Scene scene = furnace(rho, exitance);
    const app::BakeResult baked = test::bake(scene);
    for (int depth : {0, 1}) {
        RenderOptions options;
        options.spp = 16;
        options.gather_depth = depth;
        expect_furnace(render(baked, scene, options, test::quiet_context()),
                       exitance / (k_pi * (1 - rho)));
    }
}

// ---- Thin lens: a small emitting disc at distance d, the lens focused at f ----

struct LensSetup {
    double distance = 4;    ///< d, metres from the eye along the axis
    double focus = 2;       ///< f
    double aperture = 0.09; ///< A, lens radius
    double disc_radius = 0.015;
};

Scene disc_scene(const LensSetup& s) {
    Scene scene;
    const auto m = test::add_material(scene, "disc", Rgb(0.0f), Rgb(1.0f), false);
    Polygon disc;
    disc.material = m;
    disc.name = "disc";
    constexpr int k_sides = 128;
    for (int k = 0; k < k_sides; ++k) {
        // Clockwise seen from +z: the front faces the eye at the origin.
        const double phi = -2 * k_pi * k / k_sides;
        disc.vertices.push_back(
            {s.disc_radius * std::cos(phi), s.disc_radius * std::sin(phi), s.distance});
    }
    scene.polygons.push_back(disc);
    Camera camera = test::square_camera({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, 20, 96);
    camera.aperture_radius_m = s.aperture;
    camera.focus_distance_m = s.focus;
    scene.camera = camera;
    return scene;
}

/// Second moment of the image's luminance about its centroid, pixels², less the pixel's own
/// footprint (a box of one pixel adds 1/12 per axis).
double second_moment_px2(const Image& image) {
    double sum = 0, sx = 0, sy = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const double w = test::tile_luminance(image.at(x, y));
            sum += w;
            sx += w * (x + 0.5);
            sy += w * (y + 0.5);
        }
    const double cx = sx / sum, cy = sy / sum;
    double m = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const double dx = x + 0.5 - cx, dy = y + 0.5 - cy;
            m += test::tile_luminance(image.at(x, y)) * (dx * dx + dy * dy);
        }
    return m / sum - 2.0 / 12.0;
}

/// Pixels per unit of the image plane at distance 1 (tan of the angle off axis).
double pixels_per_tan(const Camera& c) {
    return c.width / (2 * std::tan(c.fov_deg * k_pi / 360));
}

TEST(FinalGatherThinLens, DiscOutOfFocusBlursToTheCircleOfConfusion) {
    const LensSetup s;
    const Scene scene = disc_scene(s);
    const app::BakeResult baked = test::bake(scene);
    RenderOptions options;
    options.spp = 256;
    options.gather = GatherMode::none;
    const Image image = render(baked, scene, options, test::quiet_context());
    // A point at d images on the plane in focus as a uniform disc of radius A |d − f| / d;
    // seen from the eye (÷ f) in pixels. Uniform discs have second moment R²/2, and the
    // disc's own image (radius r/d) convolves with it: the moments add.
    const double scale = pixels_per_tan(*scene.camera);
    const double own = s.disc_radius / s.distance * scale;
    const double expected =
        s.aperture * std::abs(s.distance - s.focus) / s.distance / s.focus * scale;
    const double measured = std::sqrt(2 * second_moment_px2(image) - own * own);
    EXPECT_NEAR(measured, expected, 0.02 * expected) << "blur radius, pixels";
    EXPECT_GT(expected, 5.0); // a blur well above the pixel
}

TEST(FinalGatherThinLens, DiscAtTheFocusDistanceStaysSharp) {
    LensSetup s;
    s.focus = s.distance;
    s.disc_radius = 0.06; // an image of 4 pixels' radius: pixel sampling adds little
    const Scene lens = disc_scene(s);
    s.aperture = 0;
    const Scene pinhole = disc_scene(s);
    RenderOptions options;
    options.spp = 64;
    options.gather = GatherMode::none;
    const double with_lens =
        second_moment_px2(render(test::bake(lens), lens, options, test::quiet_context()));
    const double without =
        second_moment_px2(render(test::bake(pinhole), pinhole, options, test::quiet_context()));
    // The disc's own image, radius r/d: second moment r²/(2d²) in pixels².
    const double own = s.disc_radius / s.distance * pixels_per_tan(*lens.camera);
    EXPECT_NEAR(without, own * own / 2, 0.05 * own * own / 2);
    EXPECT_NEAR(with_lens, without, 0.02 * without);
}

// ---- The final gather against the pure path tracer on the Cornell box ----

TEST(FinalGatherCornell, AgreesWithThePathTracerPerTile) {
    Scene scene = test::cornell_box(0.05);
    scene.camera->width = scene.camera->height = 64;
    const app::BakeResult baked = test::bake(scene);
    const raytrace::EmbreeScene rt(baked.mesh);
    constexpr int k_renders = 8;
    std::vector<Image> final_renders, path_renders;
    for (int k = 0; k < k_renders; ++k) {
        Context ctx = test::quiet_context();
        ctx.seed = std::uint64_t(k + 1);
        RenderOptions options;
        options.spp = 4; // each splits into 4 light samples and 16 gather rays (the defaults)
        final_renders.push_back(
            raytrace::render_final_gather(rt, scene, baked.solution, *scene.camera, options, ctx));
        options.gather = GatherMode::none;
        options.spp = 4; // the path tracer is the noisier
        path_renders.push_back(
            raytrace::render_final_gather(rt, scene, baked.solution, *scene.camera, options, ctx));
    }
    const test::TileStats fg = test::tile_stats(final_renders), pt = test::tile_stats(path_renders);
    int failures = 0;
    for (std::size_t t = 0; t < fg.mean.size(); ++t) {
        const double se = std::hypot(fg.standard_error[t], pt.standard_error[t]);
        const double allowed = 3 * se + 0.005 * pt.mean[t];
        if (std::abs(fg.mean[t] - pt.mean[t]) > allowed) {
            ++failures;
            ADD_FAILURE() << "tile " << t << ": final " << fg.mean[t] << ", path traced "
                          << pt.mean[t] << " ± " << se;
        }
    }
    EXPECT_EQ(failures, 0);
}

// ---- Against the Cycles reference (data/reference/cornell/README.md) ----

/// Per 16 × 16 tile of the Cornell box at 256², \p mode's mean luminance (from eight renders
/// of independent seeds) against Cycles' 4 096-spp image: |Δ| ≤ 3 standard errors (both
/// images' noise) + 0.5 % (issue #28). Returns the tiles outside it.
int tiles_off_cycles(GatherMode mode, int spp) {
    const Scene scene = test::cornell_box(0.1);
    const app::BakeResult baked = test::bake(scene);
    const raytrace::EmbreeScene rt(baked.mesh);
    std::vector<Image> renders;
    for (int k = 0; k < 8; ++k) {
        Context ctx = test::quiet_context();
        ctx.seed = std::uint64_t(k + 11);
        RenderOptions options;
        options.spp = spp;
        options.gather = mode;
        renders.push_back(
            raytrace::render_final_gather(rt, scene, baked.solution, *scene.camera, options, ctx));
    }
    return test::tiles_off_reference(renders, "data/reference/cornell/cycles_4096spp.exr",
                                     "data/reference/cornell/cycles_4096spp_stderr.exr",
                                     std::string(enum_name(mode)));
}

/// Our standard errors come from eight renders: |Δ|/SE follows Student's t with 7 degrees of
/// freedom, which leaves 2 % of the tiles beyond 3 by chance alone (5 of 256) even when the
/// renderers agree. Measured: the path tracer has none outside; the final gather one, at the
/// tall block's base by the floor (+3 %, 5 SE), the solution's error one bounce away.
constexpr int k_tiles_off_by_chance = 5;

TEST(FinalGatherCornell, TilesAgreeWithCycles) {
    EXPECT_LE(tiles_off_cycles(GatherMode::final_gather, 4), k_tiles_off_by_chance);
}

TEST(FinalGatherCornell, PathTracerTilesAgreeWithCycles) {
    EXPECT_LE(tiles_off_cycles(GatherMode::none, 1), k_tiles_off_by_chance);
}

// ---- Results do not depend on the thread count ----

TEST(FinalGather, BitwiseIdenticalForOneTwoAndFourThreads) {
    Scene scene = test::cornell_box(0.1);
    scene.camera->width = scene.camera->height = 32;
    scene.camera->aperture_radius_m = 0.01;
    const app::BakeResult baked = test::bake(scene);
    for (GatherMode mode : {GatherMode::final_gather, GatherMode::none}) {
        RenderOptions options;
        options.spp = 4;
        options.gather = mode;
        const Image one = render(baked, scene, options, test::quiet_context(1));
        for (int threads : {2, 4}) {
            const Image other = render(baked, scene, options, test::quiet_context(threads));
            ASSERT_EQ(one.pixels.size(), other.pixels.size());
            EXPECT_TRUE(std::equal(one.pixels.begin(), one.pixels.end(), other.pixels.begin()))
                << enum_name(mode) << ", " << threads << " threads";
        }
    }
}

// ---- Bad input ----

TEST(FinalGather, SppBelowOneIsAOneLineError) {
    Scene scene = test::cornell_box(0.2);
    scene.camera->width = scene.camera->height = 8;
    const app::BakeResult baked = test::bake(scene);
    RenderOptions options;
    options.spp = 0;
    try {
        render(baked, scene, options, test::quiet_context());
        FAIL() << "no error";
    } catch (const ConfigError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        EXPECT_NE(message.find("spp"), std::string::npos) << message;
    }
}

TEST(RenderCommand, BadFlagsAreOneLineErrors) {
    const std::string scene = test::source_path("data/cornell/scene.json");
    const std::string out = test::temp_dir("render_bad_flags");
    for (const std::string flags : {"--gather photons", "--spp 0", "--gather-depth -1"}) {
        const test::RunResult r = test::run_cli("render " + scene + " -o " + out + " " + flags);
        EXPECT_EQ(r.exit_code, 3) << flags << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << flags << ": " << r.err;
    }
}

// ---- Glazing: what the camera sees through a pane ----

/// A camera under a wide pane of clear glass looks up at a uniform sky of radiance L: every
/// pixel reads T(θ) L, T the pane's transmittance at the pixel ray's incidence θ (the mean of
/// its channels, as shadow rays count panes), within 1 % (T varies by less than that over a
/// pixel of this 40° view); without the pane, L.
TEST(FinalGatherGlazing, CameraSeesTheSkyThroughAPaneAttenuated) {
    const double radiance = 10.0;
    Scene scene;
    const auto black = test::add_material(scene, "black", Rgb(0), {}, false);
    const auto glass = test::add_clear_glass(scene);
    test::add_rect(scene, "floor", black, {-1, -1, 0}, {2, 0, 0}, {0, 2, 0});
    test::add_rect(scene, "pane", glass, {-10, -10, 0.5}, {20, 0, 0}, {0, 20, 0});
    scene.sky = Sky{};
    scene.sky->model = UniformSky{};
    scene.sky->zenith_radiance = radiance;
    scene.mesher.max_edge_length = 1.0;
    scene.camera = test::square_camera({0, 0, 0.2}, {0, 0, 1}, {0, 1, 0}, 40, 8);
    const ThinGlass pane = *glazing_of(scene.materials[glass]);
    const app::BakeResult baked = test::bake(scene);
    RenderOptions options;
    options.spp = 4;
    const Image image = render(baked, scene, options, test::quiet_context());
    const double half_width = std::tan(20.0 * k_pi / 180.0);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const double px = ((x + 0.5) / image.width * 2 - 1) * half_width;
            const double py = ((y + 0.5) / image.height * 2 - 1) * half_width;
            const double cos_theta = 1.0 / std::sqrt(1 + px * px + py * py);
            const Rgb t = pane.transmittance(cos_theta);
            const double expected = radiance * (t.r + t.g + t.b) / 3.0;
            EXPECT_NEAR(image.at(x, y).g, expected, 0.01 * expected) << x << ", " << y;
        }
}

// ---- Named cameras and re-rendering from an earlier bake's solution ----

/// The bundled Cornell box (its geometry copied beside it) at 32², with a second camera named
/// "corner"; returns the scene file's path.
std::string cornell_with_cameras(const std::string& dir) {
    namespace fs = std::filesystem;
    for (const char* file : {"cornell.obj", "cornell.mtl"})
        fs::copy_file(test::source_path(std::string("data/cornell/") + file), fs::path(dir) / file,
                      fs::copy_options::overwrite_existing);
    const std::string path = (fs::path(dir) / "scene.json").string();
    std::ofstream(path) << R"({
  "units": "mm", "up": [0, 1, 0], "geometry": "cornell.obj",
  "materials": {"light": {"emission_two_sided": false}},
  "camera": {"eye": [278, 273, -800], "look_at": [278, 273, 0], "fov_deg": 39.3},
  "cameras": [{"name": "corner", "eye": [500, 450, 50], "look_at": [100, 100, 500],
               "fov_deg": 60}],
  "image": {"width": 32, "height": 32, "spp": 4},
  "mesher": {"max_edge_length": 250, "discontinuity": {"enabled": false}},
  "solver": {"residual": 1e-3, "epsilon": 0.05}
})";
    return path;
}

TEST(RenderCommand, NamedCameraRendersItsOwnView) {
    const std::string dir = test::temp_dir("render_cameras");
    const std::string scene = cornell_with_cameras(dir);
    ASSERT_EQ(test::run_cli("render " + scene + " -o " + dir + "/main -q").exit_code, 0);
    ASSERT_EQ(
        test::run_cli("render " + scene + " --camera corner -o " + dir + "/corner -q").exit_code,
        0);
    const Image main = read_exr(dir + "/main/render.exr");
    const Image corner = read_exr(dir + "/corner/render.exr");
    ASSERT_EQ(main.pixels.size(), corner.pixels.size());
    EXPECT_FALSE(std::equal(main.pixels.begin(), main.pixels.end(), corner.pixels.begin()));
    // The corner camera looks down at the floor and the blocks: no pixel sees the light's
    // face, which is the brightest thing in the main view.
    const auto brightest = [](const Image& image) {
        double m = 0;
        for (const Rgb& p : image.pixels)
            m = std::max(m, test::tile_luminance(p));
        return m;
    };
    EXPECT_LT(brightest(corner), 0.5 * brightest(main));
}

TEST(RenderCommand, UnknownCameraIsAOneLineError) {
    const std::string dir = test::temp_dir("render_camera_unknown");
    const std::string scene = cornell_with_cameras(dir);
    for (const std::string command : {"render", "bake"}) {
        const test::RunResult r =
            test::run_cli(command + " " + scene + " --camera attic -o " + dir + "/out");
        EXPECT_EQ(r.exit_code, 2) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_NE(r.err.find("attic"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("corner"), std::string::npos) << r.err;
    }
}

double mean_luminance(const Image& image) {
    double sum = 0;
    for (const Rgb& p : image.pixels)
        sum += test::tile_luminance(p);
    return sum / double(image.pixels.size());
}

/// `render --gather none` is the pure path tracer: it reads no solution, so it solves none
/// (render.json times a mesh and a render stage, no solve), and still renders the scene.
TEST(RenderCommand, PathTracerModeDoesNotSolve) {
    const std::string dir = test::temp_dir("render_none");
    const std::string scene = cornell_with_cameras(dir);
    ASSERT_EQ(test::run_cli("render " + scene + " --gather none -q -o " + dir + "/none").exit_code,
              0);
    std::ifstream in(dir + "/none/render.json");
    const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(json.find("\"render\":"), std::string::npos) << json;
    EXPECT_NE(json.find("\"mesh\":"), std::string::npos) << json;
    EXPECT_EQ(json.find("\"solve\":"), std::string::npos) << json;
    EXPECT_NE(json.find("\"gather\": \"none\""), std::string::npos) << json;
    const Image image = read_exr(dir + "/none/render.exr");
    EXPECT_GT(mean_luminance(image), 0.0);
    // Nor reads a solution: one that is not there only draws a warning.
    const test::RunResult r =
        test::run_cli("render " + scene + " --gather none --spp 1 --solution " + dir +
                      "/missing -o " + dir + "/none_solution");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("--solution " + dir + "/missing is not read"), std::string::npos) << r.err;
}

/// `render --solution` re-solves from the bake's hierarchy and links (as `bake --reuse`): its
/// sweeps start from the saved radiosities, so the image matches the full run's to within the
/// solver's residual (1e-3 of the emitted power), and is bitwise the same for 1 and 2 threads.
TEST(RenderCommand, SolutionOfAnEarlierBakeRerendersTheFullRunsImage) {
    const std::string dir = test::temp_dir("render_solution");
    const std::string scene = cornell_with_cameras(dir);
    ASSERT_EQ(test::run_cli("bake " + scene + " --no-render -o " + dir + "/bake -q").exit_code, 0);
    const std::string flags = " --camera corner -q -o ";
    ASSERT_EQ(test::run_cli("render " + scene + flags + dir + "/full").exit_code, 0);
    std::vector<Image> again;
    for (const std::string threads : {"1", "2"}) {
        const std::string out = dir + "/again" + threads;
        const test::RunResult r = test::run_cli("render " + scene + " --solution " + dir +
                                                "/bake --threads " + threads + flags + out);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        again.push_back(read_exr(out + "/render.exr"));
    }
    ASSERT_EQ(again[0].pixels.size(), again[1].pixels.size());
    EXPECT_TRUE(
        std::equal(again[0].pixels.begin(), again[0].pixels.end(), again[1].pixels.begin()));
    const double full = mean_luminance(read_exr(dir + "/full/render.exr"));
    EXPECT_NEAR(mean_luminance(again[0]), full, 2e-3 * full);
}

} // namespace
} // namespace penumbra
