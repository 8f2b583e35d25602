#pragma once
// Filling lightmap texels from a radiosity solution (issue #29): each covered texel's
// irradiance is the mean over samples of its footprint of the direct light gathered at the
// sample (as sensors gather it) and the solution's indirect light interpolated there.
// docs/lightmaps.md describes the method.

#include <cstdint>
#include <optional>
#include <vector>

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

/// Per input polygon, the emitting elements of the direct light's sources mesh it may see
/// (emitters_seen_by_polygons, increasing).
using EmittersSeen = std::vector<std::vector<std::uint32_t>>;

/// \brief A texel sample found on the radiosity mesh.
struct MeshSample {
    Vec3 gather_point; ///< where its direct light is gathered: 10 ray offsets inside its element
    Rgb indirect;      ///< the solution's indirect irradiance at the sample, W/m²
};

/// \brief How far above a sample its element ray starts: 10 of the solver's ray offsets
///        (10⁻⁴ of the scene's diagonal).
double probe_height(const RadiosityMesh& mesh);

/// \brief The element under sample \p s, found by a short ray down its normal from \p height
///        above it; nothing unless that element belongs to \p polygon's front side (else the
///        sample lies on a hidden or covered part, where the mesher made no elements).
std::optional<MeshSample> locate_sample(const raytrace::EmbreeScene& rt, const Solution& solution,
                                        const lightmap::SurfacePoint& s, std::uint32_t polygon,
                                        double height);

/// \brief The irradiance atlas (W/m², RGB, linear) of \p texels: every covered texel the mean
///        over its k_texel_samples_per_axis² samples that lie on an element of their own
///        polygon's front side of [direct irradiance gathered at the sample (moved 10 ray
///        offsets inside its element) + the solution's vertex_irradiance_indirect
///        interpolated there]. A sample on no such element lies on a hidden or covered part
///        (under a wall, inside a contact) and is skipped; a texel with none takes the mean
///        of its chart's neighbouring texels, grown inwards. Then dilated into the padding:
///        each free texel within layout.padding of a chart takes its nearest covered texel.
///        \p rt traces the mesh \p solution lives on; the direct light comes from the
///        emitting elements of \p sources (solver::direct_irradiance_at) that
///        \p emitters_seen lists for the sample's polygon (emitters_seen_by_polygons: a lamp
///        whose every probe line from the polygon is blocked is left out), without the lights
///        whose lightmap_mode is indirect. With \p gather_samples > 0 a sample's value is the
///        final gather's instead (texel_sample_light). Deterministic for any thread count; adds
///        what it found to \p counts.
Image fill_atlas(const Scene& scene, const Solution& solution, const raytrace::EmbreeScene& rt,
                 const RadiosityMesh& sources, const EmittersSeen& emitters_seen,
                 const lightmap::Charts& charts, const lightmap::AtlasLayout& layout,
                 const lightmap::AtlasTexels& texels, const Context& ctx, LightmapCounts& counts,
                 int gather_samples = 0);

} // namespace penumbra::app
