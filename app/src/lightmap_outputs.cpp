// The files of `penumbra lightmap`: per atlas lightmap_N.exr (linear irradiance) and
// lightmap_N.png (preview), and lightmaps.json, the manifest an engine's importer reads.

#include <filesystem>
#include <set>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/lightmap.h"
#include "core/error.h"
#include "core/files.h"

namespace penumbra::app {

namespace {

namespace fs = std::filesystem;

std::string atlas_file(std::size_t atlas, const char* extension) {
    return fmt::format("lightmap_{}.{}", atlas, extension);
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
                          const LightmapResult& r, double exposure) {
    nlohmann::json j;
    j["scene"] = scene.name;
    j["scene_file"] = scene.file;
    j["quantity"] = "irradiance (direct + indirect) on the charted side of each polygon";
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
                           {"coverage", r.layout.coverage[a]},
                           {"preview_exposure", exposure}});
        if (a < r.directional.size())
            for (std::size_t k = 0; k < 4; ++k)
                atlases.back()["sh_exr"].push_back(directional_file(a, k));
    }
    j["atlases"] = atlases;
    if (!r.directional.empty())
        j["directional"] = {
            {"quantity", "L1 spherical harmonics of the incident radiance, per channel"},
            {"order", "sh_exr[0..3] = L00, L1-1, L10, L11: real orthonormal SH proportional to "
                      "(1, y, z, x) of a unit direction in the scene's axes"},
            {"irradiance", "E(n) = pi L00 Y00(n) + (2 pi / 3) (L1-1 Y1-1(n) + L10 Y10(n) + L11 "
                           "Y11(n)), Y00 = 0.282095, Y1m = 0.488603 (y, z, x); equals the "
                           "irradiance atlas at the surface's normal"}};
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
        for (const char* extension : {"exr", "png"}) {
            std::error_code ec;
            any |= fs::remove(fs::path(dir) / atlas_file(a, extension), ec);
        }
        for (std::size_t k = 0; k < 4; ++k) {
            std::error_code ec;
            any |= fs::remove(fs::path(dir) / directional_file(a, k), ec);
        }
        if (!any)
            return;
    }
}

} // namespace

void write_lightmaps(const std::string& dir, const Scene& scene, const LightmapOptions& options,
                     const LightmapResult& result) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec)
        throw ConfigError(fmt::format("cannot create output folder '{}': {}", dir, ec.message()));
    std::vector<std::string> names{"lightmaps.json"};
    for (std::size_t a = 0; a < result.atlases.size(); ++a)
        for (const char* extension : {"exr", "png"})
            names.push_back(atlas_file(a, extension));
    for (std::size_t a = 0; a < result.directional.size(); ++a)
        for (std::size_t k = 0; k < 4; ++k)
            names.push_back(directional_file(a, k));
    remove_stale_temp_files(dir, names);
    const double exposure = preview_exposure(result.atlases);
    for (std::size_t a = 0; a < result.atlases.size(); ++a) {
        write_exr((fs::path(dir) / atlas_file(a, "exr")).string(), result.atlases[a], options.exr);
        write_png((fs::path(dir) / atlas_file(a, "png")).string(), result.atlases[a], exposure);
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
    remove_atlas_files_from(dir, result.atlases.size());
    write_text_file((fs::path(dir) / "lightmaps.json").string(),
                    manifest_json(scene, options, result, exposure));
}

} // namespace penumbra::app
