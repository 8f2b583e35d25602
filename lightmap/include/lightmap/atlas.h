#pragma once
// Packing charts into square atlases (issue #29) at a texel density.
//
// Conventions (glTF's): an atlas is an image of size × size texels, row-major with row 0 at
// the top, as core's Image stores it. Texel coordinates (x, y) run right and down in texel
// units: texel (i, j) covers [i, i + 1) × [j, j + 1) and its centre is (i + 0.5, j + 0.5).
// The glTF TEXCOORD_1 of a point is (x / size, y / size): (0, 0) is the image's top-left
// corner. docs/lightmaps.md has the whole method.

#include <cstdint>
#include <vector>

#include "core/context.h"
#include "core/vec.h"
#include "lightmap/charts.h"

namespace penumbra::lightmap {

/// \brief Atlas settings.
struct AtlasSettings {
    double texels_per_metre = 20; ///< texel density on the surface (texels per metre of length)
    int size = 1024;              ///< width and height of every atlas, texels
    /// Free texels between any two charts' covered texels and between a chart and the
    /// atlas's edges; room for dilation, so that bilinear lookups and the first mip level
    /// never mix charts.
    int padding = 2;
};

/// \brief A rectangle of texels: columns [x, x + width), rows [y, y + height).
struct TexelRect {
    int x = 0, y = 0, width = 0, height = 0;
};

/// \brief Where one chart lies in its atlas.
struct ChartPlacement {
    std::uint32_t atlas = 0; ///< index of its atlas
    /// Texels per metre it got: AtlasSettings::texels_per_metre, or less when the chart had
    /// to be scaled down to fit one atlas (a warning says so).
    double texels_per_metre = 0;
    /// Holds every texel the chart covers; its corner (x, y) is where the chart's rotated
    /// bounding box starts, so texel centres fall on the chart the same way wherever it lies.
    TexelRect rect;
    /// Per chart vertex (Chart::vertices): its atlas texel coordinates (see the file comment).
    std::vector<Vec2> texel_uv;
};

/// \brief Which packer made a layout (pack_atlases keeps the denser).
enum class AtlasPacker {
    rectangles, ///< stb_rect_pack's skyline packer on the charts' padded bounding rectangles
    profiles,   ///< our skyline packer on the charts' covered texels (column profiles)
};

/// \brief Charts placed in atlases.
struct AtlasLayout {
    int size = 0;    ///< AtlasSettings::size
    int padding = 0; ///< AtlasSettings::padding
    int atlas_count = 0;
    AtlasPacker packer = AtlasPacker::rectangles;
    std::vector<ChartPlacement> placements; ///< per chart, in the order of Charts::charts
    /// Per atlas: the fraction of its texels that a chart covers (conservatively: every texel a
    /// triangle overlaps, as rasterize() lists them).
    std::vector<double> coverage;
};

/// \brief Rotates each generated chart to its minimum-area bounding rectangle (imported ones
///        keep their axes), scales it to the texel density and aligns it to the texel grid;
///        then packs the charts, with padding, into as many atlases as needed twice: with
///        stb_rect_pack on their bounding rectangles (both 90° orientation policies and both
///        skyline heuristics, the best kept) and with our skyline packer on their covered
///        texels; the layout with the fewest atlases, then the lowest use of the last one, is
///        kept (AtlasLayout::packer). A chart too large for one atlas is scaled down until it
///        fits, with a warning. Throws ConfigError on a density ≤ 0, a size < 1 or > 8192, or
///        a padding < 0 or leaving no room. Deterministic.
AtlasLayout pack_atlases(const Charts& charts, const AtlasSettings& settings, const Context& ctx);

} // namespace penumbra::lightmap
