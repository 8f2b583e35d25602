#include "lightmap/sh.h"

#include <cmath>

namespace penumbra::lightmap {

namespace {

// The basis's normalisation constants: √(1/4π), √(3/4π), √(15/4π), √(5/16π), √(15/16π).
const double k_y00 = 0.5 * std::sqrt(1.0 / k_pi);
const double k_y1 = std::sqrt(3.0 / (4.0 * k_pi));
const double k_y2 = std::sqrt(15.0 / (4.0 * k_pi));
const double k_y20 = std::sqrt(5.0 / (16.0 * k_pi));
const double k_y22 = std::sqrt(15.0 / (16.0 * k_pi));

} // namespace

std::array<double, k_sh_l2_count> sh_basis_l2(const Vec3& d) {
    return {k_y00,
            k_y1 * d.y,
            k_y1 * d.z,
            k_y1 * d.x,
            k_y2 * d.x * d.y,
            k_y2 * d.y * d.z,
            k_y20 * (3.0 * d.z * d.z - 1.0),
            k_y2 * d.x * d.z,
            k_y22 * (d.x * d.x - d.y * d.y)};
}

double sh_cosine_lobe_band(int l) {
    constexpr double a[] = {k_pi, 2.0 * k_pi / 3.0, k_pi / 4.0};
    return a[l];
}

void ShL2::add(const Vec3& d, const RgbD& radiance, double weight) {
    const auto y = sh_basis_l2(d);
    for (int k = 0; k < k_sh_l2_count; ++k)
        c[std::size_t(k)] += radiance * (weight * y[std::size_t(k)]);
}

RgbD ShL2::evaluate(const Vec3& n) const {
    const auto y = sh_basis_l2(n);
    RgbD sum;
    for (int k = 0; k < k_sh_l2_count; ++k)
        sum += c[std::size_t(k)] * y[std::size_t(k)];
    return sum;
}

RgbD ShL2::evaluate_l1(const Vec3& n) const {
    const auto y = sh_basis_l2(n);
    RgbD sum;
    for (int k = 0; k < k_sh_l1_count; ++k)
        sum += c[std::size_t(k)] * y[std::size_t(k)];
    return sum;
}

ShL2 irradiance_from_radiance(const ShL2& radiance) {
    ShL2 out;
    for (int k = 0; k < k_sh_l2_count; ++k)
        out.c[std::size_t(k)] = radiance.c[std::size_t(k)] * sh_cosine_lobe_band(sh_band(k));
    return out;
}

} // namespace penumbra::lightmap
