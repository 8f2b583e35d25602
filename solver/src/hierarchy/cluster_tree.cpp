#include "hierarchy/cluster_tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <utility>

#include "core/disjoint_sets.h"

namespace penumbra::solver {

Rgb lobe_projection(const Lobes& lobes, const Vec3& v) {
    Rgb out;
    for (int a = 0; a < 3; ++a)
        out += lobes[std::size_t(lobe_index(a, v[std::size_t(a)]))] *
               float(std::abs(v[std::size_t(a)]));
    return out;
}

void lobe_deposit(Lobes& lobes, const Vec3& d, const Rgb& value) {
    for (int a = 0; a < 3; ++a)
        lobes[std::size_t(lobe_index(a, d[std::size_t(a)]))] +=
            value * float(std::abs(d[std::size_t(a)]));
}

Lobes surface_lobes(const Vec3& n, double area, const Rgb& value) {
    Lobes out{};
    lobe_deposit(out, n, value * float(area));
    return out;
}

namespace {

/// Items of at most this many roots are what the volume part of the tree splits.
constexpr std::size_t k_item_roots = 32;

// Splits order[begin, end) (indices into \p point) at its middle along the longest axis of
// their points' bounds; ties by index, so the split is deterministic.
std::size_t median_split(const std::vector<Vec3>& point, std::vector<std::uint32_t>& order,
                         std::size_t begin, std::size_t end) {
    BBox bounds;
    for (std::size_t i = begin; i < end; ++i)
        bounds.extend(point[order[i]]);
    const Vec3 extent = bounds.hi - bounds.lo;
    const std::size_t axis =
        extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const std::size_t mid = (begin + end) / 2;
    std::nth_element(order.begin() + std::ptrdiff_t(begin), order.begin() + std::ptrdiff_t(mid),
                     order.begin() + std::ptrdiff_t(end), [&](std::uint32_t a, std::uint32_t b) {
                         const double ca = point[a][axis], cb = point[b][axis];
                         return ca != cb ? ca < cb : a < b;
                     });
    return mid;
}

// Planar groups: roots of one oriented plane (up to rounding) connected through shared
// vertices, each listed by its smallest root, roots ascending.
std::vector<std::vector<std::uint32_t>> planar_groups(const Hierarchy& h) {
    const std::size_t n = h.root_count;
    const double step = 1e-7 * std::max(h.diagonal, 1e-9);
    auto q = [](double x, double unit) { return std::int64_t(std::llround(x / unit)); };
    using Key = std::array<std::int64_t, 7>; // plane (4), vertex (3)
    std::vector<std::pair<Key, std::uint32_t>> corners;
    corners.reserve(3 * n);
    for (std::uint32_t r = 0; r < n; ++r) {
        const Vec3& nn = h.normal[r];
        const double offset = dot(nn, h.triangle[r][0]);
        for (const Vec3& v : h.triangle[r])
            corners.push_back({Key{q(nn.x, 1e-6), q(nn.y, 1e-6), q(nn.z, 1e-6),
                                   q(offset, 1e3 * step), q(v.x, step), q(v.y, step), q(v.z, step)},
                               r});
    }
    std::sort(corners.begin(), corners.end());
    DisjointSets sets(n);
    for (std::size_t i = 1; i < corners.size(); ++i)
        if (corners[i].first == corners[i - 1].first)
            sets.unite(corners[i].second, corners[i - 1].second);
    std::vector<std::vector<std::uint32_t>> groups;
    std::vector<std::int64_t> index(n, -1);
    for (std::uint32_t r = 0; r < n; ++r) {
        const std::uint32_t g = sets.find(r);
        if (index[g] < 0) {
            index[g] = std::int64_t(groups.size());
            groups.emplace_back();
        }
        groups[std::size_t(index[g])].push_back(r);
    }
    return groups;
}

// The clusters of \p tree by depth, for its levels.
ClusterLevels cluster_levels(const ClusterTree& tree) {
    std::vector<std::uint32_t> depth(tree.size(), 0);
    std::uint32_t deepest = 0;
    for (std::size_t c = 0; c < tree.size(); ++c) { // parents before children
        if (tree.parent[c] >= 0)
            depth[c] = depth[std::size_t(tree.parent[c])] + 1;
        deepest = std::max(deepest, depth[c]);
    }
    ClusterLevels levels;
    levels.begin.assign(tree.size() > 0 ? deepest + 2 : 1, 0);
    for (std::uint32_t d : depth)
        ++levels.begin[d + 1];
    for (std::size_t d = 1; d < levels.begin.size(); ++d)
        levels.begin[d] += levels.begin[d - 1];
    levels.order.resize(tree.size());
    std::vector<std::uint32_t> next(levels.begin.begin(), levels.begin.end() - 1);
    for (std::size_t c = 0; c < tree.size(); ++c)
        levels.order[next[depth[c]]++] = std::uint32_t(c);
    return levels;
}

} // namespace

// Roots are first gathered into planar groups (the quads of a tessellated wall), and groups
// cut by median splits into items of at most k_item_roots roots; the tree's upper part splits
// sets of whole items (at the median of their centroids), its lower part an item's roots. So
// the clusters below an item are planar, like face clusters (Willmott et al. 1999), rather
// than slices through whatever surfaces a median cut meets.
ClusterTree build_cluster_tree(const Hierarchy& h, std::size_t leaf_size) {
    ClusterTree tree;
    std::vector<Vec3> centroid(h.root_count);
    for (std::uint32_t r = 0; r < h.root_count; ++r)
        centroid[r] = h.centroid(r);
    // Items: the contiguous ranges order[starts[i], starts[i + 1]), emitted in increasing
    // order (groups one after another, each depth first, the lower half first).
    std::vector<std::uint32_t> order;
    order.reserve(h.root_count);
    std::vector<std::size_t> starts;
    for (std::vector<std::uint32_t>& group : planar_groups(h)) {
        const std::size_t base = order.size();
        order.insert(order.end(), group.begin(), group.end());
        std::vector<std::pair<std::size_t, std::size_t>> stack{{base, order.size()}};
        while (!stack.empty()) {
            const auto [b, e] = stack.back();
            stack.pop_back();
            if (e - b <= k_item_roots) {
                starts.push_back(b);
                continue;
            }
            const std::size_t mid = median_split(centroid, order, b, e);
            stack.push_back({mid, e});
            stack.push_back({b, mid});
        }
    }
    starts.push_back(order.size());
    const std::size_t items = starts.size() - 1;
    std::vector<Vec3> item_centre(items);
    for (std::size_t i = 0; i < items; ++i) {
        double area = 0;
        Vec3 sum;
        for (std::size_t k = starts[i]; k < starts[i + 1]; ++k) {
            sum += centroid[order[k]] * h.area[order[k]];
            area += h.area[order[k]];
        }
        item_centre[i] = area > 0 ? sum / area : centroid[order[starts[i]]];
    }
    std::vector<std::uint32_t> item_order(items);
    for (std::uint32_t i = 0; i < items; ++i)
        item_order[i] = i;
    struct Range {
        std::size_t begin, end; ///< over item_order (items) or order (roots)
        bool of_items;
        std::int32_t parent;
    };
    auto for_roots = [&](const Range& range, auto&& fn) {
        if (!range.of_items) {
            for (std::size_t i = range.begin; i < range.end; ++i)
                fn(order[i]);
            return;
        }
        for (std::size_t k = range.begin; k < range.end; ++k)
            for (std::size_t i = starts[item_order[k]]; i < starts[item_order[k] + 1]; ++i)
                fn(order[i]);
    };
    // Breadth first, so that parents precede children and every cluster's children are
    // appended together.
    std::deque<Range> queue;
    if (items > 0)
        queue.push_back({0, items, true, -1});
    while (!queue.empty()) {
        Range range = queue.front();
        queue.pop_front();
        if (range.of_items && range.end - range.begin == 1) // one item: its roots
            range = {starts[item_order[range.begin]], starts[item_order[range.begin] + 1], false,
                     range.parent};
        const auto c = std::uint32_t(tree.size());
        BBox box;
        double area = 0;
        Vec3 moment;
        std::size_t count = 0;
        for_roots(range, [&](std::uint32_t r) {
            for (const Vec3& v : h.triangle[r])
                box.extend(v);
            area += h.area[r];
            moment += centroid[r] * h.area[r];
            ++count;
        });
        tree.lo.push_back(box.lo);
        tree.hi.push_back(box.hi);
        tree.area.push_back(area);
        tree.centroid.push_back(area > 0 ? moment / area : (box.lo + box.hi) * 0.5);
        tree.parent.push_back(range.parent);
        tree.planar.push_back(range.of_items ? 0 : 1);
        tree.normal.push_back(range.of_items ? Vec3{} : h.normal[order[range.begin]]);
        tree.child_begin.push_back(std::uint32_t(tree.children.size()));
        if (count <= leaf_size) {
            for_roots(range, [&](std::uint32_t r) { tree.children.push_back(r); });
            continue;
        }
        const std::size_t mid = range.of_items
                                    ? median_split(item_centre, item_order, range.begin, range.end)
                                    : median_split(centroid, order, range.begin, range.end);
        // Children get consecutive indices after every cluster already queued.
        const auto first = std::uint32_t(tree.size() + queue.size());
        tree.children.push_back(cluster_ref(first));
        tree.children.push_back(cluster_ref(first + 1));
        queue.push_back({range.begin, mid, range.of_items, std::int32_t(c)});
        queue.push_back({mid, range.end, range.of_items, std::int32_t(c)});
    }
    tree.child_begin.push_back(std::uint32_t(tree.children.size()));
    tree.levels = cluster_levels(tree);
    return tree;
}

void pull_lobes(const ClusterTree& tree, const Hierarchy& h, const std::vector<Rgb>& value,
                std::vector<Lobes>& out) {
    out.assign(tree.size(), Lobes{});
    for_each_cluster_by_level(tree, true, [&](std::uint32_t c) {
        Lobes& sum = out[c];
        for (std::uint32_t k = tree.child_begin[c]; k < tree.child_begin[c + 1]; ++k) {
            const NodeRef child = tree.children[k];
            const Lobes part = is_cluster(child)
                                   ? out[cluster_index(child)]
                                   : surface_lobes(h.normal[child], h.area[child], value[child]);
            for (std::size_t l = 0; l < 6; ++l)
                sum[l] += part[l];
        }
    });
}

// Moments about the origin, summed bottom-up in double (a cluster's small spread about its
// centroid is their difference), then the 2 × 2 normal equations in the plane's frame.
void planar_gradients(const ClusterTree& tree, const Hierarchy& h, const std::vector<Rgb>& value,
                      std::vector<Slope>& out, std::vector<float>* departure) {
    struct Moments {
        double a = 0;                ///< Σ A
        Vec3 ax;                     ///< Σ A x
        std::array<double, 6> axx{}; ///< Σ A x xᵀ: xx, yy, zz, xy, xz, yz
        std::array<double, 3> av{};  ///< Σ A v, per channel
        std::array<Vec3, 3> avx{};   ///< Σ A v x, per channel
        void add(const Moments& o) {
            a += o.a;
            ax += o.ax;
            for (std::size_t k = 0; k < 6; ++k)
                axx[k] += o.axx[k];
            for (std::size_t k = 0; k < 3; ++k) {
                av[k] += o.av[k];
                avx[k] += o.avx[k];
            }
        }
    };
    std::vector<Moments> m(tree.size());
    out.assign(tree.size(), Slope{});
    if (departure)
        departure->assign(tree.size(), 0.0f);
    for_each_cluster_by_level(tree, true, [&](std::uint32_t c) {
        if (!tree.planar[c])
            return;
        Moments& sum = m[c];
        for (std::uint32_t k = tree.child_begin[c]; k < tree.child_begin[c + 1]; ++k) {
            const NodeRef child = tree.children[k];
            if (is_cluster(child)) {
                sum.add(m[cluster_index(child)]);
                continue;
            }
            const double a = h.area[child];
            const Vec3 x = h.centroid(child);
            const Rgb& v = value[child];
            Moments root;
            root.a = a;
            root.ax = x * a;
            root.axx = {a * x.x * x.x, a * x.y * x.y, a * x.z * x.z,
                        a * x.x * x.y, a * x.x * x.z, a * x.y * x.z};
            const double channel[3] = {v.r, v.g, v.b};
            for (std::size_t k2 = 0; k2 < 3; ++k2) {
                root.av[k2] = a * channel[k2];
                root.avx[k2] = x * (a * channel[k2]);
            }
            sum.add(root);
        }
        if (!(sum.a > 0))
            return;
        const Vec3 mean = sum.ax / sum.a;
        // Covariance of the centroids and covariance of value with position, about the mean.
        const double cov[3][3] = {
            {sum.axx[0] / sum.a - mean.x * mean.x, sum.axx[3] / sum.a - mean.x * mean.y,
             sum.axx[4] / sum.a - mean.x * mean.z},
            {sum.axx[3] / sum.a - mean.x * mean.y, sum.axx[1] / sum.a - mean.y * mean.y,
             sum.axx[5] / sum.a - mean.y * mean.z},
            {sum.axx[4] / sum.a - mean.x * mean.z, sum.axx[5] / sum.a - mean.y * mean.z,
             sum.axx[2] / sum.a - mean.z * mean.z}};
        auto quadratic = [&](const Vec3& u, const Vec3& w) {
            const double uu[3] = {u.x, u.y, u.z}, ww[3] = {w.x, w.y, w.z};
            double q = 0;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    q += uu[i] * cov[i][j] * ww[j];
            return q;
        };
        const Frame frame = Frame::from_normal(tree.normal[c]);
        const double css = quadratic(frame.s, frame.s), ctt = quadratic(frame.t, frame.t);
        const double cst = quadratic(frame.s, frame.t);
        Vec3 gradient[3];
        for (std::size_t k = 0; k < 3; ++k) {
            const Vec3 b = sum.avx[k] / sum.a - mean * (sum.av[k] / sum.a);
            gradient[k] = fit_gradient(frame, css, ctt, cst, dot(b, frame.s), dot(b, frame.t));
        }
        for (std::size_t axis = 0; axis < 3; ++axis)
            out[c][axis] =
                Rgb(float(gradient[0][axis]), float(gradient[1][axis]), float(gradient[2][axis]));
        if (!departure)
            return;
        // The fit at every root below (a face cluster holds at most one item's roots).
        double worst = 0;
        thread_local std::vector<std::uint32_t> stack;
        stack.assign(1, c);
        while (!stack.empty()) {
            const std::uint32_t d = stack.back();
            stack.pop_back();
            for (std::uint32_t k = tree.child_begin[d]; k < tree.child_begin[d + 1]; ++k) {
                const NodeRef child = tree.children[k];
                if (is_cluster(child)) {
                    stack.push_back(cluster_index(child));
                    continue;
                }
                const Vec3 offset = h.centroid(child) - mean;
                const double fitted[3] = {sum.av[0] / sum.a + dot(gradient[0], offset),
                                          sum.av[1] / sum.a + dot(gradient[1], offset),
                                          sum.av[2] / sum.a + dot(gradient[2], offset)};
                const Rgb& v = value[child];
                worst = std::max({worst, std::abs(v.r - fitted[0]), std::abs(v.g - fitted[1]),
                                  std::abs(v.b - fitted[2])});
            }
        }
        (*departure)[c] = float(2.0 * worst);
    });
}

} // namespace penumbra::solver
