// The final gather (issue #28; docs/rendering.md): a path tracer whose diffuse bounces read
// the radiosity solution one bounce away from the camera's hits. At every hit: emitted light
// with multiple importance sampling against the light sampling that found it (power
// heuristic, Veach & Guibas 1995); direct light from each source kind with the same MIS
// (point lights and a sun of zero size are deltas: light sampling alone); one BSDF sample
// carries the path on. A ray that leaves a diffuse lobe is a gather ray (GatherMode::
// final_gather): where it meets a Lambertian surface far enough away, the reflected radiance
// (B − E)/π interpolated from the vertex radiosity ends the path; near its origin (corners,
// contact shadows, where interpolated radiosity is worst) the path goes one bounce further.
// Caustics (final_gather only): at every surface with a diffuse part the path meets, the
// caustic photon map's estimate is added, and light that reaches such a surface through
// mirrors, glass or metals alone is not added again by the path (the map counts it).
// Splitting: a camera path's first non-delta surface takes render.light_samples stratified
// light samples and render.gather_rays stratified BSDF samples, each continuing its own path
// from a stream named by the pixel, the camera sample and its index. Pixels where the light
// seen along delta paths (a lamp's rim) varies are sampled again for that light alone, with
// multi-jittered rays (edge_refinement.h). Streams and the row-block schedule are
// render_solution's, so the image does not depend on the thread count.

#include "raytrace/raytrace.h"

#include "camera.h"
#include "edge_refinement.h"
#include "irradiance_cache.h"
#include "path_geometry.h"
#include "photon_map.h"
#include "pixel_strata.h"

#include "core/bsdf.h"
#include "core/error.h"
#include "core/memory.h"
#include "core/parallel.h"
#include "core/rng.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <optional>

namespace penumbra::raytrace {

namespace {

/// Bounces after which Russian roulette may end a path (pbrt's choice).
constexpr int k_roulette_after = 3;
/// A gather hit closer than this many element sizes to its origin continues the path.
constexpr double k_near_gather_sizes = 2.0;
/// Keys of PixelStrata: a camera sample's light picks, light directions and gather rays.
constexpr std::uint64_t k_light_pick_strata = 1, k_light_direction_strata = 2, k_gather_strata = 3;
/// Most multi-jittered samples per axis of a refined edge pixel (as the lightmap preview).
constexpr int k_edge_samples_per_axis = 64;

double power_heuristic(double pdf_a, double pdf_b) {
    const double a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    return a + b > 0 ? a / (a + b) : 0.0;
}

/// What a path remembers of its last scattering for MIS at the next hit.
struct LastScatter {
    bool delta = true;        ///< a delta lobe or the camera: no light sampling competed
    bool only_delta = true;   ///< every scattering since the camera was a delta
    double pdf = 0;           ///< solid-angle density of the BSDF sample
    Vec3 sky_normal{0, 0, 1}; ///< normal about which the sky was cosine-sampled there
    bool gather = false;      ///< the ray left a diffuse lobe and may read the solution
    double near_distance = 0; ///< closer gather hits continue the path
    /// The caustic map's estimate was added at the last surface with a diffuse part, and only
    /// surfaces that pass photons on (passes_photons) scattered the path since: light that
    /// reaches it now is a caustic the map has counted.
    bool after_receiver = false;
    bool through_specular = false; ///< after_receiver and at least one such surface since

    /// Whether light found now along the path is a caustic the map has counted.
    bool caustic() const { return after_receiver && through_specular; }
};

/// Names a camera sample: its split paths draw from streams named by it.
struct SampleId {
    int x = 0, y = 0; ///< the pixel
    int index = 0;    ///< the sample within the pixel
};

/// Where a path stands before its next ray: a camera ray's start, or the first bounce of a
/// texel's gather path.
struct PathState {
    Vec3 origin, dir;
    Rgb beta{1.0f};
    LastScatter last;
    int bounces = 0, diffuse_bounces = 0;
    /// A camera sample's path not split yet: its first non-delta surface splits it.
    std::optional<SampleId> split;
    /// Follows delta lobes only, for the light seen along them (edge refinement).
    bool seen_only = false;
};

/// Radiance a path carries back, in two parts: light met along delta scatterings only from the
/// camera (emitters, the background, the sky and sun seen directly or in mirrors), which makes
/// the sharp edges edge refinement samples again, and all the rest.
struct PathRadiance {
    Rgb seen, rest;

    void add(const LastScatter& last, const Rgb& value) {
        (last.only_delta ? seen : rest) += value;
    }
};

/// The random numbers of one light sample at a vertex: which emitting element and where on it,
/// and a direction's two for the sun's disc and the sky.
struct LightSampleU {
    double pick = 0;
    Vec2 area, dir;

