#pragma once
// The memory estimates of the pipeline's bulk stages (issue #32, docs/memory.md), each made
// from its input before the stage allocates: a render's image, the daylight coefficients'
// matrices, a year of hourly matrices, the lightmap atlases. Each throws ConfigError naming
// the setting to change when its estimate is over the context's limit (core/memory.h).

#include <cstddef>

#include "core/context.h"
#include "core/scene.h"
#include "lightmap/atlas.h"
#include "lightmap/charts.h"
#include "lightmap/texels.h"

namespace penumbra::app {

/// Sensors × hours float matrices `penumbra annual` holds at once: the sun's direct light
/// (per hour and per hour the sun is up), the illuminance and its sum's temporaries, and the
/// copies handed to the writers.
inline constexpr std::size_t k_hourly_matrices = 8;

/// Bytes per atlas texel of the lightmaps: the atlas image, the preview's copy of all
/// atlases, the written file's copy, and the coverage mask.
inline constexpr std::size_t k_lightmap_bytes_per_texel = 3 * sizeof(Rgb) + 1;
/// Bytes per covered texel besides: its rasterized texel.
inline constexpr std::size_t k_lightmap_bytes_per_covered_texel = sizeof(lightmap::Texel);

/// \brief The camera's image of \p scene (when it has a camera).
void check_render_memory(const Scene& scene, const Context& ctx);

/// \brief The coefficient matrices: \p roots elements × \p patches, and \p sensors ×
///        (2 \p patches + \p sun_bins), floats.
void check_coefficient_memory(std::size_t roots, std::size_t sensors, std::size_t patches,
                              std::size_t sun_bins, const Context& ctx);

/// \brief A year's matrices: \p patches × \p hours (the sky matrix) and k_hourly_matrices
///        of \p sensors × \p hours, floats.
void check_hourly_memory(std::size_t sensors, std::size_t patches, std::size_t hours,
                         const Context& ctx);

/// \brief The covered texels \p charts will have at least, before packing (which takes long
///        at a high density): their area at \p settings' density, at most an atlas each.
void check_lightmap_charts(const lightmap::Charts& charts, const lightmap::AtlasSettings& settings,
                           const Context& ctx);

/// \brief The atlases of \p layout: k_lightmap_bytes_per_texel per texel, and
///        k_lightmap_bytes_per_covered_texel per covered one.
void check_lightmap_memory(const lightmap::AtlasLayout& layout, const Context& ctx);

} // namespace penumbra::app
