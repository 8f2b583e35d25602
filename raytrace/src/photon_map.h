#pragma once
// The caustic photons in a kd-tree (nanoflann) and their density estimate at a surface point
// (Jensen 1996). Internal to raytrace/.

#include "raytrace/raytrace.h"

#include "path_geometry.h"

#include "core/bsdf.h"

#include <array>
#include <cstddef>
#include <memory>

namespace penumbra::raytrace {

/// \brief Reflected radiance of the caustic photons near a point: Σ f(wo, wi_p) Φ_p / (π r²)
///        over the photons within r that landed on the same side of a surface facing the same
///        way; r the distance to the 64th nearest photon (at most CausticPhotons::radius_m),
///        or that radius when fixed.
class CausticMap {
public:
    explicit CausticMap(CausticPhotons photons);
    ~CausticMap();
    CausticMap(const CausticMap&) = delete;
    CausticMap& operator=(const CausticMap&) = delete;

    bool empty() const;
    /// Radiance toward \p wo that \p bsdf reflects at \p s from the photons around it.
    Rgb radiance(const Bsdf& bsdf, const SurfaceHit& s, const Vec3& wo) const;

private:
    /// Photons of the nearest-photon estimate (Jensen 1996 uses 50 to 100).
    static constexpr std::size_t k_neighbours = 64;

    /// The k_neighbours photons nearest to \p query within \p radius2 (squared) or all within
    /// it if fewer, nearest first; returns how many.
    std::size_t nearest_within(const double query[3], double radius2,
                               std::array<std::size_t, k_neighbours>& index,
                               std::array<double, k_neighbours>& dist2) const;

    struct Tree;
    CausticPhotons photons_;
    std::unique_ptr<Tree> tree_;
};

} // namespace penumbra::raytrace