    static LightSampleU random(Pcg32& rng) { return stratified(0, 1, {}, rng); }
    /// Sample \p k of \p count: the element's pick and the direction's first number in stratum
    /// k, each in the fine cell there of the pixel's camera sample (the point on the element
    /// stays independent of the pick, which stratifies the light's elements).
    static LightSampleU stratified(int k, int count, const std::array<PixelStrata, 2>& pixel,
                                   Pcg32& rng) {
        LightSampleU u;
        u.pick = pixel[0].position(k, count, rng.next_double());
        u.area = {rng.next_double(), rng.next_double()};
        u.dir = {pixel[1].position(k, count, rng.next_double()), rng.next_double()};
        return u;
    }
};

class PathTracer {
public:
    /// \p caustics: the photon map of the final gather, null for the other modes.
    /// \p seed: the master seed of the split paths' streams.
    PathTracer(const EmbreeScene& rt, const Scene& scene, const Solution& solution,
               const RenderOptions& options, const CausticMap* caustics, std::uint64_t seed)
        : rt_(rt), mesh_(rt.mesh()), scene_(scene), solution_(solution), options_(options),
          lights_(rt.mesh()), surfaces_(rt, scene), caustics_(caustics), seed_(seed),
          has_glazing_(std::any_of(rt.mesh().patches.begin(), rt.mesh().patches.end(),
                                   [](const Patch& p) { return p.glazing.has_value(); })) {
        if (scene.sun && scene.sun->angular_radius() > 0) {
            sun_cos_max_ = std::cos(scene.sun->angular_radius());
            sun_solid_angle_ = 2.0 * k_pi * (1.0 - sun_cos_max_);
        }
    }

    /// Radiance arriving at the camera along \p ray of camera sample \p id.
    PathRadiance trace(const CameraRay& ray, Pcg32& rng, const SampleId& id) const {
        PathState path;
        path.origin = ray.origin;
        path.dir = ray.direction;
        path.split = id;
        return follow(path, rng);
    }

    /// The light seen along \p ray through delta lobes only (PathRadiance::seen).
    Rgb trace_seen(const CameraRay& ray, Pcg32& rng) const {
        PathState path;
        path.origin = ray.origin;
        path.dir = ray.direction;
        path.seen_only = true;
        return follow(path, rng).seen;
    }

    /// Irradiance (W/m²) at \p s from one light sample per source kind and one path along the
    /// cosine-distributed direction of \p u ∈ [0, 1)²: π times the radiance a white
    /// Lambertian surface there reflects (f = 1/π), so the surface's own material, emission
    /// and lobes play no part.
    Rgb irradiance(const SurfaceHit& s, const Vec2& u, Pcg32& rng) const {
        const Bsdf bsdf(white_, s.shading, TransportMode::radiance);
        const Vec3 wo = s.shading;
        Rgb radiance = direct(bsdf, s, wo, LightSampleU::random(rng));
        const auto sample = bsdf.sample(wo, 0.0, u);
        if (sample && !sample->weight.is_black() &&
            SurfaceGeometry::geometric_side_agrees(s, wo, sample->wi, false)) {
            PathState path;
            path.origin = surfaces_.offset(s, sample->wi);
            path.dir = sample->wi;
            path.beta = sample->weight;
            path.last.delta = path.last.only_delta = false;
            path.last.pdf = sample->pdf;
            path.last.sky_normal = s.shading;
            path.bounces = path.diffuse_bounces = 1;
            path.last.gather = options_.gather == GatherMode::final_gather &&
                               path.diffuse_bounces > options_.gather_depth;
            path.last.near_distance = k_near_gather_sizes * surfaces_.element_size(s.element);
            const PathRadiance carried = follow(path, rng);
            radiance += carried.seen + carried.rest;
        }
        return radiance * float(k_pi);
    }

    /// One of an irradiance record's rays from \p s along \p wi (irradiance_cache.h): the
    /// light a gather ray from a camera path's first diffuse hit brings beyond direct light,
    /// which each camera sample takes itself; and the distance to its first hit.
    RecordRay record_ray(const SurfaceHit& s, const Vec3& wi, Pcg32& rng) const {
        PathState path;
        path.origin = surfaces_.offset(s, wi);
        path.dir = wi;
        path.last.delta = path.last.only_delta = false;
        // A density of 0 gives emitters, the sky and the sun met by this first ray no weight
        // against light sampling (power_heuristic(0, p) = 0): they are direct light.
        path.last.pdf = 0;
        path.last.sky_normal = s.shading;
        path.bounces = path.diffuse_bounces = 1;
        path.last.gather = options_.gather == GatherMode::final_gather && 1 > options_.gather_depth;
        path.last.near_distance = k_near_gather_sizes * surfaces_.element_size(s.element);
        path.last.after_receiver = caustics_ != nullptr; // the record's point receives caustics
        const auto first = rt_.intersect(Vec3f(path.origin), Vec3f(wi), 0.0f, k_infinity);
        const double distance =
            first.front_element < 0 ? std::numeric_limits<double>::infinity() : double(first.t);
        const PathRadiance carried = follow(path, rng);
        return {carried.seen + carried.rest, distance};
    }

