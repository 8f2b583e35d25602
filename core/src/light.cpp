#include "core/light.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"

namespace penumbra {

namespace {

double cos_deg(double deg) {
    return std::cos(deg * k_pi / 180.0);
}

// The helper for std::visit with one lambda per kind.
template <typename... F> struct Overloaded : F... { using F::operator()...; };
template <typename... F> Overloaded(F...) -> Overloaded<F...>;

constexpr int k_index_bits = 30;
constexpr std::uint32_t k_index_mask = (std::uint32_t(1) << k_index_bits) - 1;

// The index a source of its kind carries (0 for the sun and the sky).
std::uint32_t source_index(const LightSource& source) {
    return std::visit(Overloaded{[](const AreaSource& s) { return s.polygon; },
                                 [](const PointSource& s) { return s.index; },
                                 [](const auto&) { return std::uint32_t(0); }},
                      source);
}

} // namespace

double PointLight::profile_cos(double cos_theta) const {
    if (!spot)
        return 1.0;
    const double cos_beam = cos_deg(spot->beam_deg), cos_cutoff = cos_deg(spot->cutoff_deg);
    if (cos_theta >= cos_beam)
        return 1.0;
    if (cos_theta <= cos_cutoff)
        return 0.0;
    const double t = (cos_theta - cos_cutoff) / (cos_beam - cos_cutoff);
    return t * t * (3.0 - 2.0 * t);
}

double PointLight::profile(const Vec3& unit_dir) const {
    return spot ? profile_cos(dot(unit_dir, spot->direction)) : 1.0;
}

double PointLight::profile_solid_angle() const {
    if (!spot)
        return 4.0 * k_pi;
    const double cos_beam = cos_deg(spot->beam_deg), cos_cutoff = cos_deg(spot->cutoff_deg);
    return 2.0 * k_pi * ((1.0 - cos_beam) + 0.5 * (cos_beam - cos_cutoff));
}

RgbD PointLight::power() const {
    return RgbD(intensity) * profile_solid_angle();
}

double Sun::angular_radius() const {
    return 0.5 * angular_diameter_deg * k_pi / 180.0;
}

Rgb Sun::unoccluded(const Vec3& n) const {
    return irradiance * float(std::max(0.0, dot(n, direction)));
}

bool at_infinity(const LightSource& source) {
    return std::holds_alternative<SunSource>(source) || std::holds_alternative<SkySource>(source);
}

std::string describe(const LightSource& source) {
    return std::visit(
        Overloaded{[](const AreaSource& s) { return fmt::format("polygon {}", s.polygon); },
                   [](const PointSource& s) { return fmt::format("point light {}", s.index); },
                   [](const SunSource&) { return std::string("the sun"); },
                   [](const SkySource&) { return std::string("the sky"); }},
        source);
}

int source_code(const LightSource& source) {
    if (const auto* area = std::get_if<AreaSource>(&source))
        return int(area->polygon);
    if (const auto* point = std::get_if<PointSource>(&source))
        return -2 - int(point->index);
    if (std::holds_alternative<SunSource>(source))
        return -1;
    throw InternalError(fmt::format("no source code for {}", describe(source)));
}

LightId::LightId(const LightSource& source) {
    const std::uint32_t index = source_index(source);
    if (index > k_index_mask)
        throw InternalError(
            fmt::format("LightId: {} does not fit in {} bits", describe(source), k_index_bits));
    bits_ = std::uint32_t(source.index()) << k_index_bits | index;
}

LightSource LightId::source() const {
    const std::uint32_t index = bits_ & k_index_mask;
    switch (bits_ >> k_index_bits) {
    case 0:
        return AreaSource{index};
    case 1:
        return PointSource{index};
    case 2:
        return SunSource{};
    default:
        return SkySource{};
    }
}

} // namespace penumbra
