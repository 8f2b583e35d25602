#pragma once
// Per-tile statistics of camera renders, shared by the final gather's suites (issue #28).

#include <vector>

#include "core/image.h"

namespace penumbra::test {

/// Luminance of a linear Rgb (the weights of the Cornell reference's tests).
double luminance(const Rgb& c);

/// \brief Per 16 × 16 tile (row by row), the mean luminance of several renders of one view and
///        its standard error.
struct TileStats {
    std::vector<double> mean; ///< per tile, over the renders
    std::vector<double> standard_error;
};

/// \brief Per 16 × 16 tile, the mean luminance of \p renders and its standard error from their
///        scatter (independent seeds).
TileStats tile_stats(const std::vector<Image>& renders);

} // namespace penumbra::test
