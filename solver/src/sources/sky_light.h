#pragma once
// The sky and its ground (core/sky.h) as a source for every solver: the irradiance
// ∫ L(ω) T(ω) cos θ dω over a receiver's hemisphere, with T the visibility query's
// transmittance (0 behind opaque surfaces, the panes' T(θ) through glazing). The hemisphere
// is cut into cells of equal projected solid angle (Shirley & Chiu's concentric map); each cell is
// sampled by 2 × 2 jittered directions and split into four where they disagree (a window's edge,
// the horizon, the circumsolar peak) or where a neighbour saw otherwise (an edge between its
// samples), so rays gather where the sky is partly hidden. Like the sun, the sky has no finite
// power: what it emits into a scene is what it delivers to the surfaces.

#include <cstdint>
#include <span>

#include "core/context.h"
#include "core/rng.h"
#include "core/sky.h"
#include "core/visibility.h"
#include "kernels/element_rows.h"
#include "progressive/shooting_state.h"

namespace penumbra::solver {

/// \brief The cells of a sky integral: side × side over the hemisphere to start with, each
///        of projected solid angle π / side², split in four up to max_depth times. A feature of
///        the sky's visibility smaller than half a starting cell can be missed.
struct SkyQuadrature {
    int side = 32;
    int max_depth = 6;
};

// The starting cells decide what is found, the depth how finely its edges are resolved (the
// office's calibration of both: docs/daylight.md).

/// For sensors: 1 024 starting cells (about 6° across at the normal), split down to 0.2°.
inline constexpr SkyQuadrature k_sky_point_quadrature{32, 5};
/// For mesh vertices, which are many: 256 cells to start with, split down to 0.7°.
inline constexpr SkyQuadrature k_sky_vertex_quadrature{16, 4};
/// For the elements' light links, whose values only feed interreflection.
inline constexpr SkyQuadrature k_sky_element_quadrature{12, 3};

/// \brief The sky's irradiance (W/m² per channel) at \p from (already lifted off its surface)
///        on a plane of unit normal \p n, with the jitter drawn from \p rng.
RgbD sky_point_irradiance(const Sky& sky, const Vec3& from, const Vec3& n, double diagonal,
                          const VisibilityQuery& visibility, const SkyQuadrature& quadrature,
                          Pcg32& rng);

/// \brief One sample of a sky integral: the sky's radiance in \p direction counts with
///        \p weight = T times its share of projected solid angle (sr).
struct SkySample {
    Vec3 direction;
    Rgb radiance;
    double weight = 0;
};

/// \brief The samples whose Σ radiance × weight sky_point_irradiance returns (the same
///        cells, the same rays for the same \p rng), those with T > 0 only: to bin the
///        integral by direction (daylight coefficients). Replaces \p out's contents.
void sky_point_samples(const Sky& sky, const Vec3& from, const Vec3& n, double diagonal,
                       const VisibilityQuery& visibility, const SkyQuadrature& quadrature,
                       Pcg32& rng, std::vector<SkySample>& out);

/// \brief The sky's irradiance on \p target: at its centroid lifted by \p offset, with
///        k_sky_element_quadrature and the stream (sky_visibility, key, 0, 0, seed). One point
///        (not a rule over the triangle): the links' values only feed interreflection, which
///        is smooth at the mesh's element size, and more points multiply the links' rays.
Rgb sky_triangle_irradiance(const Sky& sky, const OrientedTriangle& target, double offset,
                            double diagonal, std::uint64_t key, const VisibilityQuery& visibility,
                            std::uint64_t seed);

/// \brief Shoots the sky once: every element receives sky_triangle_irradiance. Returns the
///        delivered power Σ E A (W per channel), which is also added to state.emitted.
RgbD shoot_sky(ShootingState& state, const ElementGeometry& geo, const Sky& sky,
               const VisibilityQuery& visibility, const RowSettings& settings, const Context& ctx);

} // namespace penumbra::solver
