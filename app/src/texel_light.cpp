#include "texel_light.h"

#include <algorithm>
#include <string>
#include <type_traits>
#include <variant>

namespace penumbra::app {

namespace {

bool emits(const Material& m) {
    return !m.emission.is_black() || m.emission_flux_lm.has_value();
}

} // namespace

LightmapMode lightmap_mode_of(const Scene& scene, const LightSource& source) {
    return std::visit(
        [&](const auto& s) {
            using S = std::decay_t<decltype(s)>;
            if constexpr (std::is_same_v<S, AreaSource>)
                // A hand-made mesh's patches may name no scene polygon: those bake all.
                return s.polygon < scene.polygons.size()
                           ? scene.materials[scene.polygons[s.polygon].material].lightmap_mode
                           : LightmapMode::all;
            else if constexpr (std::is_same_v<S, PointSource>)
                return scene.point_lights[s.index].lightmap_mode;
            else if constexpr (std::is_same_v<S, SunSource>)
                return scene.sun ? scene.sun->lightmap_mode : LightmapMode::all;
            else
                return scene.sky ? scene.sky->lightmap_mode : LightmapMode::all;
        },
        source);
}

bool has_indirect_only_light(const Scene& scene) {
    for (const PointLight& light : scene.point_lights)
        if (light.lightmap_mode == LightmapMode::indirect)
            return true;
    for (const Material& m : scene.materials)
        if (emits(m) && m.lightmap_mode == LightmapMode::indirect)
            return true;
    return lightmap_mode_of(scene, SunSource{}) == LightmapMode::indirect ||
           lightmap_mode_of(scene, SkySource{}) == LightmapMode::indirect;
}

solver::DirectLightOptions baked_direct_light(const Scene& scene) {
    solver::DirectLightOptions options;
    if (has_indirect_only_light(scene))
        options.include = [&scene](const LightSource& source) {
            return lightmap_mode_of(scene, source) == LightmapMode::all;
        };
    return options;
}

std::vector<Rgb> texel_sample_light(const TexelLightSources& in, std::span<const Vec3> points,
                                    std::span<const Vec3> normals,
                                    std::span<const std::uint32_t> polygons, const Context& ctx) {
    const auto direct = [&](solver::DirectLightOptions options) {
        if (!in.emitters_seen.empty()) {
            options.list_of_point = polygons;
            options.emitter_lists = in.emitters_seen;
        }
        return solver::direct_irradiance_at(in.scene, in.emitters, in.rt, points, normals, ctx,
                                            options);
    };
    if (adds_solution_indirect(in))
        return direct(baked_direct_light(in.scene));
    std::vector<Rgb> light = raytrace::gather_irradiance_at(in.rt, in.scene, in.solution, points,
                                                            normals, in.gather_samples, ctx);
    if (!has_indirect_only_light(in.scene))
        return light;
    solver::DirectLightOptions live;
    live.include = [&](const LightSource& source) {
        return lightmap_mode_of(in.scene, source) == LightmapMode::indirect;
    };
    const std::vector<Rgb> drawn_live = direct(std::move(live));
    for (std::size_t i = 0; i < light.size(); ++i)
        for (int c = 0; c < 3; ++c)
            light[i][c] = std::max(0.0f, light[i][c] - drawn_live[i][c]);
    return light;
}

nlohmann::json lightmap_modes_json(const Scene& scene) {
    nlohmann::json out = nlohmann::json::array();
    const auto add = [&](const std::string& kind, const std::string& name, LightmapMode mode) {
        out.push_back({{"kind", kind}, {"name", name}, {"mode", std::string(enum_name(mode))}});
    };
    for (const PointLight& light : scene.point_lights)
        add(light.spot ? "spot" : "point", light.name, light.lightmap_mode);
    for (const Material& m : scene.materials)
        if (emits(m))
            add("material", m.name, m.lightmap_mode);
    if (scene.sun)
        add("sun", "sun", scene.sun->lightmap_mode);
    if (scene.sky)
        add("sky", "sky", scene.sky->lightmap_mode);
    return out;
}

} // namespace penumbra::app
