#include "edge_refinement.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace penumbra::raytrace {

namespace {

// A random permutation of 0 … n − 1 (Fisher–Yates).
std::vector<int> shuffled(int n, Pcg32& rng) {
    std::vector<int> p(std::size_t(n), 0);
    std::iota(p.begin(), p.end(), 0);
    for (int i = n - 1; i > 0; --i)
        std::swap(p[std::size_t(i)], p[std::size_t(rng.next_u32() % std::uint32_t(i + 1))]);
    return p;
}

} // namespace

// Point (i, j) lies in cell row i, column j, at fine column j·n + px_j(i) and fine row
// i·n + py_i(j) for random permutations px per column and py per row.
std::vector<Vec2> multi_jittered(int n, Pcg32& rng) {
    std::vector<std::vector<int>> px, py;
    for (int k = 0; k < n; ++k) {
        px.push_back(shuffled(n, rng));
        py.push_back(shuffled(n, rng));
    }
    const double fine = 1.0 / (double(n) * double(n));
    std::vector<Vec2> points;
    points.reserve(std::size_t(n) * std::size_t(n));
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const auto u = std::size_t(i), v = std::size_t(j);
            points.push_back({(j * n + px[v][u] + double(rng.next_float())) * fine,
                              (i * n + py[u][v] + double(rng.next_float())) * fine});
        }
    return points;
}

int refined_strata(double range, const EdgeRefinement& refine) {
    if (!(refine.tolerance > 0) || !(range > 0))
        return 0;
    const double n = std::ceil(std::sqrt(range / refine.tolerance));
    return int(std::min(n, double(refine.max_samples_per_axis)));
}

double largest_around(std::span<const double> range, int width, int height, int x, int y) {
    double around = 0;
    for (int v = std::max(y - 1, 0); v <= std::min(y + 1, height - 1); ++v)
        for (int u = std::max(x - 1, 0); u <= std::min(x + 1, width - 1); ++u)
            around = std::max(around, range[std::size_t(v) * std::size_t(width) + std::size_t(u)]);
    return around;
}

} // namespace penumbra::raytrace
