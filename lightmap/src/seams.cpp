// Seam stitching: seams found as chart-boundary edges with the same 3D corners, the texels
// of their bilinear footprints solved by least squares (Iwanicki 2013).

#include "lightmap/seams.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>

namespace penumbra::lightmap {

namespace {

// One boundary edge of a chart, from corner p to corner q, with their atlas coordinates.
struct BoundaryEdge {
    std::uint32_t chart = 0, atlas = 0;
    Vec3 p, q;
    Vec2 uv_p, uv_q;
    Vec3 normal; ///< of the chart's triangle along it
};

std::vector<BoundaryEdge> boundary_edges(const Charts& charts, const AtlasLayout& layout) {
    std::vector<BoundaryEdge> out;
    for (std::uint32_t c = 0; c < charts.charts.size(); ++c) {
        const Chart& chart = charts.charts[c];
        std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
        for (const ChartTriangle& t : chart.triangles)
            for (std::size_t k = 0; k < 3; ++k) {
                const std::uint32_t a = t.vertices[k], b = t.vertices[(k + 1) % 3];
                ++uses[{std::min(a, b), std::max(a, b)}];
            }
        const ChartPlacement& place = layout.placements[c];
        for (const ChartTriangle& t : chart.triangles)
            for (std::size_t k = 0; k < 3; ++k) {
                const std::uint32_t a = t.vertices[k], b = t.vertices[(k + 1) % 3];
                if (uses[{std::min(a, b), std::max(a, b)}] != 1)
                    continue;
                out.push_back({c, place.atlas, chart.vertices[a].position,
                               chart.vertices[b].position, place.texel_uv[a], place.texel_uv[b],
                               t.normal});
            }
    }
    return out;
}

using CornerKey = std::array<std::int64_t, 3>;

CornerKey corner_key(const Vec3& p, double cell) {
    return {std::int64_t(std::llround(p.x / cell)), std::int64_t(std::llround(p.y / cell)),
            std::int64_t(std::llround(p.z / cell))};
}

// Samples of the seam between edges \p a and \p b (b runs along a when \p same_direction).
void add_seam(const BoundaryEdge& a, const BoundaryEdge& b, bool same_direction,
              std::vector<SeamSample>& out) {
    const Vec2 b0 = same_direction ? b.uv_p : b.uv_q, b1 = same_direction ? b.uv_q : b.uv_p;
    const double texels = std::max(length(a.uv_q - a.uv_p), length(b1 - b0));
    const int n = std::max(2, int(std::ceil(3 * texels)));
    for (int s = 0; s < n; ++s) {
        const double t = (s + 0.5) / n;
        out.push_back({a.atlas, b.atlas, a.uv_p + (a.uv_q - a.uv_p) * t, b0 + (b1 - b0) * t});
    }
}

// The four texels of a bilinear lookup at atlas coordinates \p uv and their weights.
struct Footprint {
    std::array<int, 4> x{}, y{};
    std::array<double, 4> w{};
};

Footprint footprint(const Vec2& uv, int size) {
    const double fx = uv.x - 0.5, fy = uv.y - 0.5;
    const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    const double tx = fx - x0, ty = fy - y0;
    Footprint f;
    for (int k = 0; k < 4; ++k) {
        const int dx = k & 1, dy = k >> 1;
        f.x[std::size_t(k)] = std::clamp(x0 + dx, 0, size - 1);
        f.y[std::size_t(k)] = std::clamp(y0 + dy, 0, size - 1);
        f.w[std::size_t(k)] = (dx ? tx : 1 - tx) * (dy ? ty : 1 - ty);
    }
    return f;
}

RgbD lookup(const Image& image, const Vec2& uv) {
    const Footprint f = footprint(uv, image.width);
    RgbD sum;
    for (std::size_t k = 0; k < 4; ++k)
        sum += RgbD(image.at(f.x[k], f.y[k])) * f.w[k];
    return sum;
}

} // namespace

Seams find_seams(const Charts& charts, const AtlasLayout& layout, double weld_tolerance_m,
                 double max_crease_deg) {
    const double min_cos = std::cos(max_crease_deg * k_pi / 180.0);
    const std::vector<BoundaryEdge> edges = boundary_edges(charts, layout);
    const double cell = 4 * weld_tolerance_m;
    std::map<std::pair<CornerKey, CornerKey>, std::vector<std::uint32_t>> by_corners;
    for (std::uint32_t i = 0; i < edges.size(); ++i) {
        const CornerKey p = corner_key(edges[i].p, cell), q = corner_key(edges[i].q, cell);
        by_corners[{std::min(p, q), std::max(p, q)}].push_back(i);
    }
    Seams seams;
    for (const auto& [corners, list] : by_corners)
        for (std::size_t i = 0; i < list.size(); ++i)
            for (std::size_t j = i + 1; j < list.size(); ++j) {
                const BoundaryEdge& a = edges[list[i]];
                const BoundaryEdge& b = edges[list[j]];
                if (dot(a.normal, b.normal) < min_cos)
                    continue;
                const bool same = corner_key(a.p, cell) == corner_key(b.p, cell);
                add_seam(a, b, same, seams.samples);
                ++seams.edges;
            }
    return seams;
}

SeamError seam_error(const std::vector<Image>& atlases, const std::vector<SeamSample>& samples) {
    SeamError e;
    for (const SeamSample& s : samples) {
        const RgbD a = lookup(atlases[s.atlas_a], s.uv_a), b = lookup(atlases[s.atlas_b], s.uv_b);
        const double d = std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
        e.mean += d;
        e.max = std::max(e.max, d);
    }
    if (!samples.empty())
        e.mean /= double(samples.size());
    return e;
}

SeamStitch stitch_seams(std::vector<Image>& atlases, const Seams& seams, double weight) {
    SeamStitch r;
    r.edges = seams.edges;
    r.samples = seams.samples.size();
    r.before = seam_error(atlases, seams.samples);
    // Unknowns: the footprints' texels, numbered in (atlas, y, x) order.
    using TexelKey = std::tuple<std::uint32_t, int, int>;
    std::map<TexelKey, int> index;
    std::vector<std::array<std::pair<int, double>, 8>> rows;
    for (const SeamSample& s : seams.samples) {
        const Footprint fa = footprint(s.uv_a, atlases[s.atlas_a].width);
        const Footprint fb = footprint(s.uv_b, atlases[s.atlas_b].width);
        for (std::size_t k = 0; k < 4; ++k) {
            index.emplace(TexelKey{s.atlas_a, fa.y[k], fa.x[k]}, 0);
            index.emplace(TexelKey{s.atlas_b, fb.y[k], fb.x[k]}, 0);
        }
    }
    int next = 0;
    for (auto& [key, i] : index)
        i = next++;
    for (const SeamSample& s : seams.samples) {
        const Footprint fa = footprint(s.uv_a, atlases[s.atlas_a].width);
        const Footprint fb = footprint(s.uv_b, atlases[s.atlas_b].width);
        std::array<std::pair<int, double>, 8> row;
        for (std::size_t k = 0; k < 4; ++k) {
            row[k] = {index.at({s.atlas_a, fa.y[k], fa.x[k]}), weight * fa.w[k]};
            row[k + 4] = {index.at({s.atlas_b, fb.y[k], fb.x[k]}), -weight * fb.w[k]};
        }
        rows.push_back(row);
    }
    // Normal equations (I + Σ r rᵀ) x = x₀: symmetric positive definite.
    std::vector<Eigen::Triplet<double>> triplets;
    for (int i = 0; i < next; ++i)
        triplets.emplace_back(i, i, 1.0);
    for (const auto& row : rows)
        for (const auto& [i, wi] : row)
            for (const auto& [j, wj] : row)
                triplets.emplace_back(i, j, wi * wj);
    Eigen::SparseMatrix<double> m(next, next);
    m.setFromTriplets(triplets.begin(), triplets.end());
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
    cg.setTolerance(1e-8);
    cg.compute(m);
    r.texels = std::size_t(next);
    for (int c = 0; c < 3; ++c) {
        Eigen::VectorXd x0(next);
        for (const auto& [key, i] : index)
            x0[i] = atlases[std::get<0>(key)].at(std::get<2>(key), std::get<1>(key))[c];
        const Eigen::VectorXd x = cg.solveWithGuess(x0, x0);
        r.iterations = std::max(r.iterations, int(cg.iterations()));
        for (const auto& [key, i] : index)
            atlases[std::get<0>(key)].at(std::get<2>(key), std::get<1>(key))[c] = float(x[i]);
    }
    r.after = seam_error(atlases, seams.samples);
    return r;
}

} // namespace penumbra::lightmap
