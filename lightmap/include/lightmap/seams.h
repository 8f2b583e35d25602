#pragma once
// Seam stitching (issue #29, after Iwanicki 2013, "Lighting technology of The Last of Us"):
// where two charts share a 3D edge, an engine's bilinear lookups on either side of the edge
// read different texels and show a seam. Stitching moves the texels of the seams' bilinear
// footprints, by least squares, so that both sides agree while staying close to their values;
// every other texel stays as it was. docs/lightmaps.md describes the method.

#include <cstdint>
#include <vector>

#include "core/image.h"
#include "core/vec.h"
#include "lightmap/atlas.h"
#include "lightmap/charts.h"

namespace penumbra::lightmap {

/// \brief One point of a seam seen from both of its charts: the same 3D point at atlas texel
///        coordinates \p uv_a in atlas \p atlas_a and \p uv_b in atlas \p atlas_b.
struct SeamSample {
    std::uint32_t atlas_a = 0, atlas_b = 0;
    Vec2 uv_a, uv_b;
};

/// Seams up to this angle between the two sides' normals are stitched by default: a UV seam
/// on a smooth or flat surface, not a crease.
constexpr double k_smooth_seam_deg = 20;

/// \brief The seams of a layout: \p edges pairs of chart edges, sampled on both sides.
struct Seams {
    std::size_t edges = 0;
    std::vector<SeamSample> samples;
};

/// \brief Every chart-boundary edge whose two 3D corners (within about \p weld_tolerance_m)
///        are those of a boundary edge of another chart, or of another edge of the same chart,
///        paired with it and sampled at max(2, 3 × its longer length in texels) evenly spaced
///        points (interval midpoints) on both sides. Edges that share only part of their
///        length are not seams here. Deterministic order. Only edges whose triangles' normals
///        differ by at most \p max_crease_deg pair: across a crease (a room's corner) the two
///        sides' irradiance differs physically and must not be evened out.
Seams find_seams(const Charts& charts, const AtlasLayout& layout, double weld_tolerance_m,
                 double max_crease_deg = k_smooth_seam_deg);

/// \brief Seam error of \p atlases: per sample the largest channel difference of the two
///        bilinear lookups (W/m² for irradiance), its mean and maximum over the samples.
struct SeamError {
    double mean = 0, max = 0;
};
SeamError seam_error(const std::vector<Image>& atlases, const std::vector<SeamSample>& samples);

/// \brief Seam stitching's figures.
struct SeamStitch {
    std::size_t edges = 0;   ///< seam edges (pairs of chart edges)
    std::size_t samples = 0; ///< seam samples
    std::size_t texels = 0;  ///< texels in the samples' bilinear footprints: the only ones moved
    int iterations = 0;      ///< conjugate-gradient iterations, the largest over the channels
    SeamError before, after;
};

/// \brief Stitches \p atlases along \p samples: the texels x of the samples' bilinear
///        footprints minimise Σ (x − x₀)² + \p weight² Σ_samples (lookup_a − lookup_b)² per
///        channel (normal equations, Eigen's conjugate gradient to 10⁻⁸ relative residual);
///        the atlases' other texels are unchanged. Serial: the same bits for any thread count.
SeamStitch stitch_seams(std::vector<Image>& atlases, const Seams& seams, double weight);

} // namespace penumbra::lightmap
