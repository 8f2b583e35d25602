#pragma once
// Irradiance gathered at a point (vertices, sensors): analytic point-to-triangle form factors
// from each source or reflecting element, times visibility from rays.

#include <cstdint>
#include <optional>
#include <vector>

#include "core/rng.h"
#include "core/scene.h"
#include "core/visibility.h"
#include "kernels/element_rows.h"

namespace penumbra::solver {

/// What a point can gather from: emitting elements, point lights, the sun and the sky
/// (direct), reflecting elements (indirect).
struct GatherSources {
    std::vector<std::uint32_t> emitters; ///< elements with non-zero emission
    std::vector<Rgb> emission;           ///< per element, πL (W/m²)
    std::vector<PointLight> lights;
    std::optional<Sun> sun;
    std::optional<Sky> sky;
};

struct GatherPoint {
    Vec3 position;
    Vec3 normal;
    std::uint64_t id = 0; ///< names the random stream together with the purpose
    RngPurpose purpose = RngPurpose::vertex_visibility;
};

/// \brief Direct irradiance (W/m²) at \p p from the sources. The sun's share,
///        irradiance · cos θ · V, takes V from sun_point_visibility with rays from the stream
///        (sun_visibility, p.id, 2, p.purpose, seed); the sky's, sky_point_irradiance with
///        k_sky_point_quadrature for sensors (k_sky_vertex_quadrature else), from the stream
///        (sky_visibility, p.id, 3, p.purpose, seed).
///        \p emitters: the emitting elements
///        to gather from, if not all of sources.emitters (increasing).
Rgb gather_direct(const ElementGeometry& geo, const GatherSources& sources,
                  const VisibilityQuery& visibility, const GatherPoint& p, int rays_per_source,
                  std::uint64_t seed, const std::vector<std::uint32_t>* emitters = nullptr);

/// \brief An element's share of a point's irradiance: form factor times visibility.
struct ElementWeight {
    std::uint32_t element = 0;
    double weight = 0;
};

/// \brief The weights by which gather_elements sums the exitances of the elements marked in
///        \p candidate (the same form factors, the same visibility rays): to gather many
///        exitances at one point (daylight coefficients).
std::vector<ElementWeight> element_weights(const ElementGeometry& geo,
                                           const std::vector<std::uint8_t>& candidate,
                                           const VisibilityQuery& visibility, const GatherPoint& p,
                                           int rays_per_element, std::uint64_t seed);

/// \brief Irradiance (W/m²) at \p p from every element's radiance \p exitance (W/m²),
///        excluding nothing; pass reflected radiosity B − E for the indirect part.
Rgb gather_elements(const ElementGeometry& geo, const std::vector<Rgb>& exitance,
                    const VisibilityQuery& visibility, const GatherPoint& p, int rays_per_element,
                    std::uint64_t seed);

} // namespace penumbra::solver
