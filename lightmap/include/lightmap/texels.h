#pragma once
// Texels of packed charts (issue #29): which texels each chart covers and where on the
// surface each texel lies, for the fill step to sample the solution there; and the dilation
// of filled atlases into their padding. Texel coordinates as in lightmap/atlas.h.

#include <cstdint>
#include <vector>

#include "core/context.h"
#include "core/image.h"
#include "core/vec.h"
#include "lightmap/atlas.h"
#include "lightmap/charts.h"

namespace penumbra::lightmap {

/// \brief A point on a chart triangle.
struct SurfacePoint {
    std::uint32_t triangle = 0; ///< index into Chart::triangles
    Vec3 barycentric;           ///< weights of the triangle's vertices 0, 1, 2: each ≥ 0, sum 1
    Vec3 position;              ///< world, metres: Σ barycentric_k · vertex_k
    Vec3 normal;                ///< unit, ChartTriangle::normal
    Vec2 texel_uv;              ///< atlas texel coordinates of the point
};

/// \brief A covered texel: one that some triangle of its chart overlaps with positive area.
struct Texel {
    int x = 0, y = 0;        ///< column and row in the atlas (row 0 at the top)
    std::uint32_t chart = 0; ///< index into Charts::charts
    /// The texel centre when it lies on the chart; else the chart's point nearest to the
    /// centre inside the texel (edge texels, which bilinear lookups read).
    SurfacePoint centre;
    /// The chart triangles that overlap the texel: AtlasTexels::overlaps[first, first + count).
    std::uint32_t first_overlap = 0, overlap_count = 0;
};

/// \brief The covered texels of one atlas.
struct AtlasTexels {
    int size = 0;
    std::vector<Texel> texels;           ///< in row-major order (y, then x)
    std::vector<std::uint32_t> overlaps; ///< triangle indices, see Texel::first_overlap
};

/// \brief Conservative rasterization of every chart into its atlas: each texel a chart
///        triangle overlaps, with its centre sample. Charts never share a texel (packing keeps
///        them apart). Parallel over charts in an arena from \p ctx; the result does not depend
///        on the thread count.
std::vector<AtlasTexels> rasterize(const Charts& charts, const AtlasLayout& layout,
                                   const Context& ctx);

/// \brief Supersamples of a texel's footprint: the centres of an \p n × \p n grid of
///        sub-squares that lie on one of the texel's overlapping triangles, in row-major order;
///        the texel's centre sample alone when none does (a thin sliver). Equal weights.
std::vector<SurfacePoint> texel_samples(const Chart& chart, const ChartPlacement& placement,
                                        const AtlasTexels& atlas, const Texel& texel, int n);

/// \brief Per texel of the atlas (row-major), 1 where a chart covers it, else 0.
std::vector<std::uint8_t> coverage_mask(const AtlasTexels& atlas);

/// \brief Dilation: every uncovered texel within \p radius texels (Chebyshev) of a covered one
///        takes the value of the nearest covered texel (Euclidean distance; ties to the first
///        in row-major order). \p covered is coverage_mask()'s; covered texels are unchanged.
void dilate(Image& image, const std::vector<std::uint8_t>& covered, int radius);

} // namespace penumbra::lightmap
