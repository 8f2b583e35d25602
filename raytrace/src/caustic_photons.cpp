// Caustic photons (Jensen 1996; docs/rendering.md): shot from every source toward the
// surfaces that pass light on (mirrors, glass, metals: passes_photons), traced through them
// with their BSDFs in importance mode, and stored where they first land on a surface with a
// diffuse part after at least one such bounce (L S+ D paths). Photons that land on a diffuse
// surface first are dropped: the final gather finds that light itself.
//
// Every photon draws from its own stream named by its index; batches of a fixed size are
// traced in parallel and appended in index order, and the count is checked only between
// batches, so the photons do not depend on the thread count.

#include "raytrace/raytrace.h"

#include "path_geometry.h"

#include "core/bsdf.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/rng.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <variant>

namespace penumbra::raytrace {

namespace {

/// Photons traced between two checks of the stored count.
constexpr std::size_t k_batch = 8192;
/// At most this many photons shot per photon asked for (scenes whose caustics are rare).
constexpr std::uint64_t k_max_shot_per_stored = 64;
/// Largest radius of the nearest-photon estimate, relative to the scene's diagonal.
constexpr double k_max_radius_of_diagonal = 0.05;
/// Bounces after which Russian roulette may end a photon.
constexpr int k_roulette_after = 3;

/// A sphere around every surface that passes photons on: photons from a source are aimed at
/// it (Jensen's projection maps), since no other photon makes a caustic.
struct Target {
    Vec3 centre;
    double radius = 0;
};

std::optional<Target> specular_target(const RadiosityMesh& mesh, const Scene& scene) {
    BBox box;
    for (std::uint32_t e = 0; e < mesh.element_count(); ++e) {
        if (!passes_photons(scene.materials[mesh.patch_of(e).material]))
            continue;
        for (std::uint32_t v : mesh.triangles[e])
            box.extend(mesh.vertex(v));
    }
    if (box.empty())
        return std::nullopt;
    return Target{(box.lo + box.hi) * 0.5, 0.5 * length(box.hi - box.lo) * (1 + 1e-6)};
}

/// One kind of source: the emitting elements, a point light, the sun, the sky.
struct AreaKind {};
struct PointKind {
    std::uint32_t index;
};
struct SunKind {};
struct SkyKind {};
using SourceKind = std::variant<AreaKind, PointKind, SunKind, SkyKind>;

/// A photon leaving its source: where, which way, and its flux per shot photon, W (per unit
/// of the element's exitance, m², for the elements as sources of their reflected light).
struct Emission {
    Vec3 origin, dir;
    Rgb power;
    std::uint32_t element = 0; ///< the emitting element it left, if it left one
};

/// The sources, chosen in proportion to their power (toward the target for the sun and the
/// sky, whose photons all leave a disc facing it).
class PhotonSources {
public:
    /// \p offset: how far off an emitting element its photons start (not to meet it).
    /// \p exitance: empty for the scene's sources, else the elements alone, chosen by this
    /// exitance (W/m²), each photon carrying its power per unit of exitance.
    PhotonSources(const RadiosityMesh& mesh, const Scene& scene, const Target& target,
                  double offset, std::span<const Rgb> exitance)
        : mesh_(mesh), scene_(scene), target_(target), lights_(mesh, exitance), offset_(offset),
          exitance_(exitance) {
        if (!lights_.empty())
            add(AreaKind{}, lights_.power());
        if (!exitance.empty()) {
            for (double& c : cdf_)
                c /= total_;
            return;
        }
        for (std::uint32_t i = 0; i < scene.point_lights.size(); ++i) {
            const RgbD power = scene.point_lights[i].power();
            add(PointKind{i}, (power.r + power.g + power.b) / 3.0);
        }
        const double disc = k_pi * target.radius * target.radius;
        if (scene.sun)
            add(SunKind{}, channel_mean(scene.sun->irradiance) * disc);
        if (scene.sky)
            add(SkyKind{}, sky_radiance_integral() * disc);
        for (double& c : cdf_)
            c /= total_;
    }

