// The delta lobes: the mirror, the smooth dielectric and thin glass. Each sample's pdf is the
// discrete probability of the event chosen and its weight that event's factor over it.

#include "bsdf_lobes.h"

#include <cmath>

namespace penumbra {

namespace {

/// Mirror reflection about the local normal (z).
Vec3 mirror_direction(const Vec3& wo) {
    return {-wo.x, -wo.y, wo.z};
}

double mean(const Rgb& c) {
    return (double(c.r) + double(c.g) + double(c.b)) / 3.0;
}

} // namespace

std::optional<BsdfSample> sample_local(const MirrorLobe& lobe, const Vec3& wo, double, const Vec2&,
                                       TransportMode) {
    if (lobe.colour.is_black())
        return std::nullopt;
    return BsdfSample{mirror_direction(wo), lobe.colour, 1.0, BsdfLobe::specular_reflection, 1.0};
}

// Reflection with probability F, refraction otherwise: the weights are 1 and T (over η² for
// radiance, which is η² denser on the side of the higher index).
std::optional<BsdfSample> sample_local(const DielectricLobe& lobe, const Vec3& wo, double u_lobe,
                                       const Vec2&, TransportMode mode) {
    if (wo.z == 0)
        return std::nullopt;
    const double f = fresnel_dielectric(wo.z, lobe.ior);
    if (u_lobe < f)
        return BsdfSample{mirror_direction(wo), Rgb(1.0f), f, BsdfLobe::specular_reflection, 1.0};
    // Snell's law: eta = n_t / n_i for wo's side (front = outside).
    const bool outside = wo.z > 0;
    const double eta = outside ? lobe.ior : 1.0 / lobe.ior;
    const double cos_o = std::abs(wo.z);
    const double sin2_t = (1.0 - cos_o * cos_o) / (eta * eta);
    const double cos_t = std::sqrt(std::max(0.0, 1.0 - sin2_t));
    const Vec3 n(0, 0, outside ? 1.0 : -1.0);
    const Vec3 wi = normalize(-wo / eta + n * (cos_o / eta - cos_t));
    Rgb weight = lobe.transmittance;
    if (mode == TransportMode::radiance)
        weight *= float(1.0 / (eta * eta));
    if (weight.is_black())
        return std::nullopt;
    return BsdfSample{wi, weight, 1.0 - f, BsdfLobe::specular_transmission, eta};
}

// Reflection or straight transmission, chosen by the channels' mean R and T at |cos θo|.
std::optional<BsdfSample> sample_local(const ThinGlassLobe& lobe, const Vec3& wo, double u_lobe,
                                       const Vec2&, TransportMode) {
    const double c = std::abs(wo.z);
    const Rgb r = lobe.glass.reflectance(c), t = lobe.glass.transmittance(c);
    const double total = mean(r) + mean(t);
    if (!(total > 0))
        return std::nullopt;
    const double p_reflect = mean(r) / total;
    if (u_lobe < p_reflect)
        return BsdfSample{mirror_direction(wo), r / float(p_reflect), p_reflect,
                          BsdfLobe::specular_reflection, 1.0};
    return BsdfSample{-wo, t / float(1.0 - p_reflect), 1.0 - p_reflect,
                      BsdfLobe::specular_transmission, 1.0};
}

} // namespace penumbra
