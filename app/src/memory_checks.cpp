#include "memory_checks.h"

#include <algorithm>

#include <fmt/format.h>

#include "core/memory.h"

namespace penumbra::app {

void check_render_memory(const Scene& scene, const Context& ctx) {
    if (!scene.camera)
        return;
    const double pixels = double(scene.camera->width) * double(scene.camera->height);
    check_memory(
        ctx,
        fmt::format("render: an image of {}x{} pixels", scene.camera->width, scene.camera->height),
        pixels * double(k_render_bytes_per_pixel), "use a smaller image.width and image.height");
}

void check_coefficient_memory(std::size_t roots, std::size_t sensors, std::size_t patches,
                              std::size_t sun_bins, const Context& ctx) {
    const double entries =
        double(roots) * double(patches) + double(sensors) * double(2 * patches + sun_bins);
    check_memory(ctx,
                 fmt::format("daylight coefficients: {} elements and {} sensors by {} sky "
                             "patches and {} sun bins",
                             roots, sensors, patches, sun_bins),
                 entries * sizeof(float),
                 "use fewer sky patches (--patches) or sun bins (--sun-bins), or a larger "
                 "--max-edge");
}

void check_hourly_memory(std::size_t sensors, std::size_t patches, std::size_t hours,
                         const Context& ctx) {
    const double entries =
        double(hours) * (double(patches) + double(k_hourly_matrices) * double(sensors));
    check_memory(
        ctx,
        fmt::format("annual: {} sensors and {} sky patches by {} hours", sensors, patches, hours),
        entries * sizeof(float), "use fewer sensors or sky patches (--patches)");
}

void check_lightmap_charts(const lightmap::Charts& charts, const lightmap::AtlasSettings& settings,
                           const Context& ctx) {
    const double density = settings.texels_per_metre * settings.texels_per_metre;
    const double atlas = double(settings.size) * double(settings.size);
    double texels = 0;
    for (const lightmap::Chart& chart : charts.charts)
        texels += std::min(chart.area_m2() * density, atlas); // larger ones are scaled to fit
    check_memory(ctx,
                 fmt::format("lightmap: {} charts at {:g} texels per metre (at least {:.3g} "
                             "texels)",
                             charts.charts.size(), settings.texels_per_metre, texels),
                 texels * double(k_lightmap_bytes_per_texel + k_lightmap_bytes_per_covered_texel),
                 "use fewer texels per metre (--texels-per-metre) or a smaller --atlas");
}

void check_lightmap_memory(const lightmap::AtlasLayout& layout, const Context& ctx) {
    const double texels = double(layout.size) * double(layout.size);
    double bytes = 0;
    for (const double coverage : layout.coverage)
        bytes += texels * (double(k_lightmap_bytes_per_texel) +
                           coverage * double(k_lightmap_bytes_per_covered_texel));
    check_memory(ctx,
                 fmt::format("lightmap: {} atlases of {}² texels", layout.atlas_count, layout.size),
                 bytes, "use fewer texels per metre (--texels-per-metre) or a smaller --atlas");
}

} // namespace penumbra::app