    bool empty() const { return !(total_ > 0); }

    /// The photon of the draws \p rng gives; none where it leaves away from the target.
    std::optional<Emission> emit(Pcg32& rng) const {
        const double u = rng.next_double();
        const std::size_t k = std::min<std::size_t>(
            std::size_t(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin()),
            kinds_.size() - 1);
        const double probability = cdf_[k] - (k == 0 ? 0.0 : cdf_[k - 1]);
        auto emission = std::visit([&](const auto& kind) { return emit(kind, rng); }, kinds_[k]);
        if (emission)
            emission->power = emission->power * float(1.0 / probability);
        return emission;
    }

private:
    void add(SourceKind kind, double power) {
        if (!(power > 0))
            return;
        kinds_.push_back(kind);
        total_ += power;
        cdf_.push_back(total_);
    }

    /// ∫ L dω over the sphere, channel mean, by a Fibonacci lattice of directions.
    double sky_radiance_integral() const {
        constexpr int k_directions = 1024;
        double sum = 0;
        for (int i = 0; i < k_directions; ++i) {
            const double z = 1.0 - (2.0 * i + 1.0) / k_directions;
            const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
            const double phi = i * k_pi * (3.0 - std::sqrt(5.0));
            sum += channel_mean(scene_.sky->radiance({r * std::cos(phi), r * std::sin(phi), z}));
        }
        return sum * 4.0 * k_pi / k_directions;
    }

    /// A direction from \p from toward the target: uniform in the cone it subtends, or over
    /// \p fallback's pdf when \p from lies inside it. Returns the direction and 1 / pdf.
    template <typename Fallback>
    std::pair<Vec3, double> toward_target(const Vec3& from, Pcg32& rng, Fallback fallback) const {
        const double u1 = rng.next_double(), u2 = rng.next_double();
        const Vec3 to_centre = target_.centre - from;
        const double dist = length(to_centre);
        if (!(dist > target_.radius))
            return fallback(u1, u2);
        const double sin_max = target_.radius / dist;
        const double cos_max = std::sqrt(std::max(0.0, 1.0 - sin_max * sin_max));
        const Vec3 dir =
            Frame::from_normal(to_centre / dist).to_world(uniform_cone(cos_max, u1, u2));
        return {dir, 2.0 * k_pi * (1.0 - cos_max)};
    }

    std::optional<Emission> emit(AreaKind, Pcg32& rng) const {
        const std::uint32_t element = lights_.pick(rng.next_double());
        const double a = rng.next_double(), b = rng.next_double();
        const Vec3 point = uniform_point_on(mesh_, element, a, b);
        const Patch& patch = mesh_.patch_of(element);
        const Frame frame = Frame::from_normal(patch.normal);
        const auto [dir, inv_pdf] = toward_target(point, rng, [&](double u1, double u2) {
            const Vec3 d = frame.to_world(cosine_hemisphere(u1, u2));
            return std::pair{d, k_pi / std::max(dot(d, patch.normal), 1e-12)};
        });
        const double cos_light = dot(dir, patch.normal);
        if (!(cos_light > 0))
            return std::nullopt;
        // Φ = L cos A / (p_element pdf_dir), L = M / π.
        const double scale =
            cos_light * k_inv_pi * mesh_.element_area[element] / lights_.probability(element);
        const Rgb m = exitance_.empty() ? patch.emission : Rgb(1.0f);
        return Emission{point + patch.normal * offset_, dir, m * float(scale * inv_pdf), element};
    }

    std::optional<Emission> emit(PointKind kind, Pcg32& rng) const {
        const PointLight& light = scene_.point_lights[kind.index];
        const auto [dir, inv_pdf] = toward_target(light.position, rng, [](double u1, double u2) {
            return std::pair{uniform_sphere(u1, u2), 4.0 * k_pi};
        });
        const double profile = light.profile(dir);
        if (!(profile > 0))
            return std::nullopt;
        return Emission{light.position, dir, light.intensity * float(profile * inv_pdf)};
    }

