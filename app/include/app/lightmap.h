#pragma once
// `penumbra lightmap` (issue #29): the bake pipeline without render, then the scene's charts
// packed into atlases and every covered texel filled with the irradiance the solution and the
// sources give its footprint; written as linear EXR, PNG, a glTF copy of the scene with the
// lightmaps on TEXCOORD_1 (MOZ_lightmap), the camera's preview and a JSON manifest.
// docs/lightmaps.md describes the method.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/pipeline.h"
#include "core/context.h"
#include "core/image.h"
#include "core/scene.h"
#include "lightmap/atlas.h"
#include "lightmap/charts.h"
#include "lightmap/seams.h"
#include "lightmap/texels.h"

namespace penumbra::app {

/// \brief Options of `penumbra lightmap`.
struct LightmapOptions {
    lightmap::AtlasSettings atlas; ///< density, atlas size, padding
    ExrPixels exr = ExrPixels::half;
    /// Also the L1 spherical harmonics of the incident radiance per texel (four more atlases
    /// each: lightmap_N_L00, _L1m1, _L10, _L11; docs/lightmaps.md).
    bool directional = false;
    /// Stitch the seams between charts after dilation (lightmap/seams.h).
    bool stitch_seams = true;
    /// `--gather N`: each texel sample's irradiance from N final-gather paths
    /// (raytrace::gather_irradiance_at) instead of direct + the solution's indirect; 0: off.
    int gather_samples = 0;
};

/// \brief What filling found, summed over the atlases.
struct LightmapCounts {
    std::size_t texels = 0;         ///< covered texels
    std::size_t samples = 0;        ///< footprint samples on the charts
    std::size_t hidden_samples = 0; ///< on a hidden or covered part: skipped
    std::size_t hidden_texels = 0;  ///< every sample hidden: valued from their chart's texels
    std::size_t unlit_texels = 0;   ///< hidden, on a chart hidden everywhere: left 0
};

/// \brief The lightmaps of a bake: the charts and their atlases of irradiance.
struct LightmapResult {
    lightmap::Charts charts;
    lightmap::AtlasLayout layout;
    std::vector<lightmap::AtlasTexels> texels; ///< per atlas, its covered texels
    std::vector<Image> atlases; ///< irradiance, W/m², linear RGB, layout.size² each
    /// The scene camera's view shaded only from the atlases (radiance W/(sr·m²)), as an engine
    /// shows the bake; none without a camera (docs/lightmaps.md, "Preview").
    std::optional<Image> preview;
    /// With LightmapOptions::directional: per atlas the images of L00, L1−1, L10 and L11
    /// (lightmap/sh.h's order, world axes, W/(sr·m²) × sr^½ per channel).
    std::vector<std::array<Image, 4>> directional;
    LightmapOptions options; ///< as plan_lightmaps was given them, for fill_lightmaps
    LightmapCounts counts;
    /// The irradiance atlases' seams, stitched after dilation (LightmapOptions::stitch_seams).
    lightmap::SeamStitch seams;
    int samples_per_texel = 0;    ///< footprint samples of a texel that lies wholly on its chart
    std::vector<StageTime> times; ///< charts, packing, texels, bake (all its stages), fill
    std::uint64_t rays = 0;       ///< traced by the fill
};

/// \brief The charts of \p scene, packed into atlases and rasterized (no solving): throws
///        ConfigError for bad atlas settings. Fills every member but atlases, counts and rays.
LightmapResult plan_lightmaps(const Scene& scene, const LightmapOptions& options,
                              const Context& ctx);

/// \brief What a bake for lightmaps needs: no render, no solver state, the mesher's mesh
///        kept (BakeOptions::keep_input_mesh: the fill gathers direct light from its emitters).
BakeOptions lightmap_bake_options();

/// \brief Fills the atlases of \p result (from plan_lightmaps) from \p bake, a bake of
///        \p scene, and renders its preview when the scene has a camera. Deterministic for
///        any thread count.
void fill_lightmaps(const Scene& scene, const BakeResult& bake, LightmapResult& result,
                    const Context& ctx);

/// \brief plan_lightmaps, a bake with lightmap_bake_options(), fill_lightmaps.
LightmapResult bake_lightmaps(const Scene& scene, const LightmapOptions& options,
                              const Context& ctx);

/// \brief Writes into \p dir, each file atomically: per atlas lightmap_N.exr (irradiance W/m²,
///        options.exr pixels), lightmap_N.png (MOZ_lightmap's encoding: 8-bit sRGB of
///        179 lm/W × irradiance / the atlas's intensity) and lightmap_N_preview.png (8-bit sRGB
///        at one automatic exposure for all atlases); scene.bin + scene.gltf (the glTF copy);
///        preview.exr + preview.png when result.preview is set; lightmaps.json (the manifest).
///        Removes the lightmap_N files of an earlier run with more atlases, and its preview
///        files when there is no preview. Throws ExternalError/ConfigError.
void write_lightmaps(const std::string& dir, const Scene& scene, const LightmapOptions& options,
                     const LightmapResult& result);

} // namespace penumbra::app
