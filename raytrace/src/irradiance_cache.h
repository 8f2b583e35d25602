#pragma once
// Ward's irradiance cache (Ward, Rubinstein & Clear 1988) for the final gather's indirect
// light at Lambertian camera hits, with Ward & Heckbert's (1992) rotational and translational
// gradients. Records are placed before the render by a pass over a fixed pixel grid, coarse to
// fine, so the cache does not depend on the thread count; the render only reads it.
// Internal to raytrace/.

#include "camera.h"
#include "path_geometry.h"

#include "core/context.h"
#include "core/material.h"
#include "core/rng.h"
#include "core/scene.h"
#include "core/vec.h"

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace penumbra::raytrace {

/// \brief One record: the indirect irradiance gathered at a point, its gradients and reach.
struct IrradianceRecord {
    Vec3 p;              ///< where it was gathered, metres
    Vec3 n;              ///< unit shading normal of the side it was gathered on
    Rgb irradiance;      ///< indirect irradiance, W/m² per channel
    double radius_m = 0; ///< R: harmonic mean distance of its rays' first hits, clamped
    /// Per channel: d E / d(rotation about an axis) (Ward & Heckbert's rotational gradient)
    /// and d E / d(position) (translational), W/m² per radian and per metre.
    std::array<Vec3, 3> rotation_gradient{}, translation_gradient{};
};

/// \brief Whether the cache may stand for the indirect light at a surface of \p m: Lambertian
///        reflection only (no lobe, no diffuse transmission).
inline bool cacheable(const Material& m) {
    return !m.lobe && m.diffuse_transmittance.is_black();
}

/// \brief The records in a kd-tree and Ward's interpolation among them.
class IrradianceCache {
public:
    /// \p error: Ward's a; a record is valid at (p, n) while ε = |p − p_i| / R_i +
    /// √(1 − n·n_i) < a.
    IrradianceCache(std::vector<IrradianceRecord> records, double error);

    /// Indirect irradiance at \p p on the surface facing unit \p n: the records valid there,
    /// each extrapolated by its gradients, weighted by 1/ε − 1/a (Ward's 1/ε, less its value
    /// at the edge of validity, so the estimate is continuous); none where no record is valid.
    std::optional<Rgb> irradiance(const Vec3& p, const Vec3& n) const;
    /// Whether some record is valid at (p, n).
    bool covers(const Vec3& p, const Vec3& n) const;

    const std::vector<IrradianceRecord>& records() const { return records_; }

private:
    /// A uniform grid over the records' spheres of reach (a·R): each cell lists, in record
    /// order, the records whose sphere's box overlaps it, so a lookup looks at few records.
    struct Grid {
        Vec3 origin;
        double cell_m = 1;
        std::array<int, 3> cells{0, 0, 0};
        std::vector<std::uint32_t> first; ///< per cell, its list's start in items; then the end
        std::vector<std::uint32_t> items;
    };
    static Grid make_grid(const std::vector<IrradianceRecord>& records, double error);
    /// An empty grid over the boxes of radius \p reach around the records.
    static Grid sized_grid(const std::vector<IrradianceRecord>& records,
                           const std::vector<double>& reach);

    template <typename Visit> void visit_valid(const Vec3& p, const Vec3& n, Visit&& visit) const;

    std::vector<IrradianceRecord> records_;
    double error_ = 0.2;
    Grid grid_;
};

/// \brief What one of a record's rays brings back.
struct RecordRay {
    Rgb radiance;    ///< indirect radiance arriving along the ray, W/(sr·m²)
    double distance; ///< to its first hit; infinite if it leaves the scene
};

/// \brief Traces a record's ray from \p s along unit \p wi (in s's hemisphere), drawing from
///        \p rng. Called from several threads at once.
using RecordTracer = std::function<RecordRay(const SurfaceHit& s, const Vec3& wi, Pcg32& rng)>;

/// \brief Places and computes the records for \p camera's view: the pixel centres of grids of
///        32, 16, 8, 4 and 2 pixels in turn, each one's primary hit on a cacheable surface
///        not yet covered by the records of coarser grids gets a record (computed in parallel,
///        each from its own stream named by its pixel, kept in the grid's order).
IrradianceCache build_irradiance_cache(const EmbreeScene& rt, const SurfaceGeometry& surfaces,
                                       const PinholeCamera& camera,
                                       const IrradianceCacheSettings& settings,
                                       const RecordTracer& trace, const Context& ctx);

} // namespace penumbra::raytrace
