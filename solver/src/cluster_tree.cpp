#include "cluster_tree.h"

#include <algorithm>
#include <cmath>
#include <deque>

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

ClusterTree build_cluster_tree(const Hierarchy& h, std::size_t leaf_size) {
    ClusterTree tree;
    std::vector<std::uint32_t> order(h.root_count);
    std::vector<Vec3> centroid(h.root_count);
    for (std::uint32_t r = 0; r < h.root_count; ++r) {
        order[r] = r;
        centroid[r] = h.centroid(r);
    }
    struct Range {
        std::size_t begin, end;
        std::int32_t parent;
    };
    // Breadth first, so that parents precede children and every cluster's children are
    // appended together.
    std::deque<Range> queue{{0, order.size(), -1}};
    while (!queue.empty()) {
        const Range range = queue.front();
        queue.pop_front();
        const auto c = std::uint32_t(tree.size());
        BBox box, centres;
        double area = 0;
        for (std::size_t i = range.begin; i < range.end; ++i) {
            const std::uint32_t r = order[i];
            for (const Vec3& v : h.triangle[r])
                box.extend(v);
            centres.extend(centroid[r]);
            area += h.area[r];
        }
        tree.lo.push_back(box.lo);
        tree.hi.push_back(box.hi);
        tree.area.push_back(area);
        tree.parent.push_back(range.parent);
        tree.child_begin.push_back(std::uint32_t(tree.children.size()));
        if (range.end - range.begin <= leaf_size) {
            for (std::size_t i = range.begin; i < range.end; ++i)
                tree.children.push_back(order[i]);
            continue;
        }
        const Vec3 extent = centres.hi - centres.lo;
        const std::size_t axis = extent.x >= extent.y && extent.x >= extent.z
                                     ? 0
                                     : (extent.y >= extent.z ? 1 : 2);
        const std::size_t mid = (range.begin + range.end) / 2;
        std::nth_element(order.begin() + std::ptrdiff_t(range.begin),
                         order.begin() + std::ptrdiff_t(mid),
                         order.begin() + std::ptrdiff_t(range.end),
                         [&](std::uint32_t a, std::uint32_t b) {
                             const double ca = centroid[a][axis], cb = centroid[b][axis];
                             return ca != cb ? ca < cb : a < b;
                         });
        // Children get consecutive indices after every cluster already queued.
        const auto first = std::uint32_t(tree.size() + queue.size());
        tree.children.push_back(cluster_ref(first));
        tree.children.push_back(cluster_ref(first + 1));
        queue.push_back({range.begin, mid, std::int32_t(c)});
        queue.push_back({mid, range.end, std::int32_t(c)});
    }
    tree.child_begin.push_back(std::uint32_t(tree.children.size()));
    return tree;
}

void pull_lobes(const ClusterTree& tree, const Hierarchy& h, const std::vector<Rgb>& value,
                std::vector<Lobes>& out) {
    out.assign(tree.size(), Lobes{});
    for (std::size_t c = tree.size(); c-- > 0;) { // children after parents
        Lobes& sum = out[c];
        for (std::uint32_t k = tree.child_begin[c]; k < tree.child_begin[c + 1]; ++k) {
            const NodeRef child = tree.children[k];
            const Lobes part = is_cluster(child)
                                   ? out[cluster_index(child)]
                                   : surface_lobes(h.normal[child], h.area[child], value[child]);
            for (std::size_t l = 0; l < 6; ++l)
                sum[l] += part[l];
        }
    }
}

} // namespace penumbra::solver
