#pragma once
// Light probes (issue #29): L2 spherical-harmonic irradiance at the points of the scene's
// `probes` key, gathered from a bake's radiosity solution, written as probes.json and
// probes.vtp. The SH convention is lightmap/sh.h's; docs/lightmaps.md describes the method.

#include <cstdint>
#include <string>
#include <vector>

#include "app/pipeline.h"
#include "core/context.h"
#include "core/scene.h"
#include "lightmap/sh.h"

namespace penumbra::app {

/// \brief One probe: its position and the SH coefficients of its irradiance, so that
///        irradiance.evaluate(n) is the irradiance (W/m², RGB) on a surface facing n there.
struct Probe {
    Vec3 position;
    lightmap::ShL2 irradiance;
};

struct ProbeResult {
    std::vector<Probe> probes; ///< ProbeSettings::positions() order
    int rays_per_probe = 0;    ///< gather rays (ProbeSettings::rays rounded up to 2 n²)
    std::uint64_t rays = 0;    ///< traced in all, shadow rays included
    double seconds = 0;
};

/// \brief The probes of \p settings from \p bake, a bake of \p scene: per probe, incident
///        radiance on stratified random directions over the sphere (each the radiance of
///        the surface it meets, B/π, or the sky's) and the point lights, spots and sun as
///        deltas from their exact directions (shadow rays), projected onto bands 0–2 and
///        convolved with the clamped cosine (Ramamoorthi & Hanrahan 2001). Each probe's
///        directions come from a stream named by its position (RngPurpose::probe_directions):
///        bitwise the same for any thread count.
ProbeResult compute_probes(const Scene& scene, const ProbeSettings& settings,
                           const BakeResult& bake, const Context& ctx);

/// \brief Writes probes.json (the convention, then per probe its position and nine RGB
///        irradiance coefficients) and probes.vtp (VTK points: sh_0 … sh_8 and
///        irradiance_mean, RGB W/m²) into \p dir, atomically. Throws ExternalError/ConfigError.
void write_probes(const std::string& dir, const Scene& scene, const ProbeResult& result);

} // namespace penumbra::app
