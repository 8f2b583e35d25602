#pragma once

#include <array>
#include <vector>

#include "core/context.h"
#include "core/rng.h"
#include "core/scene.h"
#include "core/visibility.h"
#include "kernels/element_rows.h"
#include "progressive/shooting_state.h"

namespace penumbra::solver {

/// The range of a light's profile over the directions toward a triangle.
struct ProfileRange {
    double lo = 1, hi = 1;
    bool varies() const { return hi > lo; }
};

/// \brief The exact range of \p light's profile over the directions from it toward \p tri
///        ({1, 1} for an isotropic light): cos θ to the axis is extreme on the triangle's edges
///        unless the axis (or its opposite) passes through the triangle.
ProfileRange profile_range(const PointLight& light, const std::array<Vec3, 3>& tri);

/// \brief ∫ profile dω over the solid angle of \p tri seen from \p light, sr (the solid
///        angle itself for an isotropic light). Exact where the profile is constant over the
///        triangle; where it varies (a spot's falloff or cone edge) the triangle is split
///        1-to-4 until each part's possible error is below 1e-5 of the light's whole
///        ∫ profile dω, and such parts take the profile at their centroid.
double profile_solid_angle_triangle(const PointLight& light, const std::array<Vec3, 3>& tri);

/// \brief Casts \p rays segments from \p light to random points of \p target (lifted by
///        \p offset along its normal) drawn from \p rng; returns how many are unblocked.
int light_rays_open(const Vec3& light, const OrientedTriangle& target, double offset, int rays,
                    const VisibilityQuery& visibility, Pcg32& rng);

/// \brief Fraction of the power of \p light (the scene's point light \p id) that leaves the
///        scene, from its own rays (a spot's uniformly over its cut-off cone, each weighted by
///        the profile).
double light_escape_fraction(const ElementGeometry& geo, const VisibilityQuery& visibility,
                             const PointLight& light, PointSource id, std::uint64_t seed);

/// \brief Shoots every point light once: element j receives I·Ω_j·V_j / A_j, with Ω_j the
///        profile-weighted solid angle of j (profile_solid_angle_triangle; exact for an
///        isotropic light, so that a closed scene catches all of power()) and V_j the visible
///        fraction from rays. The escaping fraction is estimated by its own rays.
void shoot_point_lights(ShootingState& state, const ElementGeometry& geo,
                        const std::vector<PointLight>& lights, const VisibilityQuery& visibility,
                        const RowSettings& settings, const Context& ctx);

} // namespace penumbra::solver
