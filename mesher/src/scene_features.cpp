#include "scene_features.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace penumbra::mesher {

namespace {

using Key = std::tuple<std::int64_t, std::int64_t, std::int64_t>;

Key key_of(const Vec3& p, double cell) {
    return {std::int64_t(std::llround(p.x / cell)), std::int64_t(std::llround(p.y / cell)),
            std::int64_t(std::llround(p.z / cell))};
}

void add_unique(std::vector<std::uint32_t>& list, std::uint32_t s) {
    if (std::find(list.begin(), list.end(), s) == list.end())
        list.push_back(s);
}

Vec3 farthest_from_line(const Surface& s, const Vec3& a, const Vec3& b) {
    const Vec3 d = normalize(b - a);
    Vec3 best = a;
    double best_dist = -1;
    for (const Vec3& v : s.outline) {
        const Vec3 off = (v - a) - d * dot(v - a, d);
        if (length(off) > best_dist) {
            best_dist = length(off);
            best = v;
        }
    }
    return best;
}

} // namespace

Features collect_features(const std::vector<Surface>& surfaces, double merge) {
    const double cell = std::max(merge, 1e-12);
    Features out;
    std::map<Key, std::uint32_t> vertex_of;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> edge_of;
    for (const Surface& s : surfaces) {
        const std::size_t n = s.outline.size();
        std::vector<std::uint32_t> ids;
        for (const Vec3& p : s.outline) {
            auto [it, fresh] =
                vertex_of.try_emplace(key_of(p, cell), std::uint32_t(out.vertices.size()));
            if (fresh)
                out.vertices.push_back({p, {}, {}});
            ids.push_back(it->second);
        }
        for (std::size_t k = 0; k < n; ++k) {
            FeatureVertex& v = out.vertices[ids[k]];
            add_unique(v.surfaces, s.id);
            v.neighbours.push_back(s.outline[(k + n - 1) % n]);
            v.neighbours.push_back(s.outline[(k + 1) % n]);
            const std::uint32_t i = ids[k], j = ids[(k + 1) % n];
            if (i == j)
                continue;
            auto [it, fresh] = edge_of.try_emplace({std::min(i, j), std::max(i, j)},
                                                   std::uint32_t(out.edges.size()));
            if (fresh)
                out.edges.push_back({s.outline[k], s.outline[(k + 1) % n], {}, {}});
            FeatureEdge& e = out.edges[it->second];
            if (std::find(e.surfaces.begin(), e.surfaces.end(), s.id) == e.surfaces.end()) {
                e.surfaces.push_back(s.id);
                e.wings.push_back(farthest_from_line(s, e.a, e.b));
            }
        }
    }
    return out;
}

} // namespace penumbra::mesher
