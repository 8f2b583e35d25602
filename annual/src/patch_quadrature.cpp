// The rules: n × n Gauss–Legendre nodes per patch, n = max(2, ⌈4 / MF⌉) far from the sun and
// max(3, ⌈8 / MF⌉) for patches within a row's height of it; the zenith cap 8 × 8. A patch's
// mean is then within 3e-4 of a converged one (tests/annual/sky_matrix_test.cpp), with about
// 2 600 directions per hour for MF 1 and 9 500 for MF 4.

#include "patch_quadrature.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/rgb.h"

namespace penumbra::annual {

namespace {

constexpr double k_deg = k_pi / 180;
constexpr int k_cap_nodes = 8;

/// Gauss–Legendre nodes and weights of order \p n on [−1, 1] (Newton's method on P_n).
struct GaussRule {
    std::vector<double> x, w;
};

GaussRule gauss_legendre(int n) {
    GaussRule rule;
    for (int i = 0; i < n; ++i) {
        double t = std::cos(k_pi * (i + 0.75) / (n + 0.5)), derivative = 1;
        for (int iteration = 0; iteration < 100; ++iteration) {
            double p0 = 1, p1 = t;
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2 * k - 1) * t * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            derivative = n * (t * p1 - p0) / (t * t - 1);
            const double step = p1 / derivative;
            t -= step;
            if (std::abs(step) < 1e-15)
                break;
        }
        rule.x.push_back(t);
        rule.w.push_back(2 / ((1 - t * t) * derivative * derivative));
    }
    return rule;
}

template <class Nodes>
void add_patch_nodes(const SkyPatch& patch, const Compass& compass, const GaussRule& rule,
                     Nodes& nodes) {
    const double z0 = std::sin(patch.altitude_min_deg * k_deg);
    const double z1 = std::sin(patch.altitude_max_deg * k_deg);
    const double phi0 = patch.azimuth_min_deg * k_deg, phi1 = patch.azimuth_max_deg * k_deg;
    const double half_z = (z1 - z0) / 2, half_phi = (phi1 - phi0) / 2;
    const double normalise = half_z * half_phi / patch.solid_angle_sr;
    for (std::size_t i = 0; i < rule.x.size(); ++i) {
        const double z = z0 + half_z * (rule.x[i] + 1);
        const double horizontal = std::sqrt(std::max(0.0, 1 - z * z));
        for (std::size_t j = 0; j < rule.x.size(); ++j) {
            const double phi = phi0 + half_phi * (rule.x[j] + 1);
            nodes.directions.push_back(
                (compass.north * std::cos(phi) + compass.east() * std::sin(phi)) * horizontal +
                compass.up * z);
            nodes.weights.push_back(rule.w[i] * rule.w[j] * normalise);
        }
    }
}

/// The largest angle from a patch's centre to its corners (radians): how far from the centre
/// a direction inside it can be.
double angular_radius(const SkyPatch& patch, const Compass& compass) {
    double radius = 0;
    for (double altitude : {patch.altitude_min_deg, patch.altitude_max_deg})
        for (double azimuth : {patch.azimuth_min_deg, patch.azimuth_max_deg})
            radius = std::max(
                radius, std::acos(std::clamp(
                            dot(patch.centre, compass.direction(altitude, azimuth)), -1.0, 1.0)));
    return radius;
}

} // namespace

PatchQuadrature::PatchQuadrature(const SkyPatches& patches) {
    const int mf = patches.subdivision();
    const GaussRule coarse = gauss_legendre(std::max(2, (4 + mf - 1) / mf));
    const GaussRule fine = gauss_legendre(std::max(3, (8 + mf - 1) / mf));
    const GaussRule cap = gauss_legendre(k_cap_nodes);
    const double margin = patches.row_height_deg() * k_deg;
    for (Nodes* nodes : {&coarse_, &fine_})
        nodes->first.push_back(0); // the ground has no nodes: its radiance is uniform
    centres_.push_back(patches[SkyPatches::ground].centre);
    near_sun_cos_.push_back(1);
    for (std::size_t p = 1; p < patches.size(); ++p) {
        const bool is_cap = p + 1 == patches.size();
        coarse_.first.push_back(coarse_.directions.size());
        fine_.first.push_back(fine_.directions.size());
        add_patch_nodes(patches[p], patches.compass(), is_cap ? cap : coarse, coarse_);
        add_patch_nodes(patches[p], patches.compass(), is_cap ? cap : fine, fine_);
        centres_.push_back(patches[p].centre);
        near_sun_cos_.push_back(
            std::cos(std::min(k_pi, angular_radius(patches[p], patches.compass()) + margin)));
    }
    coarse_.first.push_back(coarse_.directions.size());
    fine_.first.push_back(fine_.directions.size());
}

void PatchQuadrature::mean_radiance(const Sky& sky, std::span<float> out) const {
    if (out.size() != centres_.size())
        throw InternalError("PatchQuadrature::mean_radiance: wrong output size");
    // This hour's rule: each patch's nodes from the fine or the coarse set.
    std::vector<Vec3> directions;
    std::vector<double> weights;
    std::vector<std::size_t> first{0, 0};
    for (std::size_t p = 1; p < centres_.size(); ++p) {
        const Nodes& nodes =
            dot(sky.sun_direction, centres_[p]) >= near_sun_cos_[p] ? fine_ : coarse_;
        const auto begin = std::ptrdiff_t(nodes.first[p]), end = std::ptrdiff_t(nodes.first[p + 1]);
        directions.insert(directions.end(), nodes.directions.begin() + begin,
                          nodes.directions.begin() + end);
        weights.insert(weights.end(), nodes.weights.begin() + begin, nodes.weights.begin() + end);
        first.push_back(directions.size());
    }
    std::vector<Rgb> radiance(directions.size());
    sky.radiance(directions, radiance);
    out[0] = float(sky.ground_radiance.value_or(0.0));
    for (std::size_t p = 1; p < centres_.size(); ++p) {
        double mean = 0;
        for (std::size_t k = first[p]; k < first[p + 1]; ++k)
            mean += weights[k] * to_photometric(radiance[k]);
        out[p] = float(mean / k_luminous_efficacy_lm_per_w);
    }
}

} // namespace penumbra::annual
