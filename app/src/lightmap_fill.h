#pragma once
// Filling lightmap texels from a radiosity solution (issue #29): each covered texel's
// irradiance is the mean over samples of its footprint of the direct light gathered at the
// sample (as sensors gather it) and the solution's indirect light interpolated there.
// docs/lightmaps.md describes the method.

#include "app/lightmap.h"
#include "core/context.h"
#include "core/image.h"
#include "core/mesh.h"
#include "core/scene.h"
#include "lightmap/atlas.h"
#include "lightmap/charts.h"
#include "lightmap/texels.h"
#include "raytrace/raytrace.h"

namespace penumbra::app {

/// Samples per texel along each axis of its footprint: 3 × 3, the centres of equal
/// sub-squares (lightmap::texel_samples), so that a texel is its footprint's box-filtered mean
/// and a shadow edge crossing it lands in one of four levels between its sides.
inline constexpr int k_texel_samples_per_axis = 3;

/// \brief The irradiance atlas (W/m², RGB, linear) of \p texels: every covered texel the mean
///        over its k_texel_samples_per_axis² samples that lie on an element of their own
///        polygon's front side of [direct irradiance gathered at the sample (moved 10 ray
///        offsets inside its element) + the solution's vertex_irradiance_indirect
///        interpolated there]. A sample on no such element lies on a hidden or covered part
///        (under a wall, inside a contact) and is skipped; a texel with none takes the mean
///        of its chart's neighbouring texels, grown inwards. Then dilated into the padding:
///        each free texel within layout.padding of a chart takes its nearest covered texel.
///        \p rt traces the mesh \p solution lives on; the direct light comes from the
///        emitting elements of \p sources (solver::direct_irradiance_at). Deterministic for
///        any thread count; adds what it found to \p counts.
Image fill_atlas(const Scene& scene, const Solution& solution, const raytrace::EmbreeScene& rt,
                 const RadiosityMesh& sources, const lightmap::Charts& charts,
                 const lightmap::AtlasLayout& layout, const lightmap::AtlasTexels& texels,
                 const Context& ctx, LightmapCounts& counts);

} // namespace penumbra::app
