// Light probes from a radiosity solution: gather rays over the sphere plus the delta lights,
// projected onto L2 spherical harmonics and convolved to irradiance.

#include "app/probes.h"

#include "incident_light.h"

#include <bit>
#include <chrono>
#include <cmath>

#include "core/parallel.h"
#include "core/rng.h"

namespace penumbra::app {

namespace {

// The radiance coefficients at \p p: \p n_z bands of stratified gather rays, each standing
// for an equal solid angle, plus every delta light at its exact direction.
lightmap::ShL2 probe_radiance(const IncidentLight& light, const Vec3& p, int n_z,
                              std::uint64_t seed) {
    Pcg32 rng = Pcg32::for_stream(RngPurpose::probe_directions, std::bit_cast<std::uint64_t>(p.x),
                                  std::bit_cast<std::uint64_t>(p.y),
                                  std::bit_cast<std::uint64_t>(p.z), seed);
    const std::vector<Vec3> dirs = stratified_directions(n_z, false, rng);
    const double weight = 4.0 * k_pi / double(dirs.size());
    lightmap::ShL2 radiance;
    for (const Vec3& d : dirs)
        radiance.add(d, light.radiance(p, d), weight);
    for (const DeltaLight& delta : light.deltas(p))
        radiance.add(delta.dir, delta.irradiance, 1.0);
    return radiance;
}

} // namespace

ProbeResult compute_probes(const Scene& scene, const ProbeSettings& settings,
                           const BakeResult& bake, const Context& ctx) {
    const auto start = std::chrono::steady_clock::now();
    ProbeResult r;
    const std::vector<Vec3> positions = settings.positions();
    const int n_z = std::max(1, int(std::ceil(std::sqrt(settings.rays / 2.0))));
    r.rays_per_probe = 2 * n_z * n_z;
    r.probes.resize(positions.size());
    const raytrace::EmbreeScene rt(bake.mesh);
    const IncidentLight light(scene, rt, bake.solution);
    {
        ProgressStage progress(ctx, "light probes");
        run_in_arena(ctx, [&] {
            parallel_for_index(positions.size(), 4, [&](std::size_t i) {
                r.probes[i].position = positions[i];
                r.probes[i].irradiance = lightmap::irradiance_from_radiance(
                    probe_radiance(light, positions[i], n_z, ctx.seed));
            });
        });
    }
    r.rays = rt.rays_traced();
    const std::chrono::duration<double> dt = std::chrono::steady_clock::now() - start;
    r.seconds = dt.count();
    return r;
}

} // namespace penumbra::app
