#pragma once
// The caustic photons in a kd-tree (nanoflann) and their density estimate at a surface point
// (Jensen 1996), precomputed at the photons for Lambertian receivers (Christensen 1999).
// Internal to raytrace/.

#include "raytrace/raytrace.h"

#include "path_geometry.h"

#include "core/bsdf.h"

#include <memory>
#include <vector>

namespace penumbra::raytrace {

/// \brief Reflected radiance of the caustic photons near a point: Σ f(wo, wi_p) Φ_p / (π r²)
///        over the photons within r that landed on the same side of a surface facing the same
///        way; r the distance to the 64th nearest photon (at most CausticPhotons::radius_m),
///        or that radius when fixed. At a Lambertian receiver f is constant, so the sum is
///        taken once at every fourth photon and a point reads the nearest one's (within its disc).
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
    /// The estimate's disc around one photon, as if a point there were asked.
    struct PhotonDisc {
        RgbD irradiance_w_m2; ///< Σ Φ / (π r²) of the photons the estimate there counts
        double radius2 = 0;   ///< r², m²
    };

    /// The full estimate at \p s (any receiver).
    Rgb estimate(const Bsdf& bsdf, const SurfaceHit& s, const Vec3& wo) const;
    /// The nearest photon's precomputed estimate at \p s (a Lambertian receiver).
    Rgb precomputed(const Bsdf& bsdf, const SurfaceHit& s, const Vec3& wo) const;
    PhotonDisc disc_at(const CausticPhoton& photon) const;

    struct Tree;
    CausticPhotons photons_;
    std::unique_ptr<Tree> tree_;
    std::vector<PhotonDisc> discs_; ///< one per precomputed photon (photon_map.cpp)
};

} // namespace penumbra::raytrace
