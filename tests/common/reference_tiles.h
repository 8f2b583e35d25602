#pragma once
// Per-tile comparison of renders with a stored reference image and its own noise (issue #28:
// |Δ| ≤ 3 standard errors + 0.5 % per 16 × 16 tile, not a whole-image mean where errors
// cancel). Shared by the Cornell box and cornell-spheres tests.

#include <string>
#include <vector>

#include "core/image.h"

namespace penumbra::test {

/// \brief Side of the square tiles, pixels.
inline constexpr int k_tile_px = 16;

/// \brief Luminance of a radiance with the weights 0.265 / 0.670 / 0.065 (Radiance's).
double tile_luminance(const Rgb& c);

/// \brief Per tile (row by row), the mean luminance over a set of renders and its standard
///        error.
struct TileStats {
    std::vector<double> mean;
    std::vector<double> standard_error;
};

/// \brief Per tile, the mean luminance of \p renders (independent seeds, two or more; one
///        image gives a standard error of 0) and its standard error from their scatter.
TileStats tile_stats(const std::vector<Image>& renders);

/// \brief Luminance standard error of each tile's mean of \p stderr_image (per-pixel standard
///        errors, as scripts/reference/combine_halves.py writes them).
std::vector<double> tile_standard_errors(const Image& stderr_image);

/// \brief Compares \p renders tile by tile with the reference \p reference_exr and its
///        per-pixel standard errors \p stderr_exr (paths under the source tree): a tile is
///        off when |Δ| > 3 √(SE² + SE_ref²) + 0.5 % of the reference. Prints each tile off,
///        labelled \p label, and returns how many there are.
int tiles_off_reference(const std::vector<Image>& renders, const std::string& reference_exr,
                        const std::string& stderr_exr, const std::string& label);

/// \brief Mean and sample standard deviation of a quantity over an image's pixels.
struct ImageMoments {
    double mean = 0, sd = 0;
};

/// \brief The green channel's moments over \p image's pixels (a furnace's noise).
ImageMoments green_moments(const Image& image);

} // namespace penumbra::test
