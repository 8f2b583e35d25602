// Sensor evaluation at the points themselves: direct light gathered from the sources, and
// indirect light gathered from every element's reflected radiosity B − E, both with analytic
// point-to-triangle form factors and visibility rays (no interpolation of mesh values).

#include "solver/solver.h"

#include "core/parallel.h"
#include "output/point_gather.h"
#include "output/vertex_values.h"

namespace penumbra::solver {

std::vector<SensorReading> evaluate_sensors(const Scene& scene, const RadiosityMesh& mesh,
                                            const Solution& solution,
                                            const VisibilityQuery& visibility, const Context& ctx) {
    std::vector<SensorReading> readings(scene.sensors.size());
    if (readings.empty())
        return readings;
    return run_in_arena(ctx, [&] {
        ElementGeometry geo(mesh);
        std::vector<Rgb> emission(mesh.element_count()), reflected(mesh.element_count());
        for (std::size_t e = 0; e < mesh.element_count(); ++e) {
            emission[e] = mesh.patch_of(std::uint32_t(e)).emission;
            reflected[e] = solution.radiosity[e] - emission[e];
        }
        const GatherSources sources = direct_sources(scene, emission);
        const int rays = scene.solver.visibility_rays;
        ProgressStage progress(ctx, "sensors");
        parallel_for_index(readings.size(), 1, [&](std::size_t s) {
            const Sensor& sensor = scene.sensors[s];
            GatherPoint p{sensor.position, sensor.normal, s, RngPurpose::sensor_visibility};
            SensorReading& r = readings[s];
            r.irradiance_direct = gather_direct(geo, sources, visibility, p, rays, ctx.seed);
            r.irradiance_total = r.irradiance_direct +
                                 gather_elements(geo, reflected, visibility, p, rays, ctx.seed);
            r.illuminance_direct_lx = to_photometric(r.irradiance_direct);
            r.illuminance_total_lx = to_photometric(r.irradiance_total);
        });
        progress.update(1.0);
        return readings;
    });
}

} // namespace penumbra::solver
