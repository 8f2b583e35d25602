// The files of `penumbra lightmap`: per atlas lightmap_N.exr (linear irradiance),
// lightmap_N.png (MOZ_lightmap's lux / intensity, lightmap_gltf.h) and lightmap_N_preview.png
// (tone-mapped for a look); scene.gltf + scene.bin; preview.exr/.png (the camera's view from
// the atlases); and lightmaps.json, the manifest an engine's importer reads.

#include <filesystem>
#include <set>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/lightmap.h"
#include "core/error.h"
#include "core/files.h"
#include "lightmap_gltf.h"
#include "texel_light.h"

namespace penumbra::app {

namespace {

namespace fs = std::filesystem;

std::string atlas_file(std::size_t atlas, const char* extension) {
    return fmt::format("lightmap_{}.{}", atlas, extension);
}

std::string atlas_preview_file(std::size_t atlas) {
    return fmt::format("lightmap_{}_preview.png", atlas);
}

std::vector<std::string> atlas_files(std::size_t atlas) {
    return {atlas_file(atlas, "exr"), atlas_file(atlas, "png"), atlas_preview_file(atlas)};
}

// The exposure of preview.png: the camera's, else automatic (as render.png's).
double camera_exposure(const Scene& scene, const Image& preview) {
    return scene.camera && scene.camera->exposure > 0 ? scene.camera->exposure
                                                      : auto_exposure(preview);
}

// The directional atlases' suffixes, in lightmap/sh.h's order Y00, Y1−1, Y10, Y11.
constexpr const char* k_sh_suffixes[] = {"L00", "L1m1", "L10", "L11"};

std::string directional_file(std::size_t atlas, std::size_t k) {
    return fmt::format("lightmap_{}_{}.exr", atlas, k_sh_suffixes[k]);
}

const char* kind_name(lightmap::ChartKind kind) {
    switch (kind) {
    case lightmap::ChartKind::planar:
        return "planar";
    case lightmap::ChartKind::curved:
        return "curved";
    case lightmap::ChartKind::imported:
        return "imported";
    }
    return "";
}

// One exposure for every atlas (Reinhard's key over all their texels), so that the previews
// of one bake compare with each other.
double preview_exposure(const std::vector<Image>& atlases) {
    Image all;
    all.width = atlases.empty() ? 0 : atlases.front().width;
    for (const Image& a : atlases) {
        all.pixels.insert(all.pixels.end(), a.pixels.begin(), a.pixels.end());
        all.height += a.height;
    }
    return auto_exposure(all);
}

nlohmann::json chart_json(const lightmap::Chart& chart, const lightmap::ChartPlacement& p) {
    std::set<std::uint32_t> polygons;
    for (const lightmap::ChartTriangle& t : chart.triangles)
        polygons.insert(t.polygon);
    return {{"object", chart.object},
            {"kind", kind_name(chart.kind)},
            {"polygons", polygons},
            {"atlas", p.atlas},
            {"rect", {p.rect.x, p.rect.y, p.rect.width, p.rect.height}},
            {"texels_per_metre", p.texels_per_metre},
            {"area_m2", chart.area_m2()}};
}

// Per input polygon: its object and the atlases and charts that hold it (none for a
// degenerate polygon, which gets no chart).
nlohmann::json polygons_json(const Scene& scene, const LightmapResult& r) {
    std::vector<std::set<std::uint32_t>> atlases(scene.polygons.size()), charts(atlases.size());
    for (std::size_t c = 0; c < r.charts.charts.size(); ++c)
        for (const lightmap::ChartTriangle& t : r.charts.charts[c].triangles) {
            atlases[t.polygon].insert(r.layout.placements[c].atlas);
            charts[t.polygon].insert(std::uint32_t(c));
        }
    nlohmann::json out = nlohmann::json::array();
    for (std::size_t p = 0; p < scene.polygons.size(); ++p)
        out.push_back({{"polygon", p},
                       {"object", scene.polygons[p].name},
                       {"atlases", atlases[p]},
                       {"charts", charts[p]}});
    return out;
}

std::string manifest_json(const Scene& scene, const LightmapOptions& options,
                          const LightmapResult& r, double exposure,
                          const std::vector<double>& intensities) {
    nlohmann::json j;
    j["scene"] = scene.name;
    j["scene_file"] = scene.file;
    j["quantity"] = has_indirect_only_light(scene)
                        ? "irradiance on the charted side of each polygon: every light's "
                          "indirect, the direct of the lights whose mode is all (lights)"
                        : "irradiance (direct + indirect) on the charted side of each polygon";
    j["units"] = "W/m2, linear RGB (the scene's radiometric channels; lux = 179 lm/W x "
                 "(0.265 R + 0.670 G + 0.065 B))";
    j["exr_pixels"] = options.exr == ExrPixels::half ? "half" : "float";
    j["texels_per_metre"] = options.atlas.texels_per_metre;
    j["atlas_size"] = r.layout.size;
    j["padding"] = r.layout.padding;
    j["packer"] = r.layout.packer == lightmap::AtlasPacker::rectangles ? "rectangles" : "profiles";
    j["samples_per_texel"] = r.samples_per_texel;
    j["uv"] = "texel (i, j) covers [i, i + 1) x [j, j + 1), row 0 at the top; glTF TEXCOORD_1 = "
              "(x, y) / atlas_size";
    nlohmann::json atlases = nlohmann::json::array();
    for (std::size_t a = 0; a < r.atlases.size(); ++a) {
        atlases.push_back({{"exr", atlas_file(a, "exr")},
                           {"png", atlas_file(a, "png")},
                           {"png_encoding", "sRGB(179 lm/W x irradiance / intensity), 8 bits"},
                           {"intensity", intensities[a]},
                           {"preview_png", atlas_preview_file(a)},
                           {"coverage", r.layout.coverage[a]},
                           {"preview_exposure", exposure}});
        if (a < r.directional.size())
            for (std::size_t k = 0; k < 4; ++k)
                atlases.back()["sh_exr"].push_back(directional_file(a, k));
    }
    j["atlases"] = atlases;
    j["gltf"] = {{"file", "scene.gltf"}, {"buffer", "scene.bin"}, {"up", "+y"}, {"units", "m"}};
    if (r.preview)
        j["preview"] = {{"exr", "preview.exr"},
                        {"png", "preview.png"},
                        {"quantity", "radiance (rho E + emission) / pi, W/(sr m2)"},
                        {"png_exposure", camera_exposure(scene, *r.preview)}};
    // What the browser client (client/) needs to shade as the preview does.
    if (r.preview) {
        const Rgb& background = scene.background;
        j["preview"]["background"] = {background.r, background.g, background.b};
        j["preview"]["samples_per_pixel"] = scene.camera->samples_per_pixel;
    }
    if (!r.directional.empty())
        j["directional"] = {
            {"quantity", "L1 spherical harmonics of the incident radiance, per channel"},
            {"order", "sh_exr[0..3] = L00, L1-1, L10, L11: real orthonormal SH proportional to "
                      "(1, y, z, x) of a unit direction in the scene's axes"},
            {"irradiance", "E(n) = pi L00 Y00(n) + (2 pi / 3) (L1-1 Y1-1(n) + L10 Y10(n) + L11 "
                           "Y11(n)), Y00 = 0.282095, Y1m = 0.488603 (y, z, x); equals the "
                           "irradiance atlas at the surface's normal"}};
    j["lights"] = lightmap_modes_json(scene);
    j["polygons"] = polygons_json(scene, r);
    nlohmann::json charts = nlohmann::json::array();
    for (std::size_t c = 0; c < r.charts.charts.size(); ++c)
        charts.push_back(chart_json(r.charts.charts[c], r.layout.placements[c]));
    j["charts"] = charts;
    j["texels"] = {{"covered", r.counts.texels},
                   {"samples", r.counts.samples},
                   {"hidden_samples", r.counts.hidden_samples},
                   {"hidden_texels", r.counts.hidden_texels},
                   {"unlit_texels", r.counts.unlit_texels}};
    const lightmap::SeamStitch& seams = r.seams;
    j["seams"] = {{"edges", seams.edges},
                  {"samples", seams.samples},
                  {"texels_moved", seams.texels},
                  {"error", "largest channel difference of the two sides' bilinear lookups at "
                            "each seam sample, W/m2"},
                  {"before", {{"mean", seams.before.mean}, {"max", seams.before.max}}},
                  {"after", {{"mean", seams.after.mean}, {"max", seams.after.max}}}};
    nlohmann::json times = nlohmann::json::object();
    for (const StageTime& t : r.times)
        times[t.stage] = t.seconds;
    j["times_s"] = times;
    return j.dump(2) + "\n";
}

// lightmap_N files from N = \p first on, left by an earlier run with more atlases.
void remove_atlas_files_from(const std::string& dir, std::size_t first) {
    for (std::size_t a = first;; ++a) {
        bool any = false;
        for (const std::string& name : atlas_files(a)) {
            std::error_code ec;
            any |= fs::remove(fs::path(dir) / name, ec);
        }
        for (std::size_t k = 0; k < 4; ++k) {
            std::error_code ec;
            any |= fs::remove(fs::path(dir) / directional_file(a, k), ec);
        }
        if (!any)
            return;
    }
}

// preview.exr and preview.png, or neither (an earlier run's removed) without a camera.
void write_preview(const std::string& dir, const Scene& scene,
                   const std::optional<Image>& preview) {
    if (!preview) {
        for (const char* name : {"preview.exr", "preview.png"}) {
            std::error_code ec;
            fs::remove(fs::path(dir) / name, ec);
        }
        return;
    }
    write_exr((fs::path(dir) / "preview.exr").string(), *preview);
    write_png((fs::path(dir) / "preview.png").string(), *preview, camera_exposure(scene, *preview));
}

} // namespace

void write_lightmaps(const std::string& dir, const Scene& scene, const LightmapOptions& options,
                     const LightmapResult& result) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec)
        throw ConfigError(fmt::format("cannot create output folder '{}': {}", dir, ec.message()));
    std::vector<std::string> names{"lightmaps.json", "scene.gltf", "scene.bin", "preview.exr",
                                   "preview.png"};
    for (std::size_t a = 0; a < result.atlases.size(); ++a)
        for (const std::string& name : atlas_files(a))
            names.push_back(name);
    for (std::size_t a = 0; a < result.directional.size(); ++a)
        for (std::size_t k = 0; k < 4; ++k)
            names.push_back(directional_file(a, k));
    remove_stale_temp_files(dir, names);
    const double exposure = preview_exposure(result.atlases);
    for (std::size_t a = 0; a < result.atlases.size(); ++a) {
        write_exr((fs::path(dir) / atlas_file(a, "exr")).string(), result.atlases[a], options.exr);
        write_png((fs::path(dir) / atlas_preview_file(a)).string(), result.atlases[a], exposure);
        for (std::size_t k = 0; a < result.directional.size() && k < 4; ++k)
            write_exr((fs::path(dir) / directional_file(a, k)).string(), result.directional[a][k],
                      options.exr);
    }
    // An earlier run's directional atlases, when this one has none.
    for (std::size_t a = result.directional.size(); a < result.atlases.size(); ++a)
        for (std::size_t k = 0; k < 4; ++k) {
            std::error_code ignored;
            fs::remove(fs::path(dir) / directional_file(a, k), ignored);
        }
    const std::vector<double> intensities = lightmap_intensities(result.atlases);
    write_moz_lightmaps(dir, result.atlases, intensities);
    remove_atlas_files_from(dir, result.atlases.size());
    write_lightmap_gltf(dir, scene, result, intensities);
    write_preview(dir, scene, result.preview);
    write_text_file((fs::path(dir) / "lightmaps.json").string(),
                    manifest_json(scene, options, result, exposure, intensities));
}

} // namespace penumbra::app
