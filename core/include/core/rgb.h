#pragma once
// Linear RGB (Rec.709 primaries) and the one photometric conversion of the project.

#include <algorithm>
#include <cmath>

namespace penumbra {

/// \brief Linear RGB triple; radiometric (W, W/m², W/(sr·m²)) unless a name says otherwise.
struct Rgb {
    float r = 0, g = 0, b = 0;

    constexpr Rgb() = default;
    constexpr Rgb(float r_, float g_, float b_) : r(r_), g(g_), b(b_) {}
    constexpr explicit Rgb(float v) : r(v), g(v), b(v) {}

    constexpr float operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
    constexpr float& operator[](int i) { return i == 0 ? r : (i == 1 ? g : b); }
    constexpr Rgb operator+(const Rgb& o) const { return {r + o.r, g + o.g, b + o.b}; }
    constexpr Rgb operator-(const Rgb& o) const { return {r - o.r, g - o.g, b - o.b}; }
    constexpr Rgb operator*(const Rgb& o) const { return {r * o.r, g * o.g, b * o.b}; }
    constexpr Rgb operator*(float s) const { return {r * s, g * s, b * s}; }
    constexpr Rgb operator/(float s) const { return {r / s, g / s, b / s}; }
    constexpr Rgb& operator+=(const Rgb& o) {
        r += o.r;
        g += o.g;
        b += o.b;
        return *this;
    }
    constexpr Rgb& operator-=(const Rgb& o) {
        r -= o.r;
        g -= o.g;
        b -= o.b;
        return *this;
    }
    constexpr Rgb& operator*=(float s) {
        r *= s;
        g *= s;
        b *= s;
        return *this;
    }
    constexpr bool operator==(const Rgb& o) const = default;

    constexpr float max_component() const { return std::max(r, std::max(g, b)); }
    constexpr float sum() const { return r + g + b; }
    constexpr bool is_black() const { return r == 0 && g == 0 && b == 0; }
    bool is_finite() const { return std::isfinite(r) && std::isfinite(g) && std::isfinite(b); }
};

constexpr Rgb operator*(float s, const Rgb& c) {
    return c * s;
}

/// Double-precision RGB for global accumulations (total power, balances).
struct RgbD {
    double r = 0, g = 0, b = 0;
    constexpr RgbD() = default;
    constexpr RgbD(double r_, double g_, double b_) : r(r_), g(g_), b(b_) {}
    constexpr explicit RgbD(const Rgb& c) : r(c.r), g(c.g), b(c.b) {}
    constexpr RgbD operator+(const RgbD& o) const { return {r + o.r, g + o.g, b + o.b}; }
    constexpr RgbD operator-(const RgbD& o) const { return {r - o.r, g - o.g, b - o.b}; }
    constexpr RgbD operator*(double s) const { return {r * s, g * s, b * s}; }
    constexpr RgbD& operator+=(const RgbD& o) {
        r += o.r;
        g += o.g;
        b += o.b;
        return *this;
    }
    constexpr double sum() const { return r + g + b; }
    constexpr double max_component() const { return std::max(r, std::max(g, b)); }
};

// ---- Photometry -----------------------------------------------------------------------------
// Radiance's white-light convention: 179 lm/W and luminance weights (0.265, 0.670, 0.065), so
// that figures compare with Radiance (rtrace -I, rpict) and .rad scenes load unchanged.

/// Luminous efficacy of "white" radiometric RGB, lm/W (Radiance's WHTEFFICACY).
inline constexpr double k_luminous_efficacy_lm_per_w = 179.0;
inline constexpr double k_lum_weight_r = 0.265;
inline constexpr double k_lum_weight_g = 0.670;
inline constexpr double k_lum_weight_b = 0.065;

/// \brief The one radiometric → photometric conversion: RGB watts (or W/m², W/(sr·m²)) to
///        lumens (or lx, cd/m²). Applies to any matching pair of units.
constexpr double to_photometric(const RgbD& radiometric) {
    return k_luminous_efficacy_lm_per_w *
           (k_lum_weight_r * radiometric.r + k_lum_weight_g * radiometric.g +
            k_lum_weight_b * radiometric.b);
}
constexpr double to_photometric(const Rgb& radiometric) {
    return to_photometric(RgbD(radiometric));
}

/// \brief Radiometric RGB with colour \p color scaled so that its photometric value equals
///        \p photometric (lm, lx, cd or cd/m²). A black colour yields black.
constexpr Rgb from_photometric(double photometric, const Rgb& color) {
    double unit = to_photometric(color);
    return unit > 0 ? color * float(photometric / unit) : Rgb{};
}

} // namespace penumbra
