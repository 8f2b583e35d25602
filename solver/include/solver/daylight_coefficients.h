#pragma once
// Daylight coefficients (issue #31): the irradiance each sensor receives per unit radiance of
// each patch of the sky and ground, seen directly and after interreflection, on one
// hierarchical system whose links are refined once for light from every direction. A year
// of skies is then a matrix product (annual/). The sun's direct light is computed per hour
// exactly (sun_direct_irradiance); its reflected part through coefficients of suns in a few
// hundred directions that the year's suns are binned into.

#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "core/context.h"
#include "core/mesh.h"
#include "core/scene.h"
#include "core/visibility.h"

namespace penumbra::solver {

/// \brief The sky's directions in patches (annual::SkyPatches through a function, so that the
///        solver does not depend on the annual library).
struct PatchBinning {
    std::size_t count = 0;
    /// Adds \p weight, shared among the patches of the unit world direction \p dir (pointing
    /// away from the scene, to the sky or ground), to \p sums (one per patch).
    std::function<void(const Vec3& dir, double weight, std::vector<double>& sums)> add;
};

/// \brief Coefficients of every leaf element of the system (`penumbra annual --mesh`):
///        elements × (patches + 2 × sun directions) floats.
struct ElementCoefficients {
    RadiosityMesh mesh; ///< the leaf elements
    /// Elements × patches: the element's irradiance (W/m²) per unit radiance of the patch,
    /// seen (at its root's centroid, as the system's sky links carry it) and reflected.
    Eigen::MatrixXf sky;
    /// Elements × sun directions: irradiance per unit normal irradiance of the sun, direct
    /// (the sun's links to the leaves) and reflected.
    Eigen::MatrixXf sun_direct, sun_indirect;
};

/// \brief Irradiance (W/m²) at each sensor per unit radiance (W/(sr·m²)) of each patch:
///        sensors × patches.
struct DaylightCoefficients {
    /// The patch seen from the sensor, through glazing: Σ T cos θ Δω over its directions.
    Eigen::MatrixXf direct;
    /// What the patch's light brings after reflection and transmission by the scene's
    /// surfaces (the solution's B − E gathered at the sensor).
    Eigen::MatrixXf indirect;
    /// Sensors × sun directions: what a sun of unit normal irradiance (W/m²) in each direction
    /// brings after reflection and transmission (its direct light is sun_direct_irradiance's).
    Eigen::MatrixXf sun_indirect;
    std::size_t nodes = 0, links = 0;            ///< of the system the coefficients were solved on
    std::optional<ElementCoefficients> elements; ///< with CoefficientTargets::with_elements
};

/// \brief Whether daylight_coefficients() also keeps every leaf element's coefficients.
enum class CoefficientTargets { sensors, with_elements };

/// \brief \p scene as the coefficients light it: a uniform sky and ground of radiance 1 (with
///        the scene's compass), no sun, no point lights. The links are refined under it; mesh
///        this scene, so that the mesher's hidden-region test counts the sky.
Scene coefficient_scene(const Scene& scene);

/// \brief Daylight coefficients of \p scene's sensors for the patches of \p patches and
///        suns (of \p sun_angular_diameter_deg) in \p sun_directions (unit, toward the sun).
///        The scene's own sky, sun, point lights and emission are not used: the links are
///        refined under a uniform sky and ground of the same radiance, then one solve per
///        patch and per sun reuses them. Progress per solve.
DaylightCoefficients
daylight_coefficients(const Scene& scene, const RadiosityMesh& mesh,
                      const VisibilityQuery& visibility, const PatchBinning& patches,
                      std::span<const Vec3> sun_directions, double sun_angular_diameter_deg,
                      const Context& ctx, CoefficientTargets targets = CoefficientTargets::sensors);

/// \brief The sun's direct irradiance (W/m²) at each sensor for a sun of unit normal
///        irradiance in each direction of \p sun_directions (unit, toward the sun):
///        sensors × directions, cos θ times the visibility of the sun's disc of
///        \p angular_diameter_deg (and the panes' transmittance on the way).
Eigen::MatrixXf sun_direct_irradiance(const Scene& scene, const RadiosityMesh& mesh,
                                      const VisibilityQuery& visibility,
                                      std::span<const Vec3> sun_directions,
                                      double angular_diameter_deg, const Context& ctx);

} // namespace penumbra::solver