    /// Camera paths read \p cache at their first Lambertian hit (null: never).
    void read_cache(const IrradianceCache* cache) { cache_ = cache; }

private:
    /// Radiance arriving along \p path's ray, and what the path scatters on from there.
    PathRadiance follow(PathState path, Pcg32& rng) const {
        PathRadiance out;
        Rgb& radiance = out.rest;
        const Rgb& beta = path.beta;
        const LastScatter& last = path.last;
        for (;;) {
            const Vec3 origin = path.origin, dir = path.dir;
            const auto hit = intersect_through_panes(origin, dir, path.beta);
            if (hit.front_element < 0) {
                if (!last.caustic())
                    out.add(last, beta * escaped(dir, last));
                break;
            }
            const SurfaceHit surface = surfaces_.surface_of(hit, origin, dir);
            const Material& material = surfaces_.material_of(surface.element);
            if (hit.element >= 0) {
                if (!last.caustic())
                    out.add(last, beta * emitted(std::uint32_t(hit.element), hit.t, dir, last));
                if (last.gather && !material.lobe) {
                    if (hit.t >= last.near_distance) {
                        radiance += beta * reflected(hit);
                        break;
                    }
                }
            }
            if (path.bounces++ >= scene_.render.max_bounces)
                break;

            const Bsdf bsdf(material, surface.shading, TransportMode::radiance);
            if (path.seen_only && !bsdf.is_delta())
                break;
            const Vec3 wo = -dir;
            const bool receiver = caustics_ && hit.element >= 0 && receives_photons(material);
            if (receiver)
                radiance += beta * caustics_->radiance(bsdf, surface, wo);
            if (const auto cached = cached_light(hit, surface, bsdf, wo, path, rng)) {
                radiance += beta * *cached;
                break;
            }
            if (path.split && !bsdf.is_delta()) {
                radiance += beta * split(bsdf, surface, material, wo, receiver, path);
                break;
            }
            // Light sampled at a surface that passes photons on, one chosen from a receiver's
            // lobe, reaches that receiver as a caustic.
            if (!bsdf.is_delta() && !(last.after_receiver && passes_photons(material)))
                radiance += beta * direct(bsdf, surface, wo, LightSampleU::random(rng));
            const double u_lobe = rng.next_double();
            const Vec2 u{rng.next_double(), rng.next_double()};
            if (!scatter(path, bsdf, surface, material, wo, receiver, u_lobe, u) ||
                !survives_roulette(path, rng))
                break;
        }
        return out;
    }

    /// A camera path's first non-delta surface (\p path's split): the mean of
    /// render.light_samples stratified light samples, and of render.gather_rays (rounded up to
    /// a square) stratified BSDF samples, each the start of a path with its own stream named by
    /// the camera sample and its index. Radiance toward wo, per unit of the path's throughput.
    Rgb split(const Bsdf& bsdf, const SurfaceHit& s, const Material& material, const Vec3& wo,
              bool receiver, const PathState& path) const {
        Pcg32 stream = split_stream(*path.split);
        const Rgb direct_mean = stratified_direct(bsdf, s, wo, *path.split, stream);
        const PixelStrata pixel = pixel_strata(*path.split, k_gather_strata);
        const int strata = strata_per_axis(scene_.render.gather_rays);
        RgbD carried_sum;
        for (int k = 0; k < strata * strata; ++k) {
            Pcg32 rng = stream;
            rng.advance(std::int64_t(k + 1) << 16);
            PathState child = path;
            child.split.reset();
            child.beta = Rgb(1.0f);
            const double u_lobe = rng.next_double();
            const double jx = rng.next_double(), jy = rng.next_double();
            const Vec2 u = pixel.position(k % strata, k / strata, strata, {jx, jy});
            if (!scatter(child, bsdf, s, material, wo, receiver, u_lobe, u) ||
                !survives_roulette(child, rng))
                continue;
            const PathRadiance carried = follow(child, rng);
            carried_sum += RgbD(carried.seen + carried.rest);
        }
        const double n = double(strata) * double(strata);
        return direct_mean +
               Rgb{float(carried_sum.r / n), float(carried_sum.g / n), float(carried_sum.b / n)};
    }

    /// The stream of a camera sample's split, named by its pixel and index.
    Pcg32 split_stream(const SampleId& id) const {
        return Pcg32::for_stream(RngPurpose::gather_split, std::uint64_t(id.x), std::uint64_t(id.y),
                                 std::uint64_t(id.index), seed_);
    }

    /// Which fine cells of the split's strata camera sample \p id takes (\p kind: light or
    /// gather samples).
    PixelStrata pixel_strata(const SampleId& id, std::uint64_t kind) const {
        return {strata_per_axis(options_.spp), id.index,
                hash_words({std::uint64_t(RngPurpose::gather_split), std::uint64_t(id.x),
                            std::uint64_t(id.y), kind, seed_})};
    }

    /// The mean of render.light_samples stratified light samples drawn from \p stream.
    Rgb stratified_direct(const Bsdf& bsdf, const SurfaceHit& s, const Vec3& wo, const SampleId& id,
                          Pcg32& stream) const {
        const int lights = scene_.render.light_samples;
        const std::array pixel{pixel_strata(id, k_light_pick_strata),
                               pixel_strata(id, k_light_direction_strata)};
        RgbD sum;
        for (int k = 0; k < lights; ++k)
            sum += RgbD(direct(bsdf, s, wo, LightSampleU::stratified(k, lights, pixel, stream)));
        return Rgb{float(sum.r / lights), float(sum.g / lights), float(sum.b / lights)};
    }

