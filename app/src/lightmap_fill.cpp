#include "lightmap_fill.h"

#include "texel_light.h"

#include <algorithm>
#include <array>
#include <optional>
#include <vector>

#include "core/parallel.h"
#include "solver/solver.h"

namespace penumbra::app {

using lightmap::AtlasTexels;
using lightmap::SurfacePoint;
using lightmap::Texel;

namespace {

// Texels per batch of samples handed to the direct gather: bounds the memory of the sample
// arrays and gives the progress bar its steps.
constexpr std::size_t k_batch_texels = 1 << 15;

// The point at barycentrics \p w of triangle \p v, pulled at least \p inset inside each edge
// (the map onto the inner triangle whose edges lie \p inset in): the rays of a sample at a
// wall's foot then start on the sample's own side of the wall. Tiny elements: the centroid.
Vec3 inset_point(const std::array<Vec3, 3>& v, const Vec3& w, double inset) {
    const double twice_area = length(cross(v[1] - v[0], v[2] - v[0]));
    std::array<double, 3> least{};
    double sum = 0;
    for (int k = 0; k < 3; ++k) {
        const double edge = length(v[std::size_t(k + 2) % 3] - v[std::size_t(k + 1) % 3]);
        least[std::size_t(k)] = edge > 0 ? inset * edge / twice_area : 1.0;
        sum += least[std::size_t(k)];
    }
    if (!(sum < 1))
        return (v[0] + v[1] + v[2]) / 3.0;
    const double keep = 1 - sum;
    return v[0] * (least[0] + keep * w.x) + v[1] * (least[1] + keep * w.y) +
           v[2] * (least[2] + keep * w.z);
}

// One batch of texels' samples, k_texel_samples_per_axis² slots per texel.
struct SampleBatch {
    std::vector<std::uint8_t> count;    ///< per texel: its samples on the chart
    std::vector<std::uint8_t> visible;  ///< per slot: on its polygon's own element
    std::vector<Vec3> point, normal;    ///< per slot: gather point and normal
    std::vector<std::uint32_t> polygon; ///< per slot: the input polygon it lies on
    std::vector<Rgb> indirect;          ///< per slot
};

SampleBatch locate_batch(const Solution& solution, const raytrace::EmbreeScene& rt,
                         const lightmap::Charts& charts, const lightmap::AtlasLayout& layout,
                         const AtlasTexels& texels, std::size_t begin, std::size_t end) {
    constexpr int n = k_texel_samples_per_axis;
    constexpr std::size_t slots = std::size_t(n * n);
    const double height = probe_height(rt.mesh());
    SampleBatch b;
    b.count.assign(end - begin, 0);
    b.visible.assign((end - begin) * slots, 0);
    b.point.resize(b.visible.size());
    b.normal.resize(b.visible.size());
    b.polygon.resize(b.visible.size());
    b.indirect.resize(b.visible.size());
    parallel_for_index(end - begin, 64, [&](std::size_t k) {
        const Texel& texel = texels.texels[begin + k];
        const lightmap::Chart& chart = charts.charts[texel.chart];
        const std::vector<SurfacePoint> samples =
            lightmap::texel_samples(chart, layout.placements[texel.chart], texels, texel, n);
        b.count[k] = std::uint8_t(samples.size());
        for (std::size_t i = 0; i < samples.size(); ++i) {
            const SurfacePoint& s = samples[i];
            const auto found =
                locate_sample(rt, solution, s, chart.triangles[s.triangle].polygon, height);
            if (!found)
                continue;
            const std::size_t slot = k * slots + i;
            b.visible[slot] = 1;
            b.point[slot] = found->gather_point;
            b.normal[slot] = s.normal;
            b.polygon[slot] = chart.triangles[s.triangle].polygon;
            b.indirect[slot] = found->indirect;
        }
    });
    return b;
}

// The light at the batch's visible samples (in slot order: texel_sample_light, plus the
// solution's indirect light unless it is the final gather's), then each texel's mean;
// marks the texels with a value in \p valued and counts into \p stats.
void fill_batch(const TexelLightSources& light, const AtlasTexels& texels, std::size_t begin,
                const SampleBatch& b, const Context& ctx, Image& image,
                std::vector<std::uint8_t>& valued, LightmapCounts& stats) {
    constexpr std::size_t slots = std::size_t(k_texel_samples_per_axis * k_texel_samples_per_axis);
    std::vector<Vec3> points, normals;
    std::vector<std::uint32_t> polygons;
    for (std::size_t slot = 0; slot < b.visible.size(); ++slot)
        if (b.visible[slot]) {
            points.push_back(b.point[slot]);
            normals.push_back(b.normal[slot]);
            polygons.push_back(b.polygon[slot]);
        }
    const std::vector<Rgb> direct = texel_sample_light(light, points, normals, polygons, ctx);
    std::size_t next = 0;
    for (std::size_t k = 0; k < b.count.size(); ++k) {
        RgbD sum;
        std::size_t visible = 0;
        for (std::size_t i = 0; i < b.count[k]; ++i) {
            const std::size_t slot = k * slots + i;
            if (!b.visible[slot])
                continue;
            sum += RgbD(adds_solution_indirect(light) ? direct[next++] + b.indirect[slot]
                                                      : direct[next++]);
            ++visible;
        }
        stats.samples += b.count[k];
        stats.hidden_samples += b.count[k] - visible;
        if (visible == 0)
            continue;
        const Texel& t = texels.texels[begin + k];
        const RgbD mean = sum * (1.0 / double(visible));
        image.at(t.x, t.y) = Rgb(float(mean.r), float(mean.g), float(mean.b));
        valued[std::size_t(t.y) * std::size_t(texels.size) + std::size_t(t.x)] = 1;
    }
}

// Texels without a visible sample take, pass by pass, the mean of their valued 8-neighbours
// of the same chart (each pass reads the previous pass's values): a hidden strip under a wall
// takes its chart's light from either side, never another chart's. Returns the texels left
// without a value (a chart hidden everywhere).
std::size_t grow_into_hidden(const AtlasTexels& texels, Image& image,
                             std::vector<std::uint8_t>& valued) {
    const auto size = std::size_t(texels.size);
    std::vector<std::int64_t> chart_at(size * size, -1);
    std::vector<std::size_t> hidden;
    for (std::size_t i = 0; i < texels.texels.size(); ++i) {
        const Texel& t = texels.texels[i];
        const std::size_t at = std::size_t(t.y) * size + std::size_t(t.x);
        chart_at[at] = t.chart;
        if (!valued[at])
            hidden.push_back(i);
    }
    std::vector<std::pair<std::size_t, Rgb>> grown;
    std::vector<std::size_t> still;
    while (!hidden.empty()) {
        grown.clear();
        still.clear();
        for (std::size_t i : hidden) {
            const Texel& t = texels.texels[i];
            RgbD sum;
            int count = 0;
            for (int y = std::max(t.y - 1, 0); y <= std::min(t.y + 1, texels.size - 1); ++y)
                for (int x = std::max(t.x - 1, 0); x <= std::min(t.x + 1, texels.size - 1); ++x) {
                    const std::size_t at = std::size_t(y) * size + std::size_t(x);
                    if (valued[at] && chart_at[at] == std::int64_t(t.chart)) {
                        sum += RgbD(image.at(x, y));
                        ++count;
                    }
                }
            if (count == 0) {
                still.push_back(i);
                continue;
            }
            const RgbD mean = sum * (1.0 / count);
            grown.emplace_back(i, Rgb(float(mean.r), float(mean.g), float(mean.b)));
        }
        if (grown.empty())
            break;
        for (const auto& [i, value] : grown) {
            const Texel& t = texels.texels[i];
            image.at(t.x, t.y) = value;
            valued[std::size_t(t.y) * size + std::size_t(t.x)] = 1;
        }
        hidden.swap(still);
    }
    return hidden.size();
}

} // namespace

// How far above a sample its probe ray starts, and how far inside its element it gathers
// direct light: 10 of the solver's ray offsets (10⁻⁵ of the scene's diagonal), the inset of
// the vertices' own gathers on their surfaces' boundaries.
double probe_height(const RadiosityMesh& mesh) {
    return 1e-4 * std::max(mesh.scene_diagonal, 1e-3);
}

// The element under sample \p s, found by a short ray down its normal from \p height above
// it; nothing unless that element belongs to \p polygon's front side: else the sample lies on
// a hidden or covered part (under a wall, inside a contact), where the mesher made no elements.
std::optional<MeshSample> locate_sample(const raytrace::EmbreeScene& rt, const Solution& solution,
                                        const SurfacePoint& s, std::uint32_t polygon,
                                        double height) {
    const RadiosityMesh& mesh = rt.mesh();
    const raytrace::EmbreeScene::Hit hit = rt.intersect(Vec3f(s.position + s.normal * height),
                                                        Vec3f(-s.normal), 0.0f, float(2 * height));
    if (hit.element < 0)
        return std::nullopt;
    const auto e = std::uint32_t(hit.element);
    const Patch& patch = mesh.patch_of(e);
    if (patch.polygon != polygon || patch.back || dot(patch.normal, s.normal) < 1.0 - 1e-3)
        return std::nullopt;
    const auto& t = mesh.triangles[e];
    const Vec3 w{1.0 - double(hit.u) - double(hit.v), double(hit.u), double(hit.v)};
    const std::vector<Rgb>& indirect = solution.vertex_irradiance_indirect;
    MeshSample out;
    out.indirect =
        indirect[t[0]] * float(w.x) + indirect[t[1]] * float(w.y) + indirect[t[2]] * float(w.z);
    out.gather_point =
        inset_point({mesh.vertex(t[0]), mesh.vertex(t[1]), mesh.vertex(t[2])}, w, height);
    return out;
}

Image fill_atlas(const Scene& scene, const Solution& solution, const raytrace::EmbreeScene& rt,
                 const RadiosityMesh& sources, const EmittersSeen& emitters_seen,
                 const lightmap::Charts& charts, const lightmap::AtlasLayout& layout,
                 const lightmap::AtlasTexels& texels, const Context& ctx, LightmapCounts& counts,
                 int gather_samples) {
    const TexelLightSources light{scene, solution, rt, sources, emitters_seen, gather_samples};
    Image image(texels.size, texels.size);
    std::vector<std::uint8_t> valued(image.pixels.size(), 0);
    LightmapCounts own;
    own.texels = texels.texels.size();
    {
        ProgressStage progress(ctx, "lightmap texels");
        for (std::size_t begin = 0; begin < texels.texels.size(); begin += k_batch_texels) {
            const std::size_t end = std::min(texels.texels.size(), begin + k_batch_texels);
            const SampleBatch batch = run_in_arena(ctx, [&] {
                return locate_batch(solution, rt, charts, layout, texels, begin, end);
            });
            fill_batch(light, texels, begin, batch, ctx, image, valued, own);
            progress.update(double(end) / double(texels.texels.size()));
        }
    }
    own.hidden_texels = std::size_t(std::count(valued.begin(), valued.end(), 0)) -
                        (image.pixels.size() - own.texels);
    own.unlit_texels = grow_into_hidden(texels, image, valued);
    lightmap::dilate(image, lightmap::coverage_mask(texels), layout.padding);
    counts.texels += own.texels;
    counts.samples += own.samples;
    counts.hidden_samples += own.hidden_samples;
    counts.hidden_texels += own.hidden_texels;
    counts.unlit_texels += own.unlit_texels;
    return image;
}

} // namespace penumbra::app
