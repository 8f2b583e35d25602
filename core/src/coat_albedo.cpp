#include "coat_albedo.h"

#include <algorithm>
#include <cmath>

#include "core/microfacet.h"

namespace penumbra {

namespace {

/// Strata per axis of the visible-normal quadrature: its integrand F G2 / G1 lies in [0, 1]
/// and is smooth but where wi crosses the horizon, so 48² midpoints give E within ~1e-4.
constexpr int k_strata = 48;

/// The smallest μ and α the quadrature uses for the nodes at 0 (grazing view, smooth coat).
constexpr double k_min_node = 1e-4;

struct AlbedoPair {
    double plain = 0, fifth = 0;
};

/// E₁ and E₅ by a stratified midpoint rule over the visible-normal sample space: each sample's
/// weight G2 / G1(wo) (times (1 − wo·m)⁵ for E₅) estimates the integral exactly on average.
AlbedoPair integrate_albedo(double mu, double alpha) {
    const GgxDistribution ggx{std::max(alpha, k_min_node)};
    mu = std::max(mu, k_min_node);
    const Vec3 wo(std::sqrt(1.0 - mu * mu), 0, mu);
    AlbedoPair sum;
    for (int i = 0; i < k_strata; ++i)
        for (int j = 0; j < k_strata; ++j) {
            const Vec2 u{(i + 0.5) / k_strata, (j + 0.5) / k_strata};
            const Vec3 m = ggx.sample_visible_normal(wo, u);
            const Vec3 wi = reflect(wo, m);
            if (wi.z <= 0)
                continue;
            const double weight = ggx.g2(wo, wi) / ggx.g1(wo);
            sum.plain += weight;
            sum.fifth += weight * fresnel_schlick(0.0, dot(wo, m)); // (1 − wo·m)⁵
        }
    const double n = double(k_strata) * k_strata;
    return {sum.plain / n, sum.fifth / n};
}

/// 2 ∫ E(μ) μ dμ of the piecewise-linear interpolant through \p e at μ_i = i h: per segment
/// ∫ E μ dμ = h (E₀ (2μ₀ + μ₁) + E₁ (μ₀ + 2μ₁)) / 6.
double cosine_average(const std::vector<double>& e, int nodes) {
    const double h = 1.0 / (nodes - 1);
    double sum = 0;
    for (int i = 0; i + 1 < nodes; ++i) {
        const double m0 = i * h, m1 = (i + 1) * h;
        sum += h * (e[i] * (2 * m0 + m1) + e[i + 1] * (m0 + 2 * m1)) / 6.0;
    }
    return 2.0 * sum;
}

/// Bilinear weights of x ∈ [0, 1] on nodes i / (n − 1).
struct Cell {
    int i = 0;
    double t = 0;
};
Cell cell_of(double x, int nodes) {
    const double s = std::clamp(x, 0.0, 1.0) * (nodes - 1);
    const int i = std::min(int(s), nodes - 2);
    return {i, s - i};
}

Rgb combine(const LinearFresnel& f, double plain, double fifth) {
    return f.a * float(plain) + f.b * float(fifth);
}

} // namespace

CoatAlbedo::CoatAlbedo()
    : plain_(k_nodes * k_nodes), fifth_(k_nodes * k_nodes), plain_average_(k_nodes),
      fifth_average_(k_nodes) {
    for (int a = 0; a < k_nodes; ++a) {
        std::vector<double> plain_column(k_nodes), fifth_column(k_nodes);
        for (int m = 0; m < k_nodes; ++m) {
            const AlbedoPair e =
                integrate_albedo(double(m) / (k_nodes - 1), double(a) / (k_nodes - 1));
            plain_[m * k_nodes + a] = plain_column[m] = e.plain;
            fifth_[m * k_nodes + a] = fifth_column[m] = e.fifth;
        }
        plain_average_[a] = cosine_average(plain_column, k_nodes);
        fifth_average_[a] = cosine_average(fifth_column, k_nodes);
    }
}

const CoatAlbedo& CoatAlbedo::tables() {
    static const CoatAlbedo tables; // an immutable table, built once (thread-safe)
    return tables;
}

Rgb CoatAlbedo::directional(double mu, double alpha, const LinearFresnel& fresnel) const {
    const Cell m = cell_of(mu, k_nodes), a = cell_of(alpha, k_nodes);
    auto lerp2 = [&](auto&& table) {
        const double low = (1 - a.t) * table(m.i, a.i) + a.t * table(m.i, a.i + 1);
        const double high = (1 - a.t) * table(m.i + 1, a.i) + a.t * table(m.i + 1, a.i + 1);
        return (1 - m.t) * low + m.t * high;
    };
    return combine(fresnel, lerp2([&](int i, int j) { return plain(i, j); }),
                   lerp2([&](int i, int j) { return fifth(i, j); }));
}

Rgb CoatAlbedo::average(double alpha, const LinearFresnel& fresnel) const {
    const Cell a = cell_of(alpha, k_nodes);
    const double plain = (1 - a.t) * plain_average_[a.i] + a.t * plain_average_[a.i + 1];
    const double fifth = (1 - a.t) * fifth_average_[a.i] + a.t * fifth_average_[a.i + 1];
    return combine(fresnel, plain, fifth);
}

} // namespace penumbra