    /// Samples \p bsdf at \p s with (u_lobe, u) and moves \p path onto the sampled ray.
    /// Returns false where the sample ends the path.
    bool scatter(PathState& path, const Bsdf& bsdf, const SurfaceHit& s, const Material& material,
                 const Vec3& wo, bool receiver, double u_lobe, const Vec2& u) const {
        const auto sample = bsdf.sample(wo, u_lobe, u);
        if (!sample || sample->weight.is_black() ||
            !SurfaceGeometry::geometric_side_agrees(s, wo, sample->wi, sample->transmission()))
            return false;
        LastScatter& last = path.last;
        path.beta = path.beta * sample->weight;
        last.delta = sample->delta();
        last.only_delta = last.only_delta && last.delta;
        last.pdf = sample->pdf;
        last.sky_normal = SurfaceGeometry::facing(s.shading, wo);
        last.through_specular = !receiver && last.after_receiver && passes_photons(material);
        last.after_receiver = receiver || last.through_specular;
        if (sample->lobe == BsdfLobe::diffuse)
            ++path.diffuse_bounces;
        last.gather = options_.gather == GatherMode::final_gather &&
                      sample->lobe == BsdfLobe::diffuse &&
                      path.diffuse_bounces > options_.gather_depth;
        last.near_distance = k_near_gather_sizes * surfaces_.element_size(s.element);
        path.origin = surfaces_.offset(s, sample->wi);
        path.dir = sample->wi;
        return true;
    }

    /// Russian roulette after k_roulette_after bounces: ends the path with probability
    /// 1 − max(throughput), else scales the throughput up by it.
    static bool survives_roulette(PathState& path, Pcg32& rng) {
        if (path.bounces < k_roulette_after)
            return true;
        const float keep = std::min(1.0f, path.beta.max_component());
        if (!(rng.next_float() < keep))
            return false;
        path.beta = path.beta / keep;
        return true;
    }

    /// At a camera path's first diffuse hit, on a Lambertian surface where a record of the
    /// cache is valid: ρ/π times the cached indirect irradiance, direct light (the split's
    /// stratified samples, or one), and the emitted light of one BSDF sample (its half of
    /// direct light's MIS). None elsewhere: the path goes on and gathers.
    std::optional<Rgb> cached_light(const EmbreeScene::Hit& hit, const SurfaceHit& s,
                                    const Bsdf& bsdf, const Vec3& wo, const PathState& path,
                                    Pcg32& rng) const {
        const Material& material = surfaces_.material_of(s.element);
        if (!cache_ || hit.element < 0 || path.diffuse_bounces > 0 || !cacheable(material))
            return std::nullopt;
        const auto irradiance = cache_->irradiance(s.p, s.shading);
        if (!irradiance)
            return std::nullopt;
        Rgb light = material.reflectance * *irradiance * float(k_inv_pi);
        if (path.split) {
            Pcg32 stream = split_stream(*path.split);
            light += stratified_direct(bsdf, s, wo, *path.split, stream);
        } else {
            light += direct(bsdf, s, wo, LightSampleU::random(rng));
        }
        const Vec2 u{rng.next_double(), rng.next_double()};
        const auto sample = bsdf.sample(wo, 0.0, u);
        if (!sample || sample->weight.is_black() ||
            !SurfaceGeometry::geometric_side_agrees(s, wo, sample->wi, false))
            return light;
        LastScatter last;
        last.delta = last.only_delta = false;
        last.pdf = sample->pdf;
        last.sky_normal = SurfaceGeometry::facing(s.shading, wo);
        Rgb weight = sample->weight;
        const auto next =
            intersect_through_panes(surfaces_.offset(s, sample->wi), sample->wi, weight);
        if (next.front_element < 0)
            return light + weight * escaped(sample->wi, last);
        if (next.element >= 0)
            light += weight * emitted(std::uint32_t(next.element), next.t, sample->wi, last);
        return light;
    }

    /// Fraction of the light that passes from \p from along unit \p dir over \p distance
    /// (panes of glazing attenuate, opaque surfaces block).
    float transmittance(const Vec3& from, const Vec3& dir, double distance) const {
        const float reach =
            std::isinf(distance) ? k_infinity : float(distance - 2.0 * surfaces_.offset_distance());
        if (!(reach > 0))
            return 1.0f;
        return segment_transmittance(rt_, {Vec3f(from), Vec3f(dir), 0.0f, reach}, has_glazing_);
    }

    /// The first opaque hit of the ray from \p origin along \p dir; \p beta takes the
    /// transmittance of the panes of glazing crossed before it (or on the way out of the
    /// scene), as shadow rays count them: intersect() sees through panes.
    EmbreeScene::Hit intersect_through_panes(const Vec3& origin, const Vec3& dir, Rgb& beta) const {
        const auto hit = rt_.intersect(Vec3f(origin), Vec3f(dir), 0.0f, k_infinity);
        if (has_glazing_) {
            const double distance =
                hit.front_element < 0 ? std::numeric_limits<double>::infinity() : double(hit.t);
            beta = beta * transmittance(origin, dir, distance);
        }
        return hit;
    }

