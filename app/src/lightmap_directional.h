#pragma once
// Directional lightmaps (issue #29): per texel the L1 spherical harmonics (lightmap/sh.h) of
// the radiance arriving at its footprint. docs/lightmaps.md gives the convention and layout.

#include <array>
#include <cstdint>
#include <vector>

#include "incident_light.h"
#include "lightmap_fill.h"

#include "core/image.h"
#include "lightmap/sh.h"

namespace penumbra::app {

/// \brief The emitting elements of a mesh, picked for light samples in proportion to power.
struct EmitterTable {
    const RadiosityMesh* mesh = nullptr;
    std::vector<std::uint32_t> elements; ///< the emitting ones, in mesh order
    std::vector<double> cdf;             ///< per emitting element: running share of the power
    std::vector<double> probability_of;  ///< per mesh element: its share (0: emits nothing)
};

/// \brief The emitting elements of \p mesh (kept by reference): the mesh the gather rays
///        trace, so that a ray's hit names its element's light-sample density. Without those
///        \p direct excludes (by their polygon's AreaSource: mixed lighting).
EmitterTable emitter_table(const RadiosityMesh& mesh,
                           const solver::DirectLightOptions& direct = {});

/// \brief What the directional fill reads; every pointer set, everything outliving the call.
struct DirectionalInputs {
    const IncidentLight* light = nullptr;
    const EmitterTable* emitters = nullptr;
    const raytrace::EmbreeScene* rt = nullptr; ///< over the mesh \p solution lives on
    const Solution* solution = nullptr;
    const lightmap::Charts* charts = nullptr;
    const lightmap::AtlasLayout* layout = nullptr;
    const RadiosityMesh& light_mesh() const { return rt->mesh(); }
};

/// \brief The L1 atlases of \p texels: images of L00, L1−1, L10 and L11 (RGB each; the SH
///        convention of lightmap/sh.h, world axes), where band 1 is the projection of the
///        radiance arriving over the texel's visible samples (each sample's: 8 stratified
///        gather rays over its hemisphere reading B/π or the sky, 8 light samples on the
///        emitting elements picked by power, the two combined for emitted light by multiple
///        importance sampling, and the delta lights) and L00 makes
///        π L00 Y00 + (2π/3) Σ L1m Y1m(n) equal \p irradiance (the non-directional atlas) at
///        the texel's normal n. Texels with no visible sample get L1 = 0. Dilated as the
///        irradiance atlas is. Each sample draws from a stream named by its position
///        (RngPurpose::texel_gather): the same bits for any thread count.
std::array<Image, 4> directional_atlas(const DirectionalInputs& in,
                                       const lightmap::AtlasTexels& texels, const Image& irradiance,
                                       int padding, std::uint64_t seed, const Context& ctx);

} // namespace penumbra::app
