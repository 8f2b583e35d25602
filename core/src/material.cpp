#include "core/material.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

namespace {

/// Intervals of the composite Simpson rule for the hemispherical transmittance: T(μ) μ is
/// smooth on [0, 1] (n > 1 keeps cos θt away from 0), so the rule's error is far below 1e-6.
constexpr int k_hemisphere_intervals = 128;

/// One polarisation of the pane, from the Fresnel reflectance \p r of one face and the
/// fraction \p a that one crossing of the glass leaves: the light bouncing between the two
/// faces adds up as a geometric series of ratio (r a)².
ThinGlassResponse one_polarisation(double r, double a) {
    if (r >= 1)
        return {0, 1};
    const double bounces = 1.0 / (1.0 - r * r * a * a);
    const double entered = (1 - r) * (1 - r); // in through one face and out through the other
    return {entered * a * bounces, r + entered * r * a * a * bounces};
}

template <typename F> Rgb per_channel(const Rgb& tn, F&& f) {
    return {float(f(double(tn.r))), float(f(double(tn.g))), float(f(double(tn.b)))};
}

} // namespace

ThinGlassResponse thin_glass_response(double tn, double ior, double cos_theta) {
    const double c = std::clamp(cos_theta, 0.0, 1.0);
    if (c == 0)
        return {0, 1};
    // Snell's law for the angle inside the glass, and the absorption along that path.
    const double cos_t = std::sqrt(1.0 - (1.0 - c * c) / (ior * ior));
    const double a = std::pow(tn, 1.0 / cos_t);
    const double s = (c - ior * cos_t) / (c + ior * cos_t); // perpendicular amplitude
    const double p = (cos_t - ior * c) / (cos_t + ior * c); // parallel amplitude
    const ThinGlassResponse rs = one_polarisation(s * s, a), rp = one_polarisation(p * p, a);
    return {0.5 * (rs.transmittance + rp.transmittance), 0.5 * (rs.reflectance + rp.reflectance)};
}

double thin_glass_hemispherical_transmittance(double tn, double ior) {
    constexpr int n = k_hemisphere_intervals;
    auto f = [&](int i) {
        const double mu = double(i) / n;
        return 2.0 * thin_glass_response(tn, ior, mu).transmittance * mu;
    };
    double sum = f(0) + f(n);
    for (int i = 1; i < n; ++i)
        sum += (i % 2 == 1 ? 4.0 : 2.0) * f(i);
    return sum / (3.0 * n);
}

Rgb ThinGlass::transmittance(double cos_theta) const {
    return per_channel(transmissivity, [&](double tn) {
        return thin_glass_response(tn, ior, cos_theta).transmittance;
    });
}

Rgb ThinGlass::reflectance(double cos_theta) const {
    return per_channel(transmissivity, [&](double tn) {
        return thin_glass_response(tn, ior, cos_theta).reflectance;
    });
}

Rgb ThinGlass::hemispherical_transmittance() const {
    return per_channel(transmissivity,
                       [&](double tn) { return thin_glass_hemispherical_transmittance(tn, ior); });
}

std::optional<ThinGlass> glazing_of(const Material& m) {
    if (m.lobe)
        if (const auto* glass = std::get_if<ThinGlass>(&*m.lobe))
            return *glass;
    return std::nullopt;
}

Rgb diffuse_reflectance(const Material& m) {
    if (!m.lobe)
        return m.reflectance;
    const auto* glossy = std::get_if<GgxGlossy>(&*m.lobe);
    return glossy && glossy->diffuse_base ? m.reflectance : Rgb{};
}

RadiosityResponse radiosity_response(const Material& m) {
    RadiosityResponse r;
    r.reflectance = diffuse_reflectance(m);
    r.emission = m.emission;
    r.two_sided = m.two_sided;
    r.emission_two_sided = m.emission_two_sided;
    r.diffuse_transmittance = m.diffuse_transmittance;
    if (m.lobe)
        if (const auto* glass = std::get_if<ThinGlass>(&*m.lobe))
            r.transmittance = glass->hemispherical_transmittance();
    r.specular_only = m.lobe && r.reflectance.is_black() && r.diffuse_transmittance.is_black() &&
                      r.transmittance.is_black();
    return r;
}

} // namespace penumbra