    /// Emitted radiance of \p element toward -dir, weighted against area-light sampling.
    Rgb emitted(std::uint32_t element, float t, const Vec3& dir, const LastScatter& last) const {
        const Patch& patch = mesh_.patch_of(element);
        if (patch.emission.is_black())
            return {};
        const Rgb le = patch.emission * float(k_inv_pi);
        if (last.delta)
            return le;
        const double cos_light = std::abs(dot(dir, patch.normal));
        const double light_pdf = lights_.probability(element) * double(t) * double(t) /
                                 (mesh_.element_area[element] * cos_light);
        return le * float(power_heuristic(last.pdf, light_pdf));
    }

    /// The diffuse radiance the solution gives at a hit, without the emitted part:
    /// (B − E)/π, B interpolated from the vertices of the element hit.
    Rgb reflected(const EmbreeScene::Hit& hit) const {
        const auto& tri = mesh_.triangles[std::uint32_t(hit.element)];
        const auto& b = solution_.vertex_radiosity;
        const Rgb& b0 = b[tri[0]];
        const Rgb value = b0 + (b[tri[1]] - b0) * hit.u + (b[tri[2]] - b0) * hit.v -
                          mesh_.patch_of(std::uint32_t(hit.element)).emission;
        return Rgb{std::max(0.0f, value.r), std::max(0.0f, value.g), std::max(0.0f, value.b)} *
               float(k_inv_pi);
    }

    /// What a ray that leaves the scene sees: the sky and the sun's disc, weighted against
    /// their light sampling; the background only along delta paths from the camera (it lights
    /// nothing).
    Rgb escaped(const Vec3& dir, const LastScatter& last) const {
        Rgb l;
        if (scene_.sky) {
            const double sky_pdf = std::max(0.0, dot(dir, last.sky_normal)) * k_inv_pi;
            const double w = last.delta ? 1.0 : power_heuristic(last.pdf, sky_pdf);
            l += scene_.sky->radiance(dir) * float(w);
        } else if (last.only_delta) {
            l += scene_.background;
        }
        if (sun_solid_angle_ > 0 && dot(dir, scene_.sun->direction) >= sun_cos_max_) {
            const double w = last.delta ? 1.0 : power_heuristic(last.pdf, 1.0 / sun_solid_angle_);
            l += scene_.sun->irradiance * float(w / sun_solid_angle_);
        }
        return l;
    }

    /// eval() of the (reflecting) non-delta lobes, 0 where wi leaves through the surface.
    static Rgb reflect(const Bsdf& bsdf, const SurfaceHit& s, const Vec3& wo, const Vec3& wi) {
        return SurfaceGeometry::geometric_side_agrees(s, wo, wi, false) ? bsdf.eval(wo, wi) : Rgb{};
    }

    /// Direct light at a non-delta BSDF from every source.
    Rgb direct(const Bsdf& bsdf, const SurfaceHit& s, const Vec3& wo, const LightSampleU& u) const {
        Rgb sum;
        if (!lights_.empty())
            sum += area_light(bsdf, s, wo, u);
        for (const PointLight& light : scene_.point_lights)
            sum += point_light(light, bsdf, s, wo);
        if (scene_.sun)
            sum += sun_light(bsdf, s, wo, u.dir);
        if (scene_.sky)
            sum += sky_light(bsdf, s, wo, u.dir);
        return sum;
    }

    Rgb area_light(const Bsdf& bsdf, const SurfaceHit& s, const Vec3& wo,
                   const LightSampleU& u) const {
        const std::uint32_t element = lights_.pick(u.pick);
        const Vec3 point = uniform_point_on(mesh_, element, u.area.x, u.area.y);
        const Vec3 to_light = point - s.p;
        const double dist2 = dot(to_light, to_light), dist = std::sqrt(dist2);
        if (!(dist > 0))
            return {};
        const Vec3 wi = to_light / dist;
        const Patch& patch = mesh_.patch_of(element);
        const double cos_light = -dot(wi, patch.normal);
        if (!(cos_light > 0))
            return {};
        const Rgb f = reflect(bsdf, s, wo, wi);
        if (f.is_black())
            return {};
        const double light_pdf =
            lights_.probability(element) * dist2 / (mesh_.element_area[element] * cos_light);
        const float t = transmittance(surfaces_.offset(s, wi), wi, dist);
        if (t == 0)
            return {};
        const double w = power_heuristic(light_pdf, bsdf.pdf(wo, wi));
        return f * patch.emission * float(k_inv_pi * t * w / light_pdf);
    }

    Rgb point_light(const PointLight& light, const Bsdf& bsdf, const SurfaceHit& s,
                    const Vec3& wo) const {
        const Vec3 to_light = light.position - s.p;
        const double dist2 = dot(to_light, to_light), dist = std::sqrt(dist2);
        if (!(dist > 0))
            return {};
        const Vec3 wi = to_light / dist;
        const double profile = light.profile(-wi);
        const Rgb f = reflect(bsdf, s, wo, wi);
        if (profile <= 0 || f.is_black())
            return {};
        const float t = transmittance(surfaces_.offset(s, wi), wi, dist);
        return f * light.intensity * float(profile * t / dist2);
    }

