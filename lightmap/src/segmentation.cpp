// Chart segmentation. Planar regions first, so that a planar face of any size stays one
// undistorted chart; curved parts (regions of one or a few triangles) are then grown into
// charts by normal deviation from their seed, which bounds how far LSCM has to bend them.

#include "segmentation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <numeric>
#include <set>

namespace penumbra::lightmap {

namespace {

Vec3 centroid(const InputMesh& mesh, std::uint32_t t) {
    const auto& c = mesh.triangles[t].corners;
    return (mesh.positions[c[0]] + mesh.positions[c[1]] + mesh.positions[c[2]]) / 3.0;
}

bool fits_plane(const InputMesh& mesh, std::uint32_t t, const Vec3& normal, const Vec3& origin,
                double cos_angle, double max_distance) {
    if (dot(mesh.triangles[t].normal, normal) < cos_angle)
        return false;
    for (std::uint32_t v : mesh.triangles[t].corners)
        if (std::abs(dot(mesh.positions[v] - origin, normal)) > max_distance)
            return false;
    return true;
}

// The parts of \p subset (ascending) connected through manifold edges, each ascending, in
// order of their smallest triangle.
std::vector<std::vector<std::uint32_t>> connected_parts(const InputMesh& mesh,
                                                        const std::vector<std::uint32_t>& subset) {
    auto index_of = [&](std::uint32_t t) {
        const auto it = std::lower_bound(subset.begin(), subset.end(), t);
        return it != subset.end() && *it == t ? std::ptrdiff_t(it - subset.begin())
                                              : std::ptrdiff_t(-1);
    };
    std::vector<bool> seen(subset.size(), false);
    std::vector<std::vector<std::uint32_t>> parts;
    for (std::size_t s = 0; s < subset.size(); ++s) {
        if (seen[s])
            continue;
        std::vector<std::uint32_t> part;
        std::deque<std::size_t> queue{s};
        seen[s] = true;
        while (!queue.empty()) {
            const std::uint32_t t = subset[queue.front()];
            queue.pop_front();
            part.push_back(t);
            for (const auto& n : mesh.neighbours[t]) {
                const std::ptrdiff_t i = n ? index_of(*n) : -1;
                if (i >= 0 && !seen[std::size_t(i)]) {
                    seen[std::size_t(i)] = true;
                    queue.push_back(std::size_t(i));
                }
            }
        }
        std::sort(part.begin(), part.end());
        parts.push_back(std::move(part));
    }
    return parts;
}

// The unit eigenvector of the largest eigenvalue of a symmetric 3 × 3 matrix (power
// iteration from its largest diagonal axis; enough to pick a cutting direction).
Vec3 principal_axis(const std::array<Vec3, 3>& m) {
    std::size_t start = 0;
    for (std::size_t i = 1; i < 3; ++i)
        if (m[i][i] > m[start][start])
            start = i;
    Vec3 v;
    v[start] = 1;
    for (int iteration = 0; iteration < 64; ++iteration) {
        const Vec3 w{dot(m[0], v), dot(m[1], v), dot(m[2], v)};
        if (!(length(w) > 0))
            break;
        v = normalize(w);
    }
    return v;
}

// Regions by object, then largest area first, then id.
std::vector<std::uint32_t> seed_order(const InputMesh& mesh, const PlanarRegions& regions) {
    std::vector<std::uint32_t> seeds(regions.normal.size());
    std::iota(seeds.begin(), seeds.end(), std::uint32_t(0));
    auto object_of = [&](std::uint32_t r) { return mesh.triangles[regions.members[r][0]].object; };
    std::sort(seeds.begin(), seeds.end(), [&](std::uint32_t a, std::uint32_t b) {
        if (object_of(a) != object_of(b))
            return object_of(a) < object_of(b);
        return regions.area_m2[a] > regions.area_m2[b] ||
               (regions.area_m2[a] == regions.area_m2[b] && a < b);
    });
    return seeds;
}

// One chart from \p seed: neighbouring regions not yet taken join, smallest deviation from the
// seed's normal first, when all their triangles lie within the deviation. Ascending triangles.
std::vector<std::uint32_t> grow_chart(const InputMesh& mesh, const PlanarRegions& regions,
                                      std::uint32_t seed, double cos_max,
                                      std::vector<bool>& taken) {
    const Vec3 axis = regions.normal[seed];
    if (regions.joined_collinear[seed]) {
        taken[seed] = true; // a chart of its own: CGAL's LSCM needs a manifold
        return regions.members[seed];
    }
    auto fits = [&](std::uint32_t r) {
        return !regions.joined_collinear[r] &&
               std::all_of(
                   regions.members[r].begin(), regions.members[r].end(),
                   [&](std::uint32_t t) { return dot(mesh.triangles[t].normal, axis) >= cos_max; });
    };
    std::vector<std::uint32_t> chart;
    std::set<std::pair<double, std::uint32_t>> frontier{{0.0, seed}}; // (deviation, region)
    std::set<std::uint32_t> tried{seed};
    while (!frontier.empty()) {
        const std::uint32_t r = frontier.begin()->second;
        frontier.erase(frontier.begin());
        if (r != seed && !fits(r))
            continue;
        taken[r] = true;
        chart.insert(chart.end(), regions.members[r].begin(), regions.members[r].end());
        for (std::uint32_t t : regions.members[r])
            for (const auto& n : mesh.neighbours[t]) {
                const std::uint32_t other = n ? regions.of_triangle[*n] : r;
                if (!taken[other] && tried.insert(other).second)
                    frontier.insert(
                        {std::acos(std::clamp(dot(regions.normal[other], axis), -1.0, 1.0)),
                         other});
            }
    }
    std::sort(chart.begin(), chart.end());
    return chart;
}

} // namespace

PlanarRegions find_planar_regions(const InputMesh& mesh, double max_angle_rad,
                                  double max_distance) {
    constexpr std::uint32_t unassigned = ~std::uint32_t(0);
    PlanarRegions regions;
    regions.of_triangle.assign(mesh.triangles.size(), unassigned);
    const double cos_angle = std::cos(max_angle_rad);
    for (std::uint32_t seed = 0; seed < mesh.triangles.size(); ++seed) {
        if (regions.of_triangle[seed] != unassigned)
            continue;
        const auto id = std::uint32_t(regions.normal.size());
        const Vec3 normal = mesh.triangles[seed].normal;
        const Vec3 origin = mesh.positions[mesh.triangles[seed].corners[0]];
        std::vector<std::uint32_t> members;
        std::deque<std::uint32_t> queue{seed};
        regions.of_triangle[seed] = id;
        double area = 0;
        bool collinear = false;
        auto join = [&](std::uint32_t n) {
            const bool joins = regions.of_triangle[n] == unassigned &&
                               fits_plane(mesh, n, normal, origin, cos_angle, max_distance);
            if (joins) {
                regions.of_triangle[n] = id;
                queue.push_back(n);
            }
            return joins;
        };
        while (!queue.empty()) {
            const std::uint32_t t = queue.front();
            queue.pop_front();
            members.push_back(t);
            area += mesh.triangles[t].area_m2;
            for (const auto& n : mesh.neighbours[t])
                if (n)
                    join(*n);
            for (std::uint32_t n : mesh.collinear_neighbours[t])
                collinear = join(n) || collinear;
        }
        std::sort(members.begin(), members.end());
        regions.joined_collinear.push_back(collinear);
        regions.normal.push_back(normal);
        regions.area_m2.push_back(area);
        regions.members.push_back(std::move(members));
    }
    return regions;
}

std::vector<std::vector<std::uint32_t>>
grow_charts(const InputMesh& mesh, const PlanarRegions& regions, double max_deviation_rad) {
    const double cos_max = std::cos(max_deviation_rad);
    std::vector<bool> taken(regions.normal.size(), false);
    std::vector<std::vector<std::uint32_t>> charts;
    for (std::uint32_t seed : seed_order(mesh, regions))
        if (!taken[seed])
            charts.push_back(grow_chart(mesh, regions, seed, cos_max, taken));
    return charts;
}

std::vector<std::vector<std::uint32_t>> split_chart(const InputMesh& mesh,
                                                    const std::vector<std::uint32_t>& triangles) {
    if (triangles.size() < 2)
        return {triangles};
    double total = 0;
    Vec3 mean;
    for (std::uint32_t t : triangles) {
        total += mesh.triangles[t].area_m2;
        mean += centroid(mesh, t) * mesh.triangles[t].area_m2;
    }
    mean = mean / total;
    std::array<Vec3, 3> covariance{};
    for (std::uint32_t t : triangles) {
        const Vec3 d = centroid(mesh, t) - mean;
        for (std::size_t i = 0; i < 3; ++i)
            covariance[i] += d * (d[i] * mesh.triangles[t].area_m2);
    }
    const Vec3 axis = principal_axis(covariance);
    std::vector<std::pair<double, std::uint32_t>> order;
    for (std::uint32_t t : triangles)
        order.push_back({dot(centroid(mesh, t), axis), t});
    std::sort(order.begin(), order.end());
    std::vector<std::uint32_t> halves[2];
    double area = 0;
    for (const auto& [key, t] : order) {
        // By the area before the triangle's middle: monotone, and the first triangle always
        // opens the first half.
        const double a = mesh.triangles[t].area_m2;
        halves[halves[0].empty() || area + 0.5 * a <= 0.5 * total ? 0 : 1].push_back(t);
        area += a;
    }
    if (halves[1].empty()) { // one triangle holds most of the area: cut off the last one
        halves[1].push_back(halves[0].back());
        halves[0].pop_back();
    }
    std::vector<std::vector<std::uint32_t>> parts;
    for (auto& half : halves) {
        std::sort(half.begin(), half.end());
        for (auto& part : connected_parts(mesh, half))
            parts.push_back(std::move(part));
    }
    return parts;
}

} // namespace penumbra::lightmap
