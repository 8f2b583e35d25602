#pragma once
// The sun (core/scene.h: a disc of uniform radiance at infinity) as a source for every solver:
// directions over its disc, the visible fraction of the disc from a triangle or a point, and
// shooting it onto the elements. Its direct irradiance is Sun::irradiance · max(0, cos θ) · V.
// The sun has no finite power: what it "emits" into a scene is what its direct light delivers
// to the scene's surfaces, Σ E_direct,sun · A, and none of that escapes.

#include <cstdint>

#include "core/context.h"
#include "core/rng.h"
#include "core/scene.h"
#include "core/visibility.h"
#include "kernels/element_rows.h"
#include "progressive/shooting_state.h"

namespace penumbra::solver {

/// \brief A direction uniformly distributed (in solid angle) over the sun's disc, from two
///        numbers in [0, 1): u1 picks the ring, u2 the azimuth.
Vec3 sun_disc_direction(const Sun& sun, double u1, double u2);

/// What the rays toward the sun from a triangle found.
struct SunRays {
    double open = 0;      ///< Σ of their transmittances (1 each unblocked, T(θ) through panes)
    bool partial = false; ///< some blocked and some not
};

/// \brief Visible fraction of the sun's disc from the points of \p target (lifted by
///        \p offset along its normal): \p rays rays from uniformly drawn points toward
///        uniformly drawn directions of the disc, from \p rng.
SunRays sun_rays_open(const Sun& sun, const OrientedTriangle& target, double offset,
                      double diagonal, int rays, const VisibilityQuery& visibility, Pcg32& rng);

/// \brief Visible fraction of the sun's disc from the point \p from (already lifted off its
///        surface). 17 probe rays (the centre and 16 directions on the rim) decide where they
///        agree — a blocker edge can hide at most 0.16 % of the disc between two rim probes —
///        and where they disagree (a penumbra) 8 × \p rays directions, jittered on a grid
///        mapped to the disc by Shirley & Chiu's concentric map (compact strata), estimate it.
double sun_point_visibility(const Sun& sun, const Vec3& from, double diagonal, int rays,
                            const VisibilityQuery& visibility, Pcg32& rng);

/// The sun's direct irradiance on one triangle.
struct SunIrradiance {
    Rgb irradiance;       ///< irradiance · cos θ · V, W/m²; black if the triangle faces away
    bool partial = false; ///< the visibility rays disagreed (a penumbra or shadow boundary)
};

/// \brief The sun's direct irradiance on \p target, with V from rows.visibility_rays rays of
///        the stream (sun_visibility, key, kind, rows.seed).
SunIrradiance sun_triangle_irradiance(const Sun& sun, const OrientedTriangle& target, double offset,
                                      double diagonal, std::uint64_t key, std::uint64_t kind,
                                      const VisibilityQuery& visibility, const RowSettings& rows);

/// \brief Shoots the sun once: every element facing it receives sun_triangle_irradiance.
///        Returns the delivered power Σ E A (W per channel), which is also added to
///        state.emitted; nothing is added to state.escaped.
RgbD shoot_sun(ShootingState& state, const ElementGeometry& geo, const Sun& sun,
               const VisibilityQuery& visibility, const RowSettings& settings, const Context& ctx);

} // namespace penumbra::solver
