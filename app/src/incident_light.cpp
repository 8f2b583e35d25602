#include "incident_light.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <utility>

namespace penumbra::app {

namespace {

constexpr float k_infinity = std::numeric_limits<float>::infinity();

} // namespace

IncidentLight::IncidentLight(const Scene& scene, const raytrace::EmbreeScene& rt,
                             const Solution& solution, solver::DirectLightOptions direct)
    : scene_(scene), rt_(rt), solution_(solution),
      offset_(1e-5 * std::max(rt.mesh().scene_diagonal, 1e-3)), direct_(std::move(direct)) {
    for (const Patch& p : rt.mesh().patches)
        has_glazing_ |= !p.opaque();
}

float IncidentLight::transmittance(const Vec3& from, const Vec3& dir, float reach) const {
    return raytrace::segment_transmittance(rt_, {Vec3f(from), Vec3f(dir), 0.0f, reach},
                                           has_glazing_);
}

RgbD IncidentLight::radiance(const Vec3& origin, const Vec3& dir) const {
    const RayLight l = trace(origin, dir);
    return l.reflected + l.emitted;
}

RayLight IncidentLight::trace(const Vec3& origin, const Vec3& dir) const {
    const raytrace::EmbreeScene::Hit hit =
        rt_.intersect(Vec3f(origin), Vec3f(dir), 0.0f, k_infinity);
    RayLight l;
    if (hit.element >= 0) {
        const RadiosityMesh& mesh = rt_.mesh();
        const auto e = std::uint32_t(hit.element);
        const auto& tri = mesh.triangles[e];
        const auto& b = solution_.vertex_radiosity;
        const Rgb emission = mesh.patch_of(e).emission;
        const Rgb reflected = b[tri[0]] + (b[tri[1]] - b[tri[0]]) * hit.u +
                              (b[tri[2]] - b[tri[0]]) * hit.v - emission;
        // Interpolated B may dip below E at an emitter's edge: the emitted part stays exact.
        l.reflected = RgbD(std::max(0.0f, reflected.r), std::max(0.0f, reflected.g),
                           std::max(0.0f, reflected.b)) *
                      k_inv_pi;
        if (sees(AreaSource{mesh.patch_of(e).polygon}))
            l.emitted = RgbD(emission) * k_inv_pi;
        l.element = hit.element;
        l.distance = hit.t;
    } else if (hit.front_element < 0 && scene_.sky && sees(SkySource{})) {
        l.reflected = RgbD(scene_.sky->radiance(dir));
    }
    if (!has_glazing_ || (l.reflected + l.emitted).max_component() <= 0)
        return l;
    // Panes do not stop intersect(): their transmittance up to what the ray met.
    const float reach = hit.front_element < 0 ? k_infinity : float(hit.t - offset_);
    const double t = double(transmittance(origin, dir, reach));
    l.reflected = l.reflected * t;
    l.emitted = l.emitted * t;
    return l;
}

std::vector<DeltaLight> IncidentLight::deltas(const Vec3& origin) const {
    std::vector<DeltaLight> out;
    for (std::size_t i = 0; i < scene_.point_lights.size(); ++i) {
        const PointLight& light = scene_.point_lights[i];
        if (!sees(PointSource{std::uint32_t(i)}))
            continue;
        const Vec3 to_light = light.position - origin;
        const double d = length(to_light);
        if (!(d > 2 * offset_))
            continue;
        const Vec3 dir = to_light / d;
        const double profile = light.profile(-dir);
        if (profile <= 0 || light.intensity.is_black())
            continue;
        const float t = transmittance(origin, dir, float(d - offset_));
        if (t > 0)
            out.push_back({dir, RgbD(light.intensity) * (profile * double(t) / (d * d))});
    }
    if (scene_.sun && !scene_.sun->irradiance.is_black() && sees(SunSource{})) {
        const float t = transmittance(origin, scene_.sun->direction, k_infinity);
        if (t > 0)
            out.push_back({scene_.sun->direction, RgbD(scene_.sun->irradiance) * double(t)});
    }
    return out;
}

std::vector<Vec3> stratified_directions(int n_z, bool hemisphere, Pcg32& rng) {
    const double z_low = hemisphere ? 0.0 : -1.0;
    const double dz = (1.0 - z_low) / n_z, dphi = k_pi / n_z;
    std::vector<Vec3> out;
    out.reserve(std::size_t(2 * n_z * n_z));
    for (int i = 0; i < n_z; ++i)
        for (int j = 0; j < 2 * n_z; ++j) {
            const double z = z_low + (i + rng.next_double()) * dz;
            const double phi = (j + rng.next_double()) * dphi;
            const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
            out.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
        }
    return out;
}

} // namespace penumbra::app
