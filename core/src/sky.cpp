// The sky as a radiance distribution: the models' relative luminance (sky_models.cpp), its
// horizon (sharp, or Radiance's skybright.cal blend with the ground), and the sky's horizontal
// illuminance by quadrature in polar coordinates about the sun, where the circumsolar peak
// exp(d γ) is smooth (about the zenith it is a cone-shaped cusp that product rules resolve
// slowly).

#include "core/sky.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

#include "core/error.h"

#include "sky_models.h"

namespace penumbra {

namespace {

template <class... F> struct Overloaded : F... { using F::operator()...; };
template <class... F> Overloaded(F...) -> Overloaded<F...>;

/// Gauss–Legendre nodes and weights on [−1, 1] (Newton's method on P_n).
template <int N> struct GaussLegendre {
    std::array<double, N> x{}, w{};
    GaussLegendre() {
        for (int i = 0; i < N; ++i) {
            double t = std::cos(k_pi * (i + 0.75) / (N + 0.5));
            double derivative = 1;
            for (int iteration = 0; iteration < 100; ++iteration) {
                double p0 = 1, p1 = t;
                for (int k = 2; k <= N; ++k) {
                    const double p2 = ((2 * k - 1) * t * p1 - (k - 1) * p0) / k;
                    p0 = p1;
                    p1 = p2;
                }
                derivative = N * (t * p1 - p0) / (t * t - 1);
                const double step = p1 / derivative;
                t -= step;
                if (std::abs(step) < 1e-16)
                    break;
            }
            x[std::size_t(i)] = t;
            w[std::size_t(i)] = 2 / ((1 - t * t) * derivative * derivative);
        }
    }
};

constexpr int k_nodes_per_panel = 12;
constexpr int k_azimuth_steps = 96;

const GaussLegendre<k_nodes_per_panel>& gauss_rule() {
    static const GaussLegendre<k_nodes_per_panel> rule; // an immutable table
    return rule;
}

/// The polar angles γ about a centre of altitude sine \p a at which the great half-circle of
/// azimuth ψ (b = cos(altitude) cos ψ, ψ = 0 toward the zenith) is above the horizon:
/// cos θ = a cos γ + b sin γ ≥ 0. Empty (lo ≥ hi) when the half-circle stays below.
std::pair<double, double> angles_above_horizon(double a, double b) {
    double g = std::atan2(b, a); // cos θ = R cos(γ − g)
    if (g < -k_pi / 2)
        g += 2 * k_pi;
    if (a >= 0)
        return {0.0, std::min(k_pi, g + k_pi / 2)};
    return {std::max(0.0, g - k_pi / 2), k_pi};
}

/// ∫ f(dir) cos θ dω over the upper hemisphere (dir·up > 0), in polar coordinates (γ, ψ)
/// about the unit \p centre: ψ by the midpoint rule (periodic), γ by Gauss–Legendre on panels
/// graded toward the centre. 5 760 evaluations: about 1e-5 relative for the CIE skies, 1e-4
/// for Perez's (whose gradation is clamped at Dz = 0.01), against a 1200 × 2400 midpoint rule.
template <class F>
double upper_hemisphere_integral(const Compass& compass, const Vec3& centre, const F& f) {
    const double a = dot(centre, compass.up);
    Vec3 toward_zenith = compass.up - centre * a;
    const double s = length(toward_zenith);
    toward_zenith = s > 1e-12 ? toward_zenith / s : Frame::from_normal(centre).s;
    const Vec3 side = cross(centre, toward_zenith);
    constexpr double fractions[] = {0, 1.0 / 32, 1.0 / 12, 0.25, 0.55, 1};
    const auto& rule = gauss_rule();
    double total = 0;
    for (int i = 0; i < k_azimuth_steps; ++i) {
        const double psi = (i + 0.5) * 2 * k_pi / k_azimuth_steps;
        const auto [lo, hi] = angles_above_horizon(a, s * std::cos(psi));
        if (hi <= lo)
            continue;
        const Vec3 across = toward_zenith * std::cos(psi) + side * std::sin(psi);
        for (std::size_t p = 0; p + 1 < std::size(fractions); ++p) {
            const double g0 = lo + (hi - lo) * fractions[p], g1 = lo + (hi - lo) * fractions[p + 1];
            const double half = (g1 - g0) / 2;
            for (int k = 0; k < k_nodes_per_panel; ++k) {
                const double gamma = g0 + half * (rule.x[std::size_t(k)] + 1);
                const Vec3 dir = centre * std::cos(gamma) + across * std::sin(gamma);
                const double cos_theta = std::max(0.0, dot(dir, compass.up));
                total += rule.w[std::size_t(k)] * half * f(dir) * cos_theta * std::sin(gamma);
            }
        }
    }
    return total * 2 * k_pi / k_azimuth_steps;
}

/// The pole of the quadrature: the sun where the sky peaks around it, unless the sun is so low
/// that its polar coordinates would cross the horizon at grazing angles (there the peak's
/// cusp lies where cos θ weighs it little).
Vec3 quadrature_centre(const Sky& sky) {
    const bool peaks_at_sun = std::holds_alternative<CieGeneralSky>(sky.model) ||
                              std::holds_alternative<PerezSky>(sky.model) ||
                              std::holds_alternative<PerezCoefficientsSky>(sky.model);
    // 2.9°: below it the zenith-centred rule is the better one (both tested to 1e-5).
    constexpr double min_sun_sine = 0.05;
    return peaks_at_sun && dot(sky.sun_direction, sky.compass.up) >= min_sun_sine
               ? sky.sun_direction
               : sky.compass.up;
}

double luminance_of(const Rgb& colour) {
    return to_photometric(colour) / k_luminous_efficacy_lm_per_w;
}

} // namespace

Vec3 Compass::east() const {
    return cross(north, up);
}

Vec3 Compass::direction(double altitude_deg, double azimuth_deg) const {
    const double altitude = altitude_deg * k_pi / 180, azimuth = azimuth_deg * k_pi / 180;
    return (north * std::cos(azimuth) + east() * std::sin(azimuth)) * std::cos(altitude) +
           up * std::sin(altitude);
}

namespace {

/// One sky's relative luminance with its per-sky constants (normalisation, Perez's
/// coefficients) computed once, for the many directions of a quadrature.
class RelativeLuminance {
public:
    explicit RelativeLuminance(const Sky& sky)
        : up_(sky.compass.up), sun_(sky.sun_direction),
          sun_zenith_(std::acos(std::clamp(dot(sky.sun_direction, sky.compass.up), 0.0, 1.0))) {
        std::visit(Overloaded{[](const UniformSky&) {}, [](const CieOvercastSky&) {},
                              [&](const CieGeneralSky& general) {
                                  cie_ = cie_general_parameters(general.type);
                                  scale_ = 1 / (cie_gradation(cie_, 1.0) *
                                                cie_indicatrix(cie_, sun_zenith_));
                              },
                              [&](const PerezSky& perez) {
                                  perez_ = perez_coefficients(perez, sun_zenith_);
                                  const double zenith = perez_luminance(perez_, 1.0, sun_zenith_);
                                  scale_ = zenith > 0 ? 1 / zenith : 0.0;
                              },
                              [](const RadianceIntermediateSky&) {},
                              [&](const PerezCoefficientsSky& k) {
                                  // The zenith's angle to the sun as it is (perezlum.cal's).
                                  perez_ = {k.a, k.b, k.c, k.d, k.e};
                                  const double zenith =
                                      perez_luminance(perez_, 1.0, angle_to_sun(up_));
                                  scale_ = zenith > 0 ? 1 / zenith : 0.0;
                              }},
                   sky.model);
        kind_ = sky.model.index();
    }