    Rgb sun_light(const Bsdf& bsdf, const SurfaceHit& s, const Vec3& wo, const Vec2& u) const {
        const Sun& sun = *scene_.sun;
        const double u1 = u.x, u2 = u.y;
        if (sun_solid_angle_ <= 0) {
            const Rgb f = reflect(bsdf, s, wo, sun.direction);
            if (f.is_black())
                return {};
            return f * sun.irradiance *
                   transmittance(surfaces_.offset(s, sun.direction), sun.direction,
                                 std::numeric_limits<double>::infinity());
        }
        const Vec3 wi =
            Frame::from_normal(sun.direction).to_world(uniform_cone(sun_cos_max_, u1, u2));
        const Rgb f = reflect(bsdf, s, wo, wi);
        if (f.is_black())
            return {};
        const float t =
            transmittance(surfaces_.offset(s, wi), wi, std::numeric_limits<double>::infinity());
        const double light_pdf = 1.0 / sun_solid_angle_;
        const double w = power_heuristic(light_pdf, bsdf.pdf(wo, wi));
        // L / pdf = (E_n / Ω) / (1 / Ω) = E_n.
        return f * sun.irradiance * float(t * w);
    }

    Rgb sky_light(const Bsdf& bsdf, const SurfaceHit& s, const Vec3& wo, const Vec2& u) const {
        const Vec3 normal = SurfaceGeometry::facing(s.shading, wo);
        const double u1 = u.x, u2 = u.y;
        const Vec3 wi = Frame::from_normal(normal).to_world(cosine_hemisphere(u1, u2));
        const double light_pdf = std::max(0.0, dot(wi, normal)) * k_inv_pi;
        const Rgb f = reflect(bsdf, s, wo, wi);
        if (!(light_pdf > 0) || f.is_black())
            return {};
        const float t =
            transmittance(surfaces_.offset(s, wi), wi, std::numeric_limits<double>::infinity());
        if (t == 0)
            return {};
        const double w = power_heuristic(light_pdf, bsdf.pdf(wo, wi));
        return f * scene_.sky->radiance(wi) * float(t * w / light_pdf);
    }

    const EmbreeScene& rt_;
    const RadiosityMesh& mesh_;
    const Scene& scene_;
    const Solution& solution_;
    const RenderOptions& options_;
    AreaLights lights_;
    SurfaceGeometry surfaces_;
    const CausticMap* caustics_ = nullptr;
    const IrradianceCache* cache_ = nullptr;
    std::uint64_t seed_ = 0;
    Material white_{"white", Rgb(1.0f)}; ///< the texels' gather surface: f = 1/π
    bool has_glazing_ = false;
    double sun_cos_max_ = 1, sun_solid_angle_ = 0;
};

/// What a pixel's first samples give: the filter-weighted means of the two parts of the
/// radiance (PathRadiance), and the least and greatest seen part over the samples.
struct FirstSamples {
    RgbD seen, rest;
    Rgb seen_low, seen_high;
};
static_assert(
    sizeof(FirstSamples) + sizeof(Rgb) <= k_render_bytes_per_pixel,
    "the render's memory estimate (core/memory.h) counts the first samples and the image");

/// The largest channel range of the seen part over the samples of pixel (x, y) and its eight
/// neighbours together (rows of \p width): an edge between two pixels shows even at one sample
/// each, and a rim that only clips a pixel's corner may miss its samples but not theirs. The
/// neighbours alone would keep a pixel's own rare hit (the lamp seen through cornell-spheres'
/// glass in one sample of sixteen: a firefly); its own samples alone would keep the pixel
/// exactly when they missed a small bright feature (−17 % in such a tile at 1 spp).
double seen_range_around(std::span<const FirstSamples> first, int width, int height, int x, int y) {
    constexpr float inf = std::numeric_limits<float>::infinity();
    Rgb low{inf, inf, inf}, high{-inf, -inf, -inf};
    for (int v = std::max(y - 1, 0); v <= std::min(y + 1, height - 1); ++v)
        for (int u = std::max(x - 1, 0); u <= std::min(x + 1, width - 1); ++u) {
            const FirstSamples& f = first[std::size_t(v) * std::size_t(width) + std::size_t(u)];
            for (int c = 0; c < 3; ++c) {
                low[c] = std::min(low[c], f.seen_low[c]);
                high[c] = std::max(high[c], f.seen_high[c]);
            }
        }
    return std::max({double(high.r - low.r), double(high.g - low.g), double(high.b - low.b)});
}

/// One pixel: stratified samples over the filter's footprint, each with its own stream; where
/// edge refinement asks, the seen part again from multi-jittered rays.
struct PixelSampler {
    const PathTracer& tracer;
    ThinLensCamera camera;
    int strata = 1;
    PixelFilter filter = PixelFilter::box;
    double filter_width = 1;
    EdgeRefinement edges;
    std::uint64_t seed = 0;

