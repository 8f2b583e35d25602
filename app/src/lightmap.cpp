// `penumbra lightmap`: charts and atlases first (bad settings fail before the solve), then the
// radiosity bake, then the texels filled from its solution.

#include "app/lightmap.h"

#include "lightmap_directional.h"
#include "lightmap_emitters.h"
#include "lightmap_fill.h"
#include "lightmap_preview.h"
#include "memory_checks.h"
#include "texel_light.h"

#include <algorithm>
#include <chrono>
#include <memory>
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

// Seam weight: each sample's mismatch counts 10² times a texel's change, so stitching closes
// seams to about a hundredth of their error while moving texels as little as that allows.
constexpr double k_seam_weight = 10;

// Corners this close are one (the charts' own weld tolerance: 10⁻⁶ of the scene's diagonal).
double weld_tolerance(const Scene& scene) {
    const BBox box = scene.bounds();
    return 1e-6 * std::max(length(box.hi - box.lo), 1e-3);
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
    r.options = options;
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
    // One Embree scene for the fill and the preview; its build counts in the fill's time.
    std::unique_ptr<raytrace::EmbreeScene> rt;
    timed(r.times, "fill", [&] {
        rt = std::make_unique<raytrace::EmbreeScene>(bake.mesh);
        const RadiosityMesh& sources = bake.input_mesh ? *bake.input_mesh : bake.mesh;
        const EmittersSeen seen = emitters_seen_by_polygons(bake.mesh, sources, *rt, ctx);
        for (const lightmap::AtlasTexels& atlas : r.texels)
            r.atlases.push_back(fill_atlas(scene, bake.solution, *rt, sources, seen, r.charts,
                                           r.layout, atlas, ctx, r.counts,
                                           r.options.gather_samples));
        r.rays = rt->rays_traced();
        return 0;
    });
    timed(r.times, "seams", [&] {
        const lightmap::Seams found =
            lightmap::find_seams(r.charts, r.layout, weld_tolerance(scene));
        if (r.options.stitch_seams)
            r.seams = lightmap::stitch_seams(r.atlases, found, k_seam_weight);
        else {
            const lightmap::SeamError e = lightmap::seam_error(r.atlases, found.samples);
            r.seams = {found.edges, found.samples.size(), 0, 0, e, e};
        }
        return 0;
    });
    r.directional.clear();
    if (r.options.directional)
        timed(r.times, "directional", [&] {
            const raytrace::EmbreeScene rt(bake.mesh);
            const IncidentLight light(scene, rt, bake.solution, baked_direct_light(scene));
            const EmitterTable emitters = emitter_table(bake.mesh, baked_direct_light(scene));
            const DirectionalInputs in{&light,         &emitters, &rt,
                                       &bake.solution, &r.charts, &r.layout};
            for (std::size_t a = 0; a < r.texels.size(); ++a)
                r.directional.push_back(directional_atlas(in, r.texels[a], r.atlases[a],
                                                          r.layout.padding, ctx.seed, ctx));
            r.rays += rt.rays_traced();
            return 0;
        });
    r.preview.reset();
    if (scene.camera)
        r.preview =
            timed(r.times, "preview", [&] { return render_lightmap_preview(scene, *rt, r, ctx); });
}

LightmapResult bake_lightmaps(const Scene& scene, const LightmapOptions& options,
                              const Context& ctx) {
    LightmapResult r = plan_lightmaps(scene, options, ctx);
    fill_lightmaps(scene, bake(scene, lightmap_bake_options(), ctx), r, ctx);
    return r;
}

} // namespace penumbra::app
