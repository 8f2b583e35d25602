// The tables of the cluster links (see links/cluster_tables.h).

#include "links/cluster_tables.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra::solver {

namespace {

/// Source ends are drawn by area × (radiosity + this × the brightest root's radiosity).
constexpr double k_exitance_floor = 1e-3;

float round_down(double x) {
    const float f = float(x);
    return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float round_up(double x) {
    const float f = float(x);
    return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

/// A receiver whose direction from a cluster source's centroid is within this sine of the
/// source's normal gives no offset (planar_direction, seen_offset).
constexpr double k_min_slope_sine = 0.05;

} // namespace

// A source end is drawn by exitance (area × radiosity), so that the rays' visible fraction is
// that of the light it sends: dark parts of a cluster are the occluded ones more often than
// not (under desks, in corners), and drawing by area made cluster links carry too little.
// The floor keeps the parts of a cluster without radiosity yet (reflectors before the first
// solve) drawn by area.
void ClusterTables::weigh_sources(const std::vector<Rgb>& b) {
    double peak = 0;
    for (std::uint32_t r : dfs_roots_)
        peak = std::max(peak, double(b[r].max_component()));
    const double floor = peak > 0 ? k_exitance_floor * peak : 1.0; // no light: by area
    dfs_exitance_.assign(dfs_roots_.size() + 1, 0.0);
    for (std::size_t k = 0; k < dfs_roots_.size(); ++k) {
        const std::uint32_t r = dfs_roots_[k];
        dfs_exitance_[k + 1] =
            dfs_exitance_[k] + h_.area[r] * (double(b[r].max_component()) + floor);
    }
}

ClusterTables::ClusterTables(const Hierarchy& h, const ClusterTree& tree,
                             const std::vector<Lobes>& exitance, const std::vector<Lobes>& emitted,
                             const std::vector<float>& peak, const std::vector<float>& departure)
    : h_(h), tree_(&tree), exitance_(&exitance), emitted_(&emitted), peak_(&peak),
      departure_(&departure) {
    pull_lobes(tree, h_, std::vector<Rgb>(h_.root_count, Rgb(1.0f)), area_lobes_);
    dfs_roots_.clear();
    root_begin_.assign(tree.size(), 0);
    root_end_.assign(tree.size(), 0);
    auto visit = [&](auto&& self, std::uint32_t c) -> void {
        root_begin_[c] = std::uint32_t(dfs_roots_.size());
        for (std::uint32_t k = tree.child_begin[c]; k < tree.child_begin[c + 1]; ++k) {
            const NodeRef child = tree.children[k];
            if (is_cluster(child))
                self(self, cluster_index(child));
            else
                dfs_roots_.push_back(child);
        }
        root_end_[c] = std::uint32_t(dfs_roots_.size());
    };
    if (tree.size() > 0)
        visit(visit, 0);
    dfs_area_.assign(dfs_roots_.size() + 1, 0.0);
    dfs_plane_.resize(dfs_roots_.size());
    for (std::size_t k = 0; k < dfs_roots_.size(); ++k) {
        const std::uint32_t r = dfs_roots_[k];
        dfs_area_[k + 1] = dfs_area_[k] + h_.area[r];
        dfs_plane_[k] = {h_.normal[r], dot(h_.normal[r], h_.triangle[r][0])};
    }
    dfs_exitance_ = dfs_area_; // until refine() weighs the sources by their radiosity
    specular_only_.assign(tree.size(), 0);
    for (std::size_t c = 0; c < tree.size(); ++c) {
        const auto roots = cluster_roots(std::uint32_t(c));
        specular_only_[c] = std::all_of(roots.begin(), roots.end(),
                                        [&](std::uint32_t r) { return h_.specular_only[r] != 0; });
    }
    build_boundaries();
    occluders_ = OccluderPlanes(h_);
    // Lobe bounds, children before parents (parents precede their children in the tree).
    constexpr float inf = std::numeric_limits<float>::infinity();
    lobe_bounds_.assign(tree.size(), {});
    for (auto& lobes : lobe_bounds_)
        lobes.fill({inf, inf, inf, -inf, -inf, -inf});
    auto merge = [](std::array<float, 6>& into, const std::array<float, 6>& box) {
        for (int k = 0; k < 3; ++k) {
            into[std::size_t(k)] = std::min(into[std::size_t(k)], box[std::size_t(k)]);
            into[std::size_t(k + 3)] = std::max(into[std::size_t(k + 3)], box[std::size_t(k + 3)]);
        }
    };
    for (std::size_t c = tree.size(); c-- > 0;)
        for (std::uint32_t k = tree.child_begin[c]; k < tree.child_begin[c + 1]; ++k) {
            const NodeRef child = tree.children[k];
            if (is_cluster(child)) {
                for (std::size_t l = 0; l < 6; ++l)
                    merge(lobe_bounds_[c][l], lobe_bounds_[cluster_index(child)][l]);
                continue;
            }
            std::array<float, 6> box{inf, inf, inf, -inf, -inf, -inf};
            for (const Vec3& v : h_.triangle[child])
                for (std::size_t a = 0; a < 3; ++a) {
                    box[a] = std::min(box[a], round_down(v[a]));
                    box[a + 3] = std::max(box[a + 3], round_up(v[a]));
                }
            const Vec3& n = h_.normal[child];
            for (std::size_t a = 0; a < 3; ++a)
                if (std::abs(n[a]) > k_lobe_component)
                    merge(lobe_bounds_[c][std::size_t(lobe_index(int(a), n[a]))], box);
        }
}

bool ClusterTables::emits(NodeRef n) const {
    if (!is_cluster(n))
        return !h_.emission[n].is_black();
    const std::uint32_t c = cluster_index(n);
    for (const Rgb& lobe : (*emitted_)[c])
        if (!lobe.is_black())
            return true;
    return false;
}

// Directed boundary edges of every face cluster, children before parents: a cluster's
// boundary is its children's (a root's: its three edges, wound counter-clockwise about the
// plane's normal) less the edges that appear both ways. Vertices shared by roots are the
// same doubles (the mesh's), so an interior edge's two directions compare equal.
void ClusterTables::build_boundaries() {
    const ClusterTree& tree = *tree_;
    std::vector<std::vector<BoundaryEdge>> edges(tree.size());
    auto root_edges = [&](std::uint32_t r, const Vec3& normal, std::vector<BoundaryEdge>& out) {
        const auto& t = h_.triangle[r];
        const bool ccw = dot(cross(t[1] - t[0], t[2] - t[0]), normal) >= 0;
        for (std::uint8_t k = 0; k < 3; ++k) {
            const auto next = std::uint8_t((k + 1) % 3);
            out.push_back(ccw ? BoundaryEdge{r, k, next} : BoundaryEdge{r, next, k});
        }
    };
    auto point = [&](std::uint32_t r, std::uint8_t corner) -> const Vec3& {
        return h_.triangle[r][corner];
    };
    auto key = [&](const Vec3& a, const Vec3& b) {
        return std::array<double, 6>{a.x, a.y, a.z, b.x, b.y, b.z};
    };
    for (std::size_t c = tree.size(); c-- > 0;) {
        if (!tree.planar[c])
            continue;
        std::vector<BoundaryEdge> all;
        for (std::uint32_t k = tree.child_begin[c]; k < tree.child_begin[c + 1]; ++k) {
            const NodeRef child = tree.children[k];
            if (is_cluster(child)) {
                std::vector<BoundaryEdge>& part = edges[cluster_index(child)];
                all.insert(all.end(), part.begin(), part.end());
            } else {
                root_edges(child, tree.normal[c], all);
            }
        }
        // Cancel an edge against its reverse.
        std::vector<std::pair<std::array<double, 6>, std::uint32_t>> keyed(all.size());
        for (std::size_t i = 0; i < all.size(); ++i)
            keyed[i] = {key(point(all[i].root, all[i].from), point(all[i].root, all[i].to)),
                        std::uint32_t(i)};
        std::sort(keyed.begin(), keyed.end());
        std::vector<BoundaryEdge>& out = edges[c];
        for (std::size_t i = 0; i < all.size(); ++i) {
            const BoundaryEdge& e = all[i];
            const Vec3 &a = point(e.root, e.from), &b = point(e.root, e.to);
            const auto reverse = key(b, a);
            const auto it = std::lower_bound(
                keyed.begin(), keyed.end(), reverse,
                [](const auto& x, const std::array<double, 6>& k) { return x.first < k; });
            if (it == keyed.end() || it->first != reverse)
                out.push_back(e);
        }
    }
    boundary_begin_.assign(tree.size() + 1, 0);
    boundary_.clear();
    for (std::size_t c = 0; c < tree.size(); ++c) {
        merge_collinear(edges[c], boundary_);
        boundary_begin_[c + 1] = std::uint32_t(boundary_.size());
    }
    boundary_.shrink_to_fit();
    // An emitting face cluster is an exact source when its emission is uniform (a lamp's
    // panel, not a lamp and the ceiling around it): the vertices of its receivers gather it
    // exactly, root by root.
    exact_source_.assign(tree.size(), 0);
    for (std::size_t c = 0; c < tree.size(); ++c) {
        if (!tree.planar[c])
            continue;
        const Rgb& first = h_.emission[dfs_roots_[root_begin_[c]]];
        bool uniform = true;
        for (std::uint32_t k = root_begin_[c]; k < root_end_[c] && uniform; ++k)
            uniform = h_.emission[dfs_roots_[k]] == first;
        exact_source_[c] = uniform;
    }
}

// A tessellated wall's boundary is its outline cut at every tessellation vertex: a 5 x 5
// wall of 50 triangles has 20 boundary edges and 4 straight runs. A vertex joins two edges
// into a run where it starts one edge and ends one other, the two in line.
void ClusterTables::merge_collinear(const std::vector<BoundaryEdge>& edges,
                                    std::vector<ContourEdge>& out) const {
    const std::size_t n = edges.size();
    auto start = [&](std::size_t i) -> const Vec3& {
        return h_.triangle[edges[i].root][edges[i].from];
    };
    auto end = [&](std::size_t i) -> const Vec3& {
        return h_.triangle[edges[i].root][edges[i].to];
    };
    auto key = [](const Vec3& v) { return std::array<double, 3>{v.x, v.y, v.z}; };
    // Edges by their start and by their end point.
    std::vector<std::pair<std::array<double, 3>, std::uint32_t>> starts(n), ends(n);
    for (std::size_t i = 0; i < n; ++i) {
        starts[i] = {key(start(i)), std::uint32_t(i)};
        ends[i] = {key(end(i)), std::uint32_t(i)};
    }
    std::sort(starts.begin(), starts.end());
    std::sort(ends.begin(), ends.end());
    auto range = [](const auto& sorted, const std::array<double, 3>& k) {
        return std::equal_range(sorted.begin(), sorted.end(), std::pair(k, std::uint32_t(0)),
                                [](const auto& x, const auto& y) { return x.first < y.first; });
    };
    constexpr std::uint32_t none = ~std::uint32_t(0);
    std::vector<std::uint32_t> next(n, none);
    std::vector<std::uint8_t> continues(n, 0); // the run of the edge before goes on into it
    for (std::size_t i = 0; i < n; ++i) {
        const auto k = key(end(i));
        const auto [s0, s1] = range(starts, k);
        const auto [e0, e1] = range(ends, k);
        if (s1 - s0 != 1 || e1 - e0 != 1)
            continue; // not a simple vertex of the outline
        const std::uint32_t j = s0->second;
        const Vec3 a = end(i) - start(i), b = end(j) - start(j);
        // In line to a relative 1e-9: the sliver between the run and its edges is ~1e-9 of
        // their length squared.
        if (dot(a, b) > 0 && length(cross(a, b)) <= 1e-9 * length(a) * length(b)) {
            next[i] = j;
            continues[j] = 1;
        }
    }
    std::vector<std::uint8_t> done(n, 0);
    auto emit = [&](std::size_t first, std::size_t last) {
        out.push_back({edges[first].root, edges[last].root, edges[first].from, edges[last].to});
    };
    for (std::size_t i = 0; i < n; ++i) {
        if (continues[i] || done[i])
            continue;
        std::size_t last = i;
        done[i] = 1;
        while (next[last] != none && !done[next[last]]) {
            last = next[last];
            done[last] = 1;
        }
        emit(i, last);
    }
    for (std::size_t i = 0; i < n; ++i) // edges of a run with no start (none in a plane)
        if (!done[i])
            emit(i, i);
}

Rgb ClusterTables::face_mean(std::uint32_t c, const std::vector<Lobes>& lobes) const {
    return lobe_projection(lobes[c], tree_->normal[c]) * float(1.0 / tree_->area[c]);
}

Rgb ClusterTables::exact_source_radiosity(const ClusterLink& link, const Rgb& mean,
                                          const std::vector<Slope>& gradient) const {
    if (gradient.empty() || link.d.y == 0)
        return mean;
    const Rgb seen = mean + slope_along(gradient[cluster_index(link.source)],
                                        exact_source_direction(link) * double(link.d.y));
    return Rgb(std::max(seen.r, 0.0f), std::max(seen.g, 0.0f), std::max(seen.b, 0.0f));
}

Vec3 ClusterTables::node_centroid(NodeRef n) const {
    return is_cluster(n) ? tree_->centroid[cluster_index(n)] : h_.centroid(n);
}

Vec3 ClusterTables::exact_source_direction(const ClusterLink& link) const {
    return planar_direction(link.source, link.receiver);
}

Vec3 ClusterTables::planar_direction(NodeRef from, NodeRef toward) const {
    if (!is_cluster(from))
        return {};
    const std::uint32_t c = cluster_index(from);
    const Vec3 delta = node_centroid(toward) - tree_->centroid[c];
    const Vec3& n = tree_->normal[c];
    const Vec3 along = delta - n * dot(n, delta);
    const double len = length(along);
    // An end (nearly) straight above: what it sees of `from` is centred, not off along a
    // direction.
    if (!(len > k_min_slope_sine * length(delta)))
        return {};
    return along / len;
}

Vec3 ClusterTables::exact_slope(const ClusterLink& link) const {
    if (!is_cluster(link.receiver))
        return {};
    return exact_slope(link, Frame::from_normal(tree_->normal[cluster_index(link.receiver)]));
}

} // namespace penumbra::solver