    /// Weight of an offset (dx, dy) from the pixel's centre, pixels: a Gaussian of standard
    /// deviation a sixth of the footprint (pbrt's default of radius 1.5, σ = 0.5).
    double weight(double dx, double dy) const {
        if (filter == PixelFilter::box)
            return 1.0;
        const double sigma = filter_width / 6.0;
        return std::exp(-(dx * dx + dy * dy) / (2.0 * sigma * sigma));
    }

    FirstSamples first(int x, int y) const {
        const Pcg32 stream = Pcg32::for_stream(RngPurpose::pixel_sample, std::uint64_t(x),
                                               std::uint64_t(y), 0, seed);
        constexpr float inf = std::numeric_limits<float>::infinity();
        FirstSamples out;
        Rgb &low = out.seen_low, &high = out.seen_high;
        low = {inf, inf, inf};
        high = {-inf, -inf, -inf};
        double weights = 0;
        for (int k = 0; k < strata * strata; ++k) {
            Pcg32 rng = stream;
            rng.advance(std::int64_t(k) << 16);
            const double dx = ((k % strata + rng.next_double()) / strata - 0.5) * filter_width;
            const double dy = ((k / strata + rng.next_double()) / strata - 0.5) * filter_width;
            const double lu = rng.next_double(), lv = rng.next_double();
            const CameraRay ray = camera.ray(x + 0.5 + dx, y + 0.5 + dy, lu, lv);
            const double w = weight(dx, dy);
            const PathRadiance r = tracer.trace(ray, rng, SampleId{x, y, k});
            out.seen += RgbD(r.seen) * w;
            out.rest += RgbD(r.rest) * w;
            weights += w;
            for (int c = 0; c < 3; ++c) {
                low[c] = std::min(low[c], r.seen[c]);
                high[c] = std::max(high[c], r.seen[c]);
            }
        }
        out.seen = out.seen * (1.0 / weights);
        out.rest = out.rest * (1.0 / weights);
        return out;
    }

    /// The seen part of pixel (x, y) from n² multi-jittered rays over the filter's footprint,
    /// from the pixel's own stream.
    RgbD seen_refined(int x, int y, int n) const {
        Pcg32 rng = Pcg32::for_stream(RngPurpose::pixel_sample, std::uint64_t(x), std::uint64_t(y),
                                      1, seed);
        RgbD sum;
        double weights = 0;
        for (const Vec2& p : multi_jittered(n, rng)) {
            const double dx = (p.x - 0.5) * filter_width, dy = (p.y - 0.5) * filter_width;
            const double lu = rng.next_double(), lv = rng.next_double();
            const double w = weight(dx, dy);
            sum += RgbD(tracer.trace_seen(camera.ray(x + 0.5 + dx, y + 0.5 + dy, lu, lv), rng)) * w;
            weights += w;
        }
        return sum * (1.0 / weights);
    }

