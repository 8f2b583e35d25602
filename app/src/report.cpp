// Text outputs of a bake: summary.json and sensors.csv (with the daylight factor when the
// scene has a sky).

#include <cmath>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/pipeline.h"

#include "daylight.h"

namespace penumbra::app {

namespace {

nlohmann::json rgb_json(const RgbD& c) {
    return {{"rgb_w", {c.r, c.g, c.b}}, {"lm", to_photometric(c)}};
}

nlohmann::json balance_json(const solver::PowerBalance& pb, bool distant_sources) {
    nlohmann::json j;
    j["emitted"] = rgb_json(pb.emitted);
    j["absorbed"] = rgb_json(pb.absorbed);
    j["escaped"] = rgb_json(pb.escaped);
    j["glazing"] = rgb_json(pb.glazing);
    j["residual_unshot"] = rgb_json(pb.residual);
    j["relative_imbalance"] = pb.relative_imbalance();
    std::string note =
        "emitted = absorbed + escaped + glazing + residual_unshot + imbalance; escaped (through "
        "openings, and through glazing its transmittance) is estimated by its own rays; glazing "
        "is what panes absorb and reflect of the light reaching them from inside; imbalance is "
        "discretisation and sampling error";
    if (distant_sources)
        note += "; the share of emitted of the sun and the sky is the power their direct light "
                "delivers to the scene's surfaces (sum of E_direct * A), none of which escapes";
    j["note"] = note;
    return j;
}

} // namespace

std::string summary_json(const Scene& scene, const BakeResult& result) {
    nlohmann::json j;
    j["scene"] = scene.name;
    j["scene_file"] = scene.file;
    j["elements"] = result.mesh.element_count();
    j["vertices"] = result.mesh.vertex_count();
    j["patches"] = result.mesh.patches.size();
    j["input_polygons"] = scene.polygons.size();
    j["rays_traced"] = result.rays;
    j["solver"] = {{"method", enum_name(scene.solver.method)},
                   {"shots_or_sweeps", result.stats.shots},
                   {"links", result.stats.links},
                   {"epsilon", scene.solver.epsilon},
                   {"residual_target", scene.solver.residual},
                   {"residual_history", result.stats.residual_history}};
    nlohmann::json times = nlohmann::json::object();
    double total = 0;
    for (const StageTime& t : result.times) {
        times[t.stage] = t.seconds;
        total += t.seconds;
    }
    times["total"] = total;
    j["seconds"] = times;
    j["power_balance"] =
        balance_json(result.stats.power, scene.sun.has_value() || scene.sky.has_value());
    return j.dump(2) + "\n";
}

std::string render_json(const Scene& scene, const BakeResult& result) {
    nlohmann::json j;
    j["scene"] = scene.name;
    j["scene_file"] = scene.file;
    j["gather"] = enum_name(result.render_options.gather);
    j["gather_depth"] = result.render_options.gather_depth;
    j["irradiance_cache"] = result.render_options.irradiance_cache.has_value();
    j["spp"] = result.render_options.spp;
    j["width"] = result.render ? result.render->width : 0;
    j["height"] = result.render ? result.render->height : 0;
    j["elements"] = result.mesh.element_count();
    nlohmann::json times = nlohmann::json::object();
    double total = 0, render_seconds = 0;
    for (const StageTime& t : result.times) {
        times[t.stage] = t.seconds;
        total += t.seconds;
        if (t.stage == "render")
            render_seconds = t.seconds;
    }
    times["total"] = total;
    j["seconds"] = times;
    j["render_rays"] = result.render_rays;
    j["render_rays_per_second"] =
        render_seconds > 0 ? double(result.render_rays) / render_seconds : 0.0;
    return j.dump(2) + "\n";
}

std::string sensors_csv(const Scene& scene, const BakeResult& result) {
    const std::optional<double> reference_lx = daylight_reference_lx(scene);
    std::string out =
        "name,x,y,z,nx,ny,nz,direct_r_w_m2,direct_g_w_m2,direct_b_w_m2,"
        "total_r_w_m2,total_g_w_m2,total_b_w_m2,illuminance_direct_lx,illuminance_total_lx";
    out += reference_lx ? ",daylight_factor_pct\n" : "\n";
    for (std::size_t i = 0; i < scene.sensors.size(); ++i) {
        const Sensor& s = scene.sensors[i];
        const solver::SensorReading& r = result.sensors[i];
        out += fmt::format("{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},"
                           "{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}",
                           s.name.empty() ? fmt::format("s{}", i) : s.name, s.position.x,
                           s.position.y, s.position.z, s.normal.x, s.normal.y, s.normal.z,
                           r.irradiance_direct.r, r.irradiance_direct.g, r.irradiance_direct.b,
                           r.irradiance_total.r, r.irradiance_total.g, r.irradiance_total.b,
                           r.illuminance_direct_lx, r.illuminance_total_lx);
        out += reference_lx ? fmt::format(",{:.6g}\n", 100 * r.illuminance_total_lx / *reference_lx)
                            : "\n";
    }
    return out;
}

} // namespace penumbra::app