    /// A photon from a point uniform on the disc of the target's radius facing \p toward_source
    /// (beyond the target), carrying \p irradiance (normal to the disc, W/m²) over the disc.
    Emission from_disc(const Vec3& toward_source, const Rgb& irradiance, Pcg32& rng) const {
        const double r = target_.radius * std::sqrt(rng.next_double());
        const double phi = 2.0 * k_pi * rng.next_double();
        const Frame frame = Frame::from_normal(toward_source);
        const Vec3 on_disc = frame.to_world({r * std::cos(phi), r * std::sin(phi), 0.0});
        const double back = 2.0 * target_.radius + mesh_.scene_diagonal;
        const double disc = k_pi * target_.radius * target_.radius;
        return {target_.centre + on_disc + toward_source * back, -toward_source,
                irradiance * float(disc)};
    }

    std::optional<Emission> emit(SunKind, Pcg32& rng) const {
        const Sun& sun = *scene_.sun;
        const double u1 = rng.next_double(), u2 = rng.next_double();
        Vec3 toward = sun.direction;
        if (sun.angular_radius() > 0)
            toward = Frame::from_normal(sun.direction)
                         .to_world(uniform_cone(std::cos(sun.angular_radius()), u1, u2));
        // Uniform over the disc: L / pdf = (E_n / Ω) / (1 / Ω) = E_n.
        return from_disc(toward, sun.irradiance, rng);
    }

    std::optional<Emission> emit(SkyKind, Pcg32& rng) const {
        const double u1 = rng.next_double(), u2 = rng.next_double();
        const Vec3 toward = uniform_sphere(u1, u2);
        return from_disc(toward, scene_.sky->radiance(toward) * float(4.0 * k_pi), rng);
    }

