#pragma once

#include <vector>

#include "core/context.h"
#include "core/rng.h"
#include "core/scene.h"
#include "core/visibility.h"
#include "element_rows.h"
#include "shooting_state.h"

namespace penumbra::solver {

/// \brief Casts \p rays segments from \p light to random points of \p target (lifted by
///        \p offset along its normal) drawn from \p rng; returns how many are unblocked.
int light_rays_open(const Vec3& light, const OrientedTriangle& target, double offset, int rays,
                    const VisibilityQuery& visibility, Pcg32& rng);

/// \brief Fraction of a point light's power that leaves the scene, from its own rays.
double light_escape_fraction(const ElementGeometry& geo, const VisibilityQuery& visibility,
                             const Vec3& light, std::size_t light_id, std::uint64_t seed);

/// \brief Shoots every isotropic point light once: element j receives I·Ω_j·V_j / A_j, with
///        Ω_j the exact solid angle of j (so that a closed scene catches all 4πI) and V_j the
///        visible fraction from rays. The escaping fraction is estimated by its own rays.
void shoot_point_lights(ShootingState& state, const ElementGeometry& geo,
                        const std::vector<PointLight>& lights, const VisibilityQuery& visibility,
                        const RowSettings& settings, const Context& ctx);

} // namespace penumbra::solver
