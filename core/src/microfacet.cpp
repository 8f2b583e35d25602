#include "core/microfacet.h"

#include <cmath>

namespace penumbra {

double GgxDistribution::d(const Vec3& m) const {
    if (m.z <= 0)
        return 0;
    const double a2 = alpha * alpha;
    const double c2 = m.z * m.z;
    const double denominator = c2 * (a2 - 1.0) + 1.0;
    return a2 / (k_pi * denominator * denominator);
}

double GgxDistribution::lambda(const Vec3& w) const {
    const double c2 = w.z * w.z;
    const double s2 = std::max(0.0, 1.0 - c2);
    if (s2 == 0)
        return 0;
    // α² tan² θ = α² s² / c²: the form without tan keeps grazing directions finite.
    return 0.5 * (std::sqrt(1.0 + alpha * alpha * s2 / c2) - 1.0);
}

double GgxDistribution::g1(const Vec3& w) const {
    return w.z > 0 ? 1.0 / (1.0 + lambda(w)) : 0.0;
}

double GgxDistribution::g2(const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0 || wi.z <= 0)
        return 0;
    return 1.0 / (1.0 + lambda(wo) + lambda(wi));
}

double GgxDistribution::visible_normal_pdf(const Vec3& wo, const Vec3& m) const {
    if (wo.z <= 0)
        return 0;
    return g1(wo) * std::max(0.0, dot(wo, m)) * d(m) / wo.z;
}

Vec3 GgxDistribution::sample_visible_normal(const Vec3& wo, const Vec2& u) const {
    // Stretch the view into the configuration of α = 1 (the hemisphere).
    const Vec3 v = normalize(Vec3(alpha * wo.x, alpha * wo.y, wo.z));
    // An orthonormal basis (t1, t2, v); t1 horizontal.
    const double len2 = v.x * v.x + v.y * v.y;
    const Vec3 t1 = len2 > 0 ? Vec3(-v.y, v.x, 0) / std::sqrt(len2) : Vec3(1, 0, 0);
    const Vec3 t2 = cross(v, t1);
    // A uniform point of the unit disc, its upper half squeezed onto the part of the projected
    // hemisphere that the view sees (the lower half of the disc is the back of the ellipse).
    const double r = std::sqrt(u.x), phi = 2.0 * k_pi * u.y;
    const double p1 = r * std::cos(phi);
    const double s = 0.5 * (1.0 + v.z);
    const double p2 = (1.0 - s) * std::sqrt(std::max(0.0, 1.0 - p1 * p1)) + s * r * std::sin(phi);
    // Lift onto the hemisphere, then unstretch to the α of the surface.
    const Vec3 h = t1 * p1 + t2 * p2 + v * std::sqrt(std::max(0.0, 1.0 - p1 * p1 - p2 * p2));
    return normalize(Vec3(alpha * h.x, alpha * h.y, std::max(1e-12, h.z)));
}

double fresnel_dielectric(double cos_i, double eta) {
    if (cos_i < 0) { // arriving from inside: swap the media
        eta = 1.0 / eta;
        cos_i = -cos_i;
    }
    cos_i = std::min(cos_i, 1.0);
    const double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0)
        return 1.0;
    const double cos_t = std::sqrt(1.0 - sin2_t);
    const double r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    const double r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5 * (r_s * r_s + r_p * r_p);
}

} // namespace penumbra