    double operator()(const Vec3& dir) const {
        const double dz = dot(dir, up_);
        switch (kind_) {
        case 0: // UniformSky
            return 1.0;
        case 1: // CieOvercastSky
            return std::max(0.0, (1 + 2 * dz) / 3);
        case 2: // CieGeneralSky
            return scale_ * cie_gradation(cie_, dz) * cie_indicatrix(cie_, angle_to_sun(dir));
        case 3: // PerezSky
        case 5: // PerezCoefficientsSky
            return scale_ * perez_luminance(perez_, dz, angle_to_sun(dir));
        default: // RadianceIntermediateSky
            return radiance_intermediate_sky(std::acos(std::clamp(dz, -1.0, 1.0)),
                                             angle_to_sun(dir), sun_zenith_);
        }
    }

private:
    double angle_to_sun(const Vec3& dir) const {
        return std::acos(std::clamp(dot(dir, sun_), -1.0, 1.0));
    }

    Vec3 up_, sun_;
    double sun_zenith_;
    std::size_t kind_ = 0;
    double scale_ = 1;
    CieParameters cie_{};
    PerezCoefficients perez_{};
};
static_assert(std::is_same_v<std::variant_alternative_t<2, SkyModel>, CieGeneralSky> &&
              std::is_same_v<std::variant_alternative_t<3, SkyModel>, PerezSky> &&
              std::is_same_v<std::variant_alternative_t<4, SkyModel>, RadianceIntermediateSky> &&
              std::is_same_v<std::variant_alternative_t<5, SkyModel>, PerezCoefficientsSky>);

} // namespace

double Sky::relative_luminance(const Vec3& dir) const {
    return RelativeLuminance(*this)(dir);
}

namespace {

/// The weights of the sky's and the ground's radiance in a direction of up-component \p dz.
std::pair<double, double> sky_and_ground_weights(const Sky& sky, double dz) {
    if (!sky.ground_radiance)
        return {dz > 0 ? 1.0 : 0.0, 0.0};
    if (sky.horizon == Horizon::sharp)
        return dz > 0 ? std::pair{1.0, 0.0} : std::pair{0.0, 1.0};
    // skybright.cal: wmean((Dz + 1.01)^10, sky, (Dz + 1.01)^−10, ground); Dz ≥ −1 keeps the
    // base ≥ 0.01.
    const double ground_over_sky = std::pow(dz + 1.01, -20.0);
    const double sky_weight = 1 / (1 + ground_over_sky);
    return {sky_weight, 1 - sky_weight};
}

} // namespace

namespace {

Rgb radiance_of(const Sky& sky, const RelativeLuminance& relative, const Vec3& dir) {
    const auto [sky_weight, ground_weight] = sky_and_ground_weights(sky, dot(dir, sky.compass.up));
    Rgb result;
    if (sky_weight > 0)
        result = sky.colour * float(sky_weight * sky.zenith_radiance * relative(dir));
    if (ground_weight > 0)
        result += Rgb(float(ground_weight * *sky.ground_radiance));
    return result;
}

} // namespace

Rgb Sky::radiance(const Vec3& dir) const {
    return radiance_of(*this, RelativeLuminance(*this), dir);
}

void Sky::radiance(std::span<const Vec3> dirs, std::span<Rgb> out) const {
    if (dirs.size() != out.size())
        throw InternalError("Sky::radiance: " + std::to_string(dirs.size()) + " directions, " +
                            std::to_string(out.size()) + " outputs");
    const RelativeLuminance relative(*this);
    for (std::size_t i = 0; i < dirs.size(); ++i)
        out[i] = radiance_of(*this, relative, dirs[i]);
}

double Sky::horizontal_illuminance_lx() const {
    const double colour_luminance = luminance_of(colour);
    const RelativeLuminance relative(*this);
    const auto luminance = [&](const Vec3& dir) {
        const auto [sky_weight, ground_weight] =
            sky_and_ground_weights(*this, dot(dir, compass.up));
        double value = 0;
        if (sky_weight > 0)
            value += sky_weight * zenith_radiance * colour_luminance * relative(dir);
        if (ground_weight > 0)
            value += ground_weight * *ground_radiance;
        return value;
    };
    const Vec3 centre = quadrature_centre(*this);
    return k_luminous_efficacy_lm_per_w * upper_hemisphere_integral(compass, centre, luminance);
}

double Sky::horizontal_illuminance_per_zenith_luminance() const {
    const Vec3 centre = quadrature_centre(*this);
    return upper_hemisphere_integral(compass, centre, RelativeLuminance(*this));
}

double horizontal_illuminance_lx(const Sun& sun, const Compass& compass) {
    return to_photometric(sun.irradiance) * std::max(0.0, dot(sun.direction, compass.up));
}

Sky make_sky(const SkyDescription& description, double sun_horizontal_illuminance_lx) {
    if (const auto* general = std::get_if<CieGeneralSky>(&description.model))
        cie_general_parameters(general->type); // throws for a type outside [1, 15]
    const double colour_luminance = luminance_of(description.colour);
    if (!(colour_luminance > 0))
        throw InternalError("make_sky: the sky's colour has no luminance");
    const double rho = description.ground_reflectance.value_or(0);
    if (!(rho >= 0 && rho <= 1) || !(sun_horizontal_illuminance_lx >= 0))
        throw InternalError("make_sky: ground reflectance outside [0, 1] or negative sun");

    Sky sky;
    sky.model = description.model;
    sky.compass = description.compass;
    sky.sun_direction = description.sun_direction;
    sky.colour = description.colour / float(colour_luminance);
    sky.horizon = description.horizon;
    const double ratio = sky.horizontal_illuminance_per_zenith_luminance();
    const double zenith_luminance = std::visit(
        Overloaded{[&](const HorizontalIlluminance& e) { return ratio > 0 ? e.lx / ratio : 0.0; },
                   [](const ZenithLuminance& l) { return l.cd_m2; }},
        description.level);
    if (!(zenith_luminance >= 0) || !std::isfinite(zenith_luminance))
        throw InternalError("make_sky: the sky's level must be finite and >= 0");
    sky.zenith_radiance = zenith_luminance / k_luminous_efficacy_lm_per_w;
    if (description.ground_reflectance) {
        const double global_lx = zenith_luminance * ratio + sun_horizontal_illuminance_lx;
        sky.ground_radiance = rho * global_lx / (k_pi * k_luminous_efficacy_lm_per_w);
    }
    return sky;
}

} // namespace penumbra
