// The non-delta lobes: Lambertian, GGX reflection and the plastic (a GGX coat over a
// Lambertian base), each in its local frame with wo above the surface.

#include "bsdf_lobes.h"

#include <algorithm>
#include <cmath>

#include "coat_albedo.h"

namespace penumbra {

namespace {

double mean(const Rgb& c) {
    return (double(c.r) + double(c.g) + double(c.b)) / 3.0;
}

/// Cosine-distributed direction on the upper hemisphere (Shirley–Chiu's concentric map of the
/// square onto the disc, lifted: Malley's method).
Vec3 cosine_direction(const Vec2& u) {
    const double a = 2.0 * u.x - 1.0, b = 2.0 * u.y - 1.0;
    if (a == 0 && b == 0)
        return {0, 0, 1};
    double r, phi;
    if (std::abs(a) > std::abs(b)) {
        r = a;
        phi = 0.25 * k_pi * (b / a);
    } else {
        r = b;
        phi = 0.5 * k_pi - 0.25 * k_pi * (a / b);
    }
    const double x = r * std::cos(phi), y = r * std::sin(phi);
    return {x, y, std::sqrt(std::max(0.0, 1.0 - x * x - y * y))};
}

/// The half vector of a reflection pair; none when it is degenerate or below the surface.
std::optional<Vec3> half_vector(const Vec3& wo, const Vec3& wi) {
    const Vec3 h = wo + wi;
    const double len = length(h);
    if (!(len > 0) || h.z <= 0)
        return std::nullopt;
    return h / len;
}

/// The plastic's base: ρ/π (1 − E(μo)) (1 − E(μi)) / (1 − E_avg), times cos θi.
Rgb plastic_base(const PlasticLobe& lobe, const Vec3& wo, const Vec3& wi) {
    const CoatAlbedo& tables = CoatAlbedo::tables();
    const double alpha = lobe.coat.distribution.alpha;
    const auto& fresnel = std::get<LinearFresnel>(lobe.coat.fresnel);
    const Rgb eo = tables.directional(wo.z, alpha, fresnel);
    const Rgb ei = tables.directional(wi.z, alpha, fresnel);
    const Rgb avg = tables.average(alpha, fresnel);
    Rgb f;
    for (int c = 0; c < 3; ++c) {
        const double rest = 1.0 - avg[c];
        // A coat that reflects (nearly) everything leaves the base no light.
        f[c] = rest > 1e-6 ? float(lobe.reflectance[c] * (1.0 - eo[c]) * (1.0 - ei[c]) / rest) : 0;
    }
    return f * float(k_inv_pi * wi.z);
}

} // namespace

// ---- Lambertian ------------------------------------------------------------------------------

Rgb eval_local(const LambertLobe& lobe, const Vec3&, const Vec3& wi) {
    return lobe.reflectance * float(k_inv_pi * wi.z);
}

double pdf_local(const LambertLobe&, const Vec3&, const Vec3& wi) {
    return k_inv_pi * wi.z;
}

std::optional<BsdfSample> sample_local(const LambertLobe& lobe, const Vec3&, double, const Vec2& u,
                                       TransportMode) {
    const Vec3 wi = cosine_direction(u);
    if (wi.z <= 0 || lobe.reflectance.is_black())
        return std::nullopt;
    return BsdfSample{wi, lobe.reflectance, k_inv_pi * wi.z, BsdfLobe::diffuse, 1.0};
}

// ---- GGX reflection --------------------------------------------------------------------------

Rgb LinearFresnel::at(double cos_i) const {
    return a + b * float(fresnel_schlick(0.0, cos_i));
}

Rgb GgxLobe::fresnel_at(double cos_i) const {
    if (const auto* linear = std::get_if<LinearFresnel>(&fresnel))
        return linear->at(cos_i);
    const auto& scaled = std::get<ScaledDielectricFresnel>(fresnel);
    return scaled.scale * float(fresnel_dielectric(cos_i, scaled.eta));
}

Rgb eval_local(const GgxLobe& lobe, const Vec3& wo, const Vec3& wi) {
    const std::optional<Vec3> m = half_vector(wo, wi);
    if (!m)
        return {};
    const GgxDistribution& ggx = lobe.distribution;
    // f cos θi = F D G2 / (4 cos θo).
    const double value = ggx.d(*m) * ggx.g2(wo, wi) / (4.0 * wo.z);
    return lobe.fresnel_at(dot(wo, *m)) * float(value);
}

double pdf_local(const GgxLobe& lobe, const Vec3& wo, const Vec3& wi) {
    const std::optional<Vec3> m = half_vector(wo, wi);
    if (!m)
        return 0;
    // The visible-normal density over the Jacobian of reflection, 4 (wo·m).
    const GgxDistribution& ggx = lobe.distribution;
    return ggx.g1(wo) * ggx.d(*m) / (4.0 * wo.z);
}

std::optional<BsdfSample> sample_local(const GgxLobe& lobe, const Vec3& wo, double, const Vec2& u,
                                       TransportMode) {
    const GgxDistribution& ggx = lobe.distribution;
    const Vec3 m = ggx.sample_visible_normal(wo, u);
    const Vec3 wi = reflect(wo, m);
    if (wi.z <= 0)
        return std::nullopt;
    // f cos θi / pdf = F G2 / G1(wo): no D, so no spike for small α.
    const Rgb weight = lobe.fresnel_at(dot(wo, m)) * float(ggx.g2(wo, wi) / ggx.g1(wo));
    if (weight.is_black())
        return std::nullopt;
    return BsdfSample{wi, weight, pdf_local(lobe, wo, wi), BsdfLobe::glossy_reflection, 1.0};
}

// ---- Plastic ---------------------------------------------------------------------------------

double plastic_coat_probability(const PlasticLobe& lobe, const Vec3& wo) {
    const auto& fresnel = std::get<LinearFresnel>(lobe.coat.fresnel);
    const Rgb coat = CoatAlbedo::tables().directional(wo.z, lobe.coat.distribution.alpha, fresnel);
    const double e = mean(coat);
    const double base = mean(lobe.reflectance * (Rgb(1.0f) - coat));
    return e + base > 0 ? e / (e + base) : 1.0;
}

Rgb eval_local(const PlasticLobe& lobe, const Vec3& wo, const Vec3& wi) {
    return eval_local(lobe.coat, wo, wi) + plastic_base(lobe, wo, wi);
}

double pdf_local(const PlasticLobe& lobe, const Vec3& wo, const Vec3& wi) {
    const double p = plastic_coat_probability(lobe, wo);
    return p * pdf_local(lobe.coat, wo, wi) + (1.0 - p) * k_inv_pi * wi.z;
}

std::optional<BsdfSample> sample_local(const PlasticLobe& lobe, const Vec3& wo, double u_lobe,
                                       const Vec2& u, TransportMode) {
    // One lobe is sampled, the weight is of the whole BSDF over the mixture's density.
    const bool coat = u_lobe < plastic_coat_probability(lobe, wo);
    const Vec3 wi = coat ? reflect(wo, lobe.coat.distribution.sample_visible_normal(wo, u))
                         : cosine_direction(u);
    if (wi.z <= 0)
        return std::nullopt;
    const double pdf = pdf_local(lobe, wo, wi);
    const Rgb f = eval_local(lobe, wo, wi);
    if (!(pdf > 0) || f.is_black())
        return std::nullopt;
    return BsdfSample{wi, f / float(pdf), pdf,
                      coat ? BsdfLobe::glossy_reflection : BsdfLobe::diffuse, 1.0};
}

} // namespace penumbra
