// Edges that meet along a line without sharing both ends: input models cut a planar face
// into pieces with T-junctions (a wall around a window, tiles of different sizes). Joining
// such pieces into one planar chart removes seams a lightmap would show between them.

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include "input_mesh.h"

namespace penumbra::lightmap {

namespace {

struct Edge {
    Vec3 a, b;
    std::uint32_t triangle;
};

// The edges without a manifold partner.
std::vector<Edge> open_edges(const InputMesh& mesh) {
    std::vector<Edge> edges;
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
        for (std::size_t k = 0; k < 3; ++k)
            if (!mesh.neighbours[t][k])
                edges.push_back({mesh.positions[mesh.triangles[t].corners[k]],
                                 mesh.positions[mesh.triangles[t].corners[(k + 1) % 3]], t});
    return edges;
}

bool meet_along_line(const Edge& e, const Edge& f, double tolerance) {
    const Vec3 d = e.b - e.a;
    const double len = length(d);
    if (!(len > tolerance) || dot(d, f.b - f.a) >= 0)
        return false; // opposite directions only: the two faces lie on either side
    const Vec3 u = d / len;
    auto off_line = [&](const Vec3& p) { return length(cross(p - e.a, u)); };
    if (off_line(f.a) > tolerance || off_line(f.b) > tolerance)
        return false;
    const double s0 = dot(f.a - e.a, u), s1 = dot(f.b - e.a, u);
    return std::min(len, std::max(s0, s1)) - std::max(0.0, std::min(s0, s1)) > tolerance;
}

// Candidate pairs from a hash grid over points sampled along each edge at half a cell: two
// edges that share a stretch of line have samples less than a cell apart, so in the same or
// adjacent cells.
class EdgeGrid {
public:
    using Key = std::array<std::int64_t, 3>;

    EdgeGrid(const std::vector<Edge>& edges, double cell) : cell_(cell), keys_(edges.size()) {
        for (std::uint32_t i = 0; i < edges.size(); ++i) {
            const double len = length(edges[i].b - edges[i].a);
            const int steps = std::max(1, int(std::ceil(2 * len / cell_)));
            for (int s = 0; s <= steps; ++s)
                keys_[i].push_back(
                    key(edges[i].a + (edges[i].b - edges[i].a) * (double(s) / steps)));
            std::sort(keys_[i].begin(), keys_[i].end());
            keys_[i].erase(std::unique(keys_[i].begin(), keys_[i].end()), keys_[i].end());
            for (const Key& k : keys_[i])
                cells_[k].push_back(i);
        }
    }

    /// Edges after \p i in the cells around \p i's samples, ascending.
    std::vector<std::uint32_t> candidates(std::uint32_t i) const {
        std::vector<std::uint32_t> out;
        for (const Key& k : keys_[i])
            for (std::int64_t dx = -1; dx <= 1; ++dx)
                for (std::int64_t dy = -1; dy <= 1; ++dy)
                    for (std::int64_t dz = -1; dz <= 1; ++dz) {
                        const auto it = cells_.find({k[0] + dx, k[1] + dy, k[2] + dz});
                        if (it == cells_.end())
                            continue;
                        for (std::uint32_t j : it->second)
                            if (j > i)
                                out.push_back(j);
                    }
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
        return out;
    }

private:
    struct KeyHash {
        std::size_t operator()(const Key& k) const {
            return std::size_t(k[0] * 73856093) ^ std::size_t(k[1] * 19349663) ^
                   std::size_t(k[2] * 83492791);
        }
    };
    Key key(const Vec3& p) const {
        return {std::int64_t(std::floor(p.x / cell_)), std::int64_t(std::floor(p.y / cell_)),
                std::int64_t(std::floor(p.z / cell_))};
    }
    double cell_;
    std::vector<std::vector<Key>> keys_;
    std::unordered_map<Key, std::vector<std::uint32_t>, KeyHash> cells_;
};

double median_length(const std::vector<Edge>& edges) {
    std::vector<double> lengths;
    for (const Edge& e : edges)
        lengths.push_back(length(e.b - e.a));
    std::nth_element(lengths.begin(), lengths.begin() + std::ptrdiff_t(lengths.size() / 2),
                     lengths.end());
    return lengths[lengths.size() / 2];
}

} // namespace

std::vector<std::vector<std::uint32_t>> find_collinear_neighbours(const InputMesh& mesh,
                                                                  double tolerance) {
    std::vector<std::vector<std::uint32_t>> result(mesh.triangles.size());
    const std::vector<Edge> edges = open_edges(mesh);
    if (edges.size() < 2)
        return result;
    const EdgeGrid grid(edges, std::max(median_length(edges), 1e3 * tolerance));
    for (std::uint32_t i = 0; i < edges.size(); ++i)
        for (std::uint32_t j : grid.candidates(i)) {
            const Edge &e = edges[i], &f = edges[j];
            if (e.triangle != f.triangle &&
                mesh.triangles[e.triangle].object == mesh.triangles[f.triangle].object &&
                meet_along_line(e, f, tolerance)) {
                result[e.triangle].push_back(f.triangle);
                result[f.triangle].push_back(e.triangle);
            }
        }
    // A triangle pair may meet along two edges.
    for (auto& list : result) {
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
    }
    return result;
}

} // namespace penumbra::lightmap
