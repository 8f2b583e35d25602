// `penumbra lightmap`: charts and atlases first (bad settings fail before the solve), then the
// radiosity bake, then the texels filled from its solution.

#include "app/lightmap.h"

#include "lightmap_fill.h"
#include "memory_checks.h"

#include <chrono>
#include <utility>

#include "lightmap/texels.h"
#include "raytrace/raytrace.h"

namespace penumbra::app {

namespace {

// Runs \p fn and appends its wall time to \p times under \p stage.
template <typename Fn>
decltype(auto) timed(std::vector<StageTime>& times, const char* stage, Fn&& fn) {
    const auto start = std::chrono::steady_clock::now();
    decltype(auto) out = fn();
    const std::chrono::duration<double> dt = std::chrono::steady_clock::now() - start;
    times.push_back({stage, dt.count()});
    return out;
}

} // namespace

LightmapResult plan_lightmaps(const Scene& scene, const LightmapOptions& options,
                              const Context& ctx) {
    LightmapResult r;
    r.charts = timed(r.times, "charts",
                     [&] { return lightmap::build_charts(scene, lightmap::ChartSettings{}, ctx); });
    check_lightmap_charts(r.charts, options.atlas, ctx);
    r.layout = timed(r.times, "packing",
                     [&] { return lightmap::pack_atlases(r.charts, options.atlas, ctx); });
    check_lightmap_memory(r.layout, ctx);
    r.texels =
        timed(r.times, "texels", [&] { return lightmap::rasterize(r.charts, r.layout, ctx); });
    r.samples_per_texel = k_texel_samples_per_axis * k_texel_samples_per_axis;
    return r;
}

BakeOptions lightmap_bake_options() {
    BakeOptions options;
    options.render = false;
    options.keep_state = false;
    options.keep_input_mesh = true;
    return options;
}

void fill_lightmaps(const Scene& scene, const BakeResult& bake, LightmapResult& r,
                    const Context& ctx) {
    double bake_seconds = 0;
    for (const StageTime& t : bake.times)
        bake_seconds += t.seconds;
    r.times.push_back({"bake", bake_seconds});
    r.atlases.clear();
    r.counts = {};
    timed(r.times, "fill", [&] {
        const raytrace::EmbreeScene rt(bake.mesh);
        const RadiosityMesh& sources = bake.input_mesh ? *bake.input_mesh : bake.mesh;
        for (const lightmap::AtlasTexels& atlas : r.texels)
            r.atlases.push_back(fill_atlas(scene, bake.solution, rt, sources, r.charts, r.layout,
                                           atlas, ctx, r.counts));
        r.rays = rt.rays_traced();
        return 0;
    });
}

LightmapResult bake_lightmaps(const Scene& scene, const LightmapOptions& options,
                              const Context& ctx) {
    LightmapResult r = plan_lightmaps(scene, options, ctx);
    fill_lightmaps(scene, bake(scene, lightmap_bake_options(), ctx), r, ctx);
    return r;
}

} // namespace penumbra::app
