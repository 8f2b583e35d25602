#pragma once
// The camera's view of a lightmap bake as an engine draws it (issue #29): every visible point
// shaded only from the atlas texels, looked up bilinearly at its lightmap UV.

#include "app/lightmap.h"
#include "core/context.h"
#include "core/image.h"
#include "core/scene.h"
#include "raytrace/raytrace.h"

namespace penumbra::app {

/// A pixel of the preview whose first samples differ by R W/(sr·m²) is sampled again with about
/// R / this many multi-jittered samples (at most 64²; raytrace::EdgeRefinement): the rim of a
/// lamp of 17 W/(sr·m²) is then placed to about 0.002 W/(sr·m²).
inline constexpr double k_preview_edge_tolerance = 0.004;

/// \brief Bilinear lookup of \p atlas at atlas texel coordinates \p texel_uv (texel (i, j)'s
///        centre at (i + 0.5, j + 0.5)), clamped at the atlas's edges, as a GPU samples a
///        texture with linear filtering and clamp-to-edge.
Rgb sample_bilinear(const Image& atlas, const Vec2& texel_uv);

/// \brief The view of \p scene's camera (its image size and samples per pixel, more at edges
///        of high contrast: k_preview_edge_tolerance) over \p rt
///        (the bake's mesh): at each primary hit on a polygon's front side the outgoing
///        radiance (ρ E + emission) / π, E the bilinear lookup of r.atlases at the hit's
///        lightmap UV, ρ and emission the element's; backs of surfaces (no lightmap) black,
///        misses the scene's background. Returns W/(sr·m²); bitwise the same for any thread
///        count. Needs scene.camera.
Image render_lightmap_preview(const Scene& scene, const raytrace::EmbreeScene& rt,
                              const LightmapResult& r, const Context& ctx);

} // namespace penumbra::app
