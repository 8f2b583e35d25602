#pragma once
// What a lightmap texel sample receives (issue #29). Mixed lighting: per light, its
// `lightmap_mode` says whether the lightmaps hold all of its light or only its indirect part
// (the engine draws the direct part in real time); the solution's indirect light keeps every
// light's bounces, only the direct gathers leave the indirect-only lights out. `--gather`:
// the final gather's paths instead of direct light + the solution's indirect light.

#include <span>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/context.h"
#include "core/light.h"
#include "core/mesh.h"
#include "core/scene.h"
#include "raytrace/raytrace.h"
#include "solver/solver.h"

namespace penumbra::app {

/// \brief The lightmap mode of \p source in \p scene (an area source's: its material's).
LightmapMode lightmap_mode_of(const Scene& scene, const LightSource& source);

/// \brief Whether some light of \p scene bakes only its indirect light.
bool has_indirect_only_light(const Scene& scene);

/// \brief The direct gather's options for the fill: leave out the lights whose mode is
///        indirect; every source (no predicate) when none is.
solver::DirectLightOptions baked_direct_light(const Scene& scene);

/// \brief lightmaps.json's `lights`: per light (point lights by name, "sun", "sky", emitting
///        materials by name) its kind and mode.
nlohmann::json lightmap_modes_json(const Scene& scene);

/// \brief What the fill reads at texel samples; everything outliving the call.
struct TexelLightSources {
    const Scene& scene;
    const Solution& solution;
    const raytrace::EmbreeScene& rt; ///< over the mesh \p solution lives on
    const RadiosityMesh& emitters;   ///< whose emitting elements give direct light
    /// Per input polygon, the emitting elements of \p emitters it may see (all when empty).
    std::span<const std::vector<std::uint32_t>> emitters_seen;
    int gather_samples = 0; ///< > 0: `--gather` with this many paths per sample
};

/// \brief The light at texel samples (\p points facing \p normals, on \p polygons) that the
///        fill adds to the
///        solution's indirect irradiance: the direct irradiance of the lights whose mode is
///        all (solver::direct_irradiance_at from the emitters in.emitters_seen lists). With
///        in.gather_samples > 0 the whole irradiance instead (raytrace::gather_irradiance_at), less
///        the direct light of the indirect-only lights gathered as above (clamped at 0): then
///        adds_solution_indirect() is false.
std::vector<Rgb> texel_sample_light(const TexelLightSources& in, std::span<const Vec3> points,
                                    std::span<const Vec3> normals,
                                    std::span<const std::uint32_t> polygons, const Context& ctx);

/// \brief Whether texel_sample_light()'s values still need the solution's indirect light.
inline bool adds_solution_indirect(const TexelLightSources& in) {
    return in.gather_samples <= 0;
}

} // namespace penumbra::app