    const RadiosityMesh& mesh_;
    const Scene& scene_;
    Target target_;
    AreaLights lights_;
    double offset_ = 0;
    std::span<const Rgb> exitance_;
    std::vector<SourceKind> kinds_;
    std::vector<double> cdf_;
    double total_ = 0;
};

/// Traces one photon: stored (power not yet divided by the photons shot) where it first lands
/// on a diffuse surface after a specular bounce; none if it is absorbed, escapes or lands
/// first on a diffuse surface.
std::optional<CausticPhoton> trace_photon(const EmbreeScene& rt, const SurfaceGeometry& surfaces,
                                          Emission photon, int max_bounces, Pcg32& rng) {
    const float start = photon.power.max_component();
    for (int bounces = 0; bounces <= max_bounces; ++bounces) {
        const auto hit = rt.intersect(Vec3f(photon.origin), Vec3f(photon.dir), 0.0f, k_infinity);
        if (hit.front_element < 0)
            return std::nullopt;
        const SurfaceHit s = surfaces.surface_of(hit, photon.origin, photon.dir);
        const Material& material = surfaces.material_of(s.element);
        if (receives_photons(material)) {
            if (bounces == 0 || hit.element < 0)
                return std::nullopt;
            return CausticPhoton{s.p, -photon.dir, s.normal, photon.power,
                                 std::uint32_t(hit.element)};
        }
        if (!material.lobe)
            return std::nullopt;
        const Bsdf bsdf(material, s.shading, TransportMode::importance);
        const Vec3 wo = -photon.dir;
        const double u_lobe = rng.next_double();
        const Vec2 u{rng.next_double(), rng.next_double()};
        const auto sample = bsdf.sample(wo, u_lobe, u);
        if (!sample || sample->weight.is_black() ||
            !SurfaceGeometry::geometric_side_agrees(s, wo, sample->wi, sample->transmission()))
            return std::nullopt;
        photon.power = photon.power * sample->weight;
        photon.origin = surfaces.offset(s, sample->wi);
        photon.dir = sample->wi;
        if (bounces + 1 >= k_roulette_after) {
            const float keep = std::min(1.0f, photon.power.max_component() / start);
            if (!(rng.next_float() < keep))
                return std::nullopt;
            photon.power = photon.power / keep;
        }
    }
    return std::nullopt;
}

/// Stored photons and, for each, the element it left (0 for the other sources).
struct StoredPhotons {
    CausticPhotons out;
    std::vector<std::uint32_t> sources;
};

/// The photons of the scene's sources (\p exitance empty) or of the elements chosen by their
/// \p exitance (powers per unit of exitance).
StoredPhotons shoot_photons(const EmbreeScene& rt, const Scene& scene,
                            std::span<const Rgb> exitance, const Context& ctx) {
    StoredPhotons stored;
    CausticPhotons& out = stored.out;
    const auto wanted = std::uint64_t(std::max(0, scene.render.caustic_photons));
    const auto target = specular_target(rt.mesh(), scene);
    if (wanted == 0 || !target)
        return stored;
    const SurfaceGeometry surfaces(rt, scene);
    const PhotonSources sources(rt.mesh(), scene, *target, surfaces.offset_distance(), exitance);
    if (sources.empty())
        return stored;
    std::vector<std::optional<CausticPhoton>> batch(k_batch);
    std::vector<std::uint32_t> batch_sources(k_batch);
    run_in_arena(ctx, [&] {
        while (out.photons.size() < wanted && out.shot < k_max_shot_per_stored * wanted) {
            const std::uint64_t first = out.shot;
            parallel_for_index(k_batch, 64, [&](std::size_t i) {
                Pcg32 rng =
                    Pcg32::for_stream(RngPurpose::caustic_photon, first + i, 0, 0, ctx.seed);
                const auto emission = sources.emit(rng);
                batch[i] =
                    emission ? trace_photon(rt, surfaces, *emission, scene.render.max_bounces, rng)
                             : std::nullopt;
                batch_sources[i] = emission ? emission->element : 0;
            });
            for (std::size_t i = 0; i < k_batch; ++i)
                if (batch[i]) {
                    out.photons.push_back(*batch[i]);
                    stored.sources.push_back(batch_sources[i]);
                }
            out.shot += k_batch;
        }
    });
    for (CausticPhoton& photon : out.photons)
        photon.power_w = photon.power_w * float(1.0 / double(out.shot));
    out.fixed_radius = scene.render.caustic_radius_m.has_value();
    out.radius_m =
        scene.render.caustic_radius_m.value_or(k_max_radius_of_diagonal * rt.mesh().scene_diagonal);
    ctx.debug("{} photons: {} stored of {} shot, radius {:.4g} m",
              exitance.empty() ? "caustic" : "reflected", out.photons.size(), out.shot,
              out.radius_m);
    return stored;
}

} // namespace

CausticPhotons shoot_caustic_photons(const EmbreeScene& rt, const Scene& scene,
                                     const Context& ctx) {
    return shoot_photons(rt, scene, {}, ctx).out;
}

std::vector<SpecularLight::Transfer> specular_transfers(const EmbreeScene& rt, const Scene& scene,
                                                        std::span<const Rgb> exitance,
                                                        const Context& ctx) {
    if (exitance.size() != rt.mesh().element_count())
        throw InternalError("specular_transfers: one exitance per element expected");
    const StoredPhotons stored = shoot_photons(rt, scene, exitance, ctx);
    std::vector<SpecularLight::Transfer> transfers;
    transfers.reserve(stored.out.photons.size());
    for (std::size_t i = 0; i < stored.out.photons.size(); ++i) {
        const CausticPhoton& photon = stored.out.photons[i];
        transfers.push_back({stored.sources[i], photon.element, photon.power_w});
    }
    return transfers;
}

std::vector<Rgb> caustic_irradiance(const CausticPhotons& photons, const RadiosityMesh& mesh) {
    if (photons.photons.empty())
        return {};
    std::vector<RgbD> flux(mesh.element_count());
    for (const CausticPhoton& photon : photons.photons)
        flux[photon.element] += RgbD(photon.power_w);
    std::vector<Rgb> out(flux.size());
    for (std::size_t e = 0; e < flux.size(); ++e) {
        const RgbD h = flux[e] * (1.0 / mesh.element_area[e]);
        out[e] = Rgb(float(h.r), float(h.g), float(h.b));
    }
    return out;
}

} // namespace penumbra::raytrace
