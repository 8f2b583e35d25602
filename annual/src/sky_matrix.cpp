// Sky vectors: each patch's mean radiance by a product Gauss–Legendre rule in (sin altitude,
// azimuth), the coordinates in which dω = d(sin alt) dφ is uniform, so the weights of a patch
// sum to its solid angle exactly. The rule's size shrinks as the patches do: n × n nodes per
// patch with n = max(3, ⌈8 / MF⌉) (9 280 over the sky for MF 1 and 2, 20 800 for MF 4); the
// zenith cap keeps 8 × 8. A patch's mean is then within 3e-4 of a converged one even where
// the circumsolar peak's cusp lies inside it (2 × 2 nodes: 1.4e-3).

#include "annual/sky_matrix.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "core/error.h"
#include "core/parallel.h"
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

/// Every sky patch's quadrature directions, with weights that sum to 1 over each patch (so
/// that the weighted sum of radiances is the patch's mean).
struct PatchQuadrature {
    std::vector<Vec3> directions;
    std::vector<double> weights;
    std::vector<std::size_t> first; ///< per patch, into directions; size() + 1 entries
};

void add_patch_nodes(const SkyPatch& patch, const Compass& compass, const GaussRule& rule,
                     PatchQuadrature& q) {
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
            q.directions.push_back(
                (compass.north * std::cos(phi) + compass.east() * std::sin(phi)) * horizontal +
                compass.up * z);
            q.weights.push_back(rule.w[i] * rule.w[j] * normalise);
        }
    }
}

PatchQuadrature patch_quadrature(const SkyPatches& patches) {
    const int subdivision = patches.subdivision();
    const GaussRule band_rule = gauss_legendre(std::max(3, (8 + subdivision - 1) / subdivision));
    const GaussRule cap_rule = gauss_legendre(k_cap_nodes);
    PatchQuadrature q;
    q.first.push_back(0); // the ground has no nodes: its radiance is uniform
    for (std::size_t p = 1; p < patches.size(); ++p) {
        q.first.push_back(q.directions.size());
        add_patch_nodes(patches[p], patches.compass(),
                        p + 1 == patches.size() ? cap_rule : band_rule, q);
    }
    q.first.push_back(q.directions.size());
    return q;
}

/// \p sky's mean radiance over each patch into \p out (patches.size() entries).
template <class Out> void fill_sky_vector(const Sky& sky, const PatchQuadrature& q, Out&& out) {
    std::vector<Rgb> radiance(q.directions.size());
    sky.radiance(q.directions, radiance);
    out(0) = float(sky.ground_radiance.value_or(0.0));
    for (std::size_t p = 1; p + 1 < q.first.size(); ++p) {
        double mean = 0;
        for (std::size_t k = q.first[p]; k < q.first[p + 1]; ++k)
            mean += q.weights[k] * to_photometric(radiance[k]);
        out(Eigen::Index(p)) = float(mean / k_luminous_efficacy_lm_per_w);
    }
}

/// The hour's solar components from the fields \p input names.
SolarComponents components(const Weather& weather, const WeatherHour& h, WeatherInput input) {
    if (input == WeatherInput::irradiance)
        return SolarIrradiance{h.direct_normal_w_m2, h.diffuse_horizontal_w_m2};
    const auto required = [&](const std::optional<double>& value, int field, const char* name) {
        if (!value)
            throw InputError(weather.file, fmt::format("field {} ({})", field, name),
                             "missing (blank or 999900), and the illuminance sky needs it", h.line);
        return *value;
    };
    return SolarIlluminance{
        required(h.direct_normal_lx, 18, "direct normal illuminance"),
        required(h.diffuse_horizontal_lx, 19, "diffuse horizontal illuminance")};
}

bool has_daylight(const SolarComponents& c) {
    return std::visit(
        [](const auto& given) {
            const auto [direct, diffuse] = given;
            return direct + diffuse > 0;
        },
        c);
}

} // namespace

Eigen::VectorXf sky_vector(const Sky& sky, const SkyPatches& patches) {
    Eigen::VectorXf vector(Eigen::Index(patches.size()));
    fill_sky_vector(sky, patch_quadrature(patches), vector);
    return vector;
}

SkyMatrix sky_matrix(const Weather& weather, const SkyPatches& patches,
                     const SkyMatrixOptions& options, const Context& ctx) {
    if (!(options.ground_reflectance >= 0 && options.ground_reflectance <= 1))
        throw ConfigError(
            fmt::format("ground reflectance {} is outside [0, 1]", options.ground_reflectance));
    const std::size_t hours = weather.hours.size();
    std::vector<SolarComponents> weather_of_hour;
    for (const WeatherHour& h : weather.hours) // serially: the first bad line is the one named
        weather_of_hour.push_back(components(weather, h, options.input));

    const PatchQuadrature q = patch_quadrature(patches);
    const Compass& compass = patches.compass();
    SkyMatrix m;
    m.radiance = Eigen::MatrixXf::Zero(Eigen::Index(patches.size()), Eigen::Index(hours));
    m.suns.resize(hours);
    run_in_arena(ctx, [&] {
        parallel_for_index(hours, 8, [&](std::size_t i) {
            HourSun& sun = m.suns[i];
            sun.angles = sun_position(weather, i);
            sun.direction = compass.direction(sun.angles.altitude_deg, sun.angles.azimuth_deg);
            if (!has_daylight(weather_of_hour[i]))
                return; // night: the column stays zero
            const PerezSkyAndSun hour =
                perez_sky_and_sun(weather_of_hour[i], compass, sun.direction,
                                  day_of_year(weather, i), options.ground_reflectance);
            if (hour.sun)
                sun.normal_lx = to_photometric(hour.sun->irradiance);
            fill_sky_vector(hour.sky, q, m.radiance.col(Eigen::Index(i)));
        });
    });
    return m;
}

} // namespace penumbra::annual