    /// The pixel from its first samples, its seen part refined where the seen range \p around
    /// it asks for more samples than the first.
    Rgb pixel(const FirstSamples& first, double around, int x, int y) const {
        const int n = refined_strata(around, edges);
        const RgbD seen = n > strata ? seen_refined(x, y, n) : first.seen;
        const RgbD sum = seen + first.rest;
        return {float(sum.r), float(sum.g), float(sum.b)};
    }
};

/// The irradiance cache of \p camera's view when \p options ask for it (final mode).
std::optional<IrradianceCache> place_records(const PathTracer& tracer, const EmbreeScene& rt,
                                             const Scene& scene, const Camera& camera,
                                             const RenderOptions& options, const Context& ctx) {
    if (!options.irradiance_cache || options.gather != GatherMode::final_gather)
        return std::nullopt;
    return build_irradiance_cache(
        rt, SurfaceGeometry(rt, scene), make_camera(camera), *options.irradiance_cache,
        [&](const SurfaceHit& s, const Vec3& wi, Pcg32& rng) {
            return tracer.record_ray(s, wi, rng);
        },
        ctx);
}

/// Runs pixel(x, y) over \p width × \p height in row blocks, rows in parallel; each pixel is
/// written by the task that owns its row.
template <typename Pixel>
void for_each_pixel(int width, int height, const Context& ctx, const char* stage_name,
                    const Pixel& pixel) {
    ProgressStage stage(ctx, stage_name);
    run_in_arena(ctx, [&] {
        // Row blocks run one after another so that progress is reported from this thread only.
        const int rows_per_block = std::max(4, 2 * thread_count(ctx));
        for (int y0 = 0; y0 < height; y0 += rows_per_block) {
            const int y1 = std::min(height, y0 + rows_per_block);
            parallel_for(blocked_range<int>(y0, y1, 1), [&](const blocked_range<int>& rows) {
                for (int y = rows.begin(); y != rows.end(); ++y)
                    for (int x = 0; x < width; ++x)
                        pixel(x, y);
            });
            stage.update(double(y1) / height);
        }
    });
}

void check_options(const RenderOptions& options, const Solution& solution,
                   const RadiosityMesh& mesh) {
    if (options.spp < 1)
        throw ConfigError(fmt::format("render: spp {} must be at least 1", options.spp));
    if (options.gather_depth < 0)
        throw ConfigError(
            fmt::format("render: gather depth {} must be at least 0", options.gather_depth));
    if (options.gather != GatherMode::none &&
        solution.vertex_radiosity.size() != mesh.vertex_count())
        throw InternalError(
            fmt::format("render_final_gather: {} vertex radiosities for {} vertices",
                        solution.vertex_radiosity.size(), mesh.vertex_count()));
}

} // namespace

Image render_final_gather(const EmbreeScene& rt, const Scene& scene, const Solution& solution,
                          const Camera& camera, const RenderOptions& options, const Context& ctx) {
    check_options(options, solution, rt.mesh());
    Camera sampled = camera;
    sampled.samples_per_pixel = options.spp;
    if (options.gather == GatherMode::radiosity)
        return render_solution(rt, solution, sampled, ctx);

    std::optional<CausticMap> caustics;
    if (options.gather == GatherMode::final_gather)
        caustics.emplace(shoot_caustic_photons(rt, scene, ctx));
    PathTracer tracer(rt, scene, solution, options,
                      caustics && !caustics->empty() ? &*caustics : nullptr, ctx.seed);
    const std::optional<IrradianceCache> cache =
        place_records(tracer, rt, scene, sampled, options, ctx);
    tracer.read_cache(cache ? &*cache : nullptr);
    const PixelSampler sampler{tracer,
                               make_thin_lens(sampled),
                               strata_per_axis(options.spp),
                               scene.render.pixel_filter,
                               scene.render.filter_width_px,
                               EdgeRefinement{scene.render.edge_tolerance, k_edge_samples_per_axis},
                               ctx.seed};
    const int width = camera.width, height = camera.height;
    const auto index = [&](int x, int y) {
        return std::size_t(y) * std::size_t(width) + std::size_t(x);
    };
    std::vector<FirstSamples> first(std::size_t(width) * std::size_t(height));
    const std::uint64_t rays_before = rt.rays_traced();
    for_each_pixel(width, height, ctx, "render",
                   [&](int x, int y) { first[index(x, y)] = sampler.first(x, y); });
    Image image(width, height);
    for_each_pixel(width, height, ctx, "render edges", [&](int x, int y) {
        image.at(x, y) =
            sampler.pixel(first[index(x, y)], seen_range_around(first, width, height, x, y), x, y);
    });
    ctx.debug("render ({} gather): {}x{} pixels, {} samples each, {} rays",
              enum_name(options.gather), image.width, image.height, sampler.strata * sampler.strata,
              rt.rays_traced() - rays_before);
    return image;
}

namespace {

// Names a point's gather stream by its coordinates and normal: the same point draws the same
// paths whichever batch or thread gathers it.
std::uint64_t point_stream_id(const Vec3& p, const Vec3& n) {
    const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
    return hash_words({bits(p.x), bits(p.y), bits(p.z), bits(n.x), bits(n.y), bits(n.z)});
}

} // namespace

std::vector<Rgb> gather_irradiance_at(const EmbreeScene& rt, const Scene& scene,
                                      const Solution& solution, std::span<const Vec3> points,
                                      std::span<const Vec3> normals, int samples,
                                      const Context& ctx) {
    if (points.size() != normals.size())
        throw InternalError("gather_irradiance_at: points and normals differ in number");
    if (samples < 1)
        throw ConfigError(fmt::format("gather: {} samples, expected at least 1", samples));
    RenderOptions options;
    options.gather = GatherMode::final_gather;
    check_options(options, solution, rt.mesh());
    const PathTracer tracer(rt, scene, solution, options, nullptr, ctx.seed);
    const SurfaceGeometry surfaces(rt, scene);
    const int strata = strata_per_axis(samples);
    // The surface under a point: a short ray down its normal, as the lightmap fill finds it.
    const double height = 1e-4 * std::max(rt.mesh().scene_diagonal, 1e-3);
    std::vector<Rgb> out(points.size());
    run_in_arena(ctx, [&] {
        parallel_for_index(points.size(), 4, [&](std::size_t i) {
            const Vec3 from = points[i] + normals[i] * height;
            const auto hit = rt.intersect(Vec3f(from), Vec3f(-normals[i]), 0.0f, float(2 * height));
            if (hit.element < 0)
                return;
            const SurfaceHit s = surfaces.surface_of(hit, from, -normals[i]);
            const Pcg32 stream = Pcg32::for_stream(
                RngPurpose::texel_paths, point_stream_id(points[i], normals[i]), 0, 0, ctx.seed);
            RgbD sum;
            for (int k = 0; k < strata * strata; ++k) {
                Pcg32 rng = stream;
                rng.advance(std::int64_t(k) << 16);
                const Vec2 u{(k % strata + rng.next_double()) / strata,
                             (k / strata + rng.next_double()) / strata};
                sum += RgbD(tracer.irradiance(s, u, rng));
            }
            const double n = double(strata) * double(strata);
            out[i] = Rgb(float(sum.r / n), float(sum.g / n), float(sum.b / n));
        });
    });
    return out;
}

} // namespace penumbra::raytrace
