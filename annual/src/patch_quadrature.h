#pragma once
// Each sky patch's mean radiance by a product Gauss–Legendre rule in (sin altitude, azimuth),
// the coordinates in which dω = d(sin alt) dφ is uniform, so that a patch's weights sum to its
// solid angle exactly. A sky is smooth but for the cusp of Perez's circumsolar peak exp(d γ)
// at the sun, so patches near the sun get a finer rule than the rest.

#include <cstddef>
#include <span>
#include <vector>

#include "core/sky.h"
#include "core/vec.h"

#include "annual/sky_patches.h"

namespace penumbra::annual {

class PatchQuadrature {
public:
    explicit PatchQuadrature(const SkyPatches& patches);

    /// \brief \p sky's mean radiance over each patch into \p out (one entry per patch, the
    ///        ground's first), W/(sr·m²) of luminance-equivalent grey.
    void mean_radiance(const Sky& sky, std::span<float> out) const;

private:
    /// Directions and weights (summing to 1 over each patch) of every sky patch.
    struct Nodes {
        std::vector<Vec3> directions;
        std::vector<double> weights;
        std::vector<std::size_t> first; ///< per patch, into directions; one more at the end
    };

    Nodes coarse_, fine_;
    std::vector<Vec3> centres_;
    std::vector<double> near_sun_cos_; ///< per patch: the sun nearer than this takes fine_
};

} // namespace penumbra::annual
