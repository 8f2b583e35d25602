// Directional lightmaps (issue #29): per texel the L1 spherical harmonics of the radiance
// arriving at its footprint, from the solution's reflected light (gather rays), the emitting
// surfaces (light samples), the sky (rays that leave) and the delta lights (exact directions).

#include "lightmap_directional.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/parallel.h"
#include "core/rng.h"

namespace penumbra::app {

using lightmap::ShL2;
using lightmap::Texel;

namespace {

// Gather rays per visible sample: 2 bands × 4 sectors of the hemisphere (72 per texel wholly
// on its chart), and as many light samples on the emitting elements, picked by power; the two
// estimates of emitted light are combined by multiple importance sampling (power heuristic).
constexpr int k_gather_bands = 2;
constexpr int k_gather_rays = 2 * k_gather_bands * k_gather_bands;
constexpr int k_light_samples = 8;
constexpr double k_gather_pdf = 1.0 / (2.0 * k_pi); // uniform over the hemisphere, per sr

// A random point on triangle \p v (uniform by area).
Vec3 point_on_triangle(const std::array<Vec3, 3>& v, double r1, double r2) {
    const double s = std::sqrt(r1);
    return v[0] * (1 - s) + v[1] * (s * (1 - r2)) + v[2] * (s * r2);
}

// Density (per sr) of a light sample toward \p e at distance \p d and cosine \p cos_light.
double light_pdf(const EmitterTable& emitters, std::uint32_t e, double d, double cos_light) {
    return emitters.probability_of[e] * d * d / (emitters.mesh->element_area[e] * cos_light);
}

// The power heuristic's weight of a technique with \p n samples at density \p pdf against
// the other's.
double power_heuristic(int n, double pdf, int n_other, double pdf_other) {
    const double a = n * pdf, b = n_other * pdf_other;
    return a * a / (a * a + b * b);
}

// Adds to \p sh the emitting elements' radiance seen from \p origin (facing \p normal): light
// samples picked in proportion to power, each weighted by the solid angle it stands for and
// its share against the gather rays.
void add_light_samples(const EmitterTable& emitters, const IncidentLight& light, const Vec3& origin,
                       const Vec3& normal, Pcg32& rng, double weight, ShL2& sh) {
    if (emitters.elements.empty())
        return;
    const RadiosityMesh& mesh = *emitters.mesh;
    for (int k = 0; k < k_light_samples; ++k) {
        const auto pick = std::size_t(
            std::upper_bound(emitters.cdf.begin(), emitters.cdf.end(), rng.next_double()) -
            emitters.cdf.begin());
        const std::uint32_t e = emitters.elements[std::min(pick, emitters.elements.size() - 1)];
        const auto& t = mesh.triangles[e];
        const Vec3 y = point_on_triangle({mesh.vertex(t[0]), mesh.vertex(t[1]), mesh.vertex(t[2])},
                                         rng.next_double(), rng.next_double());
        const double d = length(y - origin);
        const Vec3 dir = (y - origin) / d;
        const double cos_light = -dot(dir, mesh.patch_of(e).normal);
        if (!(d > 0) || cos_light <= 0 || dot(dir, normal) <= 0)
            continue;
        const float visible = light.transmittance(origin, dir, float(d - 2 * light.ray_offset()));
        if (visible <= 0)
            continue;
        const double pdf = light_pdf(emitters, e, d, cos_light);
        const double mis = power_heuristic(k_light_samples, pdf, k_gather_rays, k_gather_pdf);
        sh.add(dir, RgbD(mesh.patch_of(e).emission) * (k_inv_pi * double(visible)),
               weight * mis / (k_light_samples * pdf));
    }
}

// The radiance coefficients of one visible sample at \p point (facing \p normal), weighted by
// \p weight (1 / the texel's visible samples).
void add_sample(const DirectionalInputs& in, const Vec3& point, const Vec3& normal, double weight,
                std::uint64_t seed, ShL2& sh) {
    const Vec3 origin = point + normal * in.light->ray_offset();
    Pcg32 rng = Pcg32::for_stream(RngPurpose::texel_gather, std::bit_cast<std::uint64_t>(point.x),
                                  std::bit_cast<std::uint64_t>(point.y),
                                  std::bit_cast<std::uint64_t>(point.z), seed);
    const Frame frame = Frame::from_normal(normal);
    const RadiosityMesh& mesh = in.light_mesh();
    for (const Vec3& local : stratified_directions(k_gather_bands, true, rng)) {
        const Vec3 dir = frame.to_world(local);
        const RayLight l = in.light->trace(origin, dir);
        RgbD radiance = l.reflected;
        if (l.element >= 0 && l.emitted.max_component() > 0) {
            const auto e = std::uint32_t(l.element);
            const double cos_light = std::abs(dot(dir, mesh.patch_of(e).normal));
            const double pdf =
                cos_light > 0 ? light_pdf(*in.emitters, e, l.distance, cos_light) : 0.0;
            radiance +=
                l.emitted * power_heuristic(k_gather_rays, k_gather_pdf, k_light_samples, pdf);
        }
        sh.add(dir, radiance, weight / (k_gather_rays * k_gather_pdf));
    }
    add_light_samples(*in.emitters, *in.light, origin, normal, rng, weight, sh);
    for (const DeltaLight& delta : in.light->deltas(origin))
        if (dot(delta.dir, normal) > 0)
            sh.add(delta.dir, delta.irradiance, weight);
}

// L00 and L1 of one texel: L1 as gathered; L00 such that π L00 Y00 + (2π/3) Σ L1m Y1m(n) at
// the texel's normal n is its irradiance \p e exactly, as the non-directional atlas has it.
std::array<RgbD, 4> texel_coefficients(const ShL2& radiance, const Vec3& normal, const RgbD& e) {
    const auto y = lightmap::sh_basis_l2(normal);
    RgbD band1;
    for (std::size_t k = 1; k < 4; ++k)
        band1 += radiance.c[k] * y[k];
    const double a1 = lightmap::sh_cosine_lobe_band(1), a0 = lightmap::sh_cosine_lobe_band(0);
    return {(e - band1 * a1) * (1.0 / (a0 * y[0])), radiance.c[1], radiance.c[2], radiance.c[3]};
}

} // namespace

EmitterTable emitter_table(const RadiosityMesh& mesh, const solver::DirectLightOptions& direct) {
    EmitterTable t;
    t.mesh = &mesh;
    t.probability_of.assign(mesh.element_count(), 0.0);
    double total = 0;
    for (std::uint32_t e = 0; e < mesh.element_count(); ++e) {
        const double power = RgbD(mesh.patch_of(e).emission).sum() * mesh.element_area[e];
        if (power <= 0 || (direct.include && !direct.include(AreaSource{mesh.patch_of(e).polygon})))
            continue;
        t.elements.push_back(e);
        t.probability_of[e] = power;
        total += power;
    }
    double running = 0;
    for (std::uint32_t e : t.elements) {
        running += t.probability_of[e];
        t.cdf.push_back(running / total);
        t.probability_of[e] /= total;
    }
    return t;
}

std::array<Image, 4> directional_atlas(const DirectionalInputs& in,
                                       const lightmap::AtlasTexels& texels, const Image& irradiance,
                                       int padding, std::uint64_t seed, const Context& ctx) {
    std::array<Image, 4> out;
    for (Image& image : out)
        image = Image(texels.size, texels.size);
    constexpr int n = k_texel_samples_per_axis;
    const double height = probe_height(in.light_mesh());
    ProgressStage progress(ctx, "directional texels");
    run_in_arena(ctx, [&] {
        parallel_for_index(texels.texels.size(), 16, [&](std::size_t i) {
            const Texel& texel = texels.texels[i];
            const lightmap::Chart& chart = in.charts->charts[texel.chart];
            const auto samples = lightmap::texel_samples(chart, in.layout->placements[texel.chart],
                                                         texels, texel, n);
            std::vector<std::pair<Vec3, Vec3>> visible;
            for (const lightmap::SurfacePoint& s : samples)
                if (const auto found = locate_sample(*in.rt, *in.solution, s,
                                                     chart.triangles[s.triangle].polygon, height))
                    visible.emplace_back(found->gather_point, s.normal);
            ShL2 radiance;
            for (const auto& [point, normal] : visible)
                add_sample(in, point, normal, 1.0 / double(visible.size()), seed, radiance);
            const auto c = texel_coefficients(radiance, texel.centre.normal,
                                              RgbD(irradiance.at(texel.x, texel.y)));
            for (std::size_t k = 0; k < 4; ++k)
                out[k].at(texel.x, texel.y) = Rgb(float(c[k].r), float(c[k].g), float(c[k].b));
        });
    });
    const std::vector<std::uint8_t> covered = lightmap::coverage_mask(texels);
    for (Image& image : out)
        lightmap::dilate(image, covered, padding);
    return out;
}

} // namespace penumbra::app
