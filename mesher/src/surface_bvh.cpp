#include "surface_bvh.h"

#include <algorithm>
#include <array>
#include <limits>

namespace penumbra::mesher {

namespace {

Vec3 centre(const BBox& b) {
    return (b.lo + b.hi) * 0.5;
}

bool boxes_overlap(const BBox& a, const BBox& b) {
    return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y &&
           a.lo.z <= b.hi.z && b.lo.z <= a.hi.z;
}

// The box widened by a relative epsilon, so that flat boxes of planar surfaces are never
// missed by the slab test.
BBox padded(const BBox& b) {
    BBox out = b;
    for (std::size_t k = 0; k < 3; ++k) {
        const double pad = 1e-9 * (std::abs(b.hi[k]) + std::abs(b.lo[k])) + 1e-12;
        out.lo[k] = b.lo[k] - pad;
        out.hi[k] = b.hi[k] + pad;
    }
    return out;
}

// Slab test of the ray against a padded box.
bool ray_hits_box(const BBox& b, const Vec3& o, const Vec3& inv, double t0, double t1) {
    for (std::size_t k = 0; k < 3; ++k) {
        double ta = (b.lo[k] - o[k]) * inv[k], tb = (b.hi[k] - o[k]) * inv[k];
        if (ta > tb)
            std::swap(ta, tb);
        if (std::isnan(ta) || std::isnan(tb))
            continue; // zero direction component and origin on the slab boundary
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 > t1)
            return false;
    }
    return true;
}

} // namespace

bool SurfaceBvh::ignored(std::uint32_t s, std::span<const std::uint32_t> skip, Meets meets) const {
    return std::find(skip.begin(), skip.end(), s) != skip.end() ||
           (meets == Meets::opaque && !surfaces_[s].opaque);
}

SurfaceBvh::SurfaceBvh(const std::vector<Surface>& surfaces) : surfaces_(surfaces) {
    order_.resize(surfaces.size());
    for (std::uint32_t i = 0; i < order_.size(); ++i)
        order_[i] = i;
    if (!order_.empty())
        build(0, std::uint32_t(order_.size()));
    ray_boxes_.reserve(nodes_.size());
    for (const Node& node : nodes_)
        ray_boxes_.push_back(padded(node.box));
    // Hits at exactly equal t go to the surface met first by the depth-first traversal that
    // pops the right child first (the order first_hit always had); rank them once.
    tie_rank_.resize(surfaces.size());
    std::uint32_t rank = 0;
    std::vector<std::int32_t> stack;
    if (!nodes_.empty())
        stack.push_back(0);
    while (!stack.empty()) {
        const Node& node = nodes_[std::size_t(stack.back())];
        stack.pop_back();
        if (node.left >= 0) {
            stack.push_back(node.left);
            stack.push_back(node.right);
            continue;
        }
        for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
            tie_rank_[order_[i]] = rank++;
    }
}

std::int32_t SurfaceBvh::build(std::uint32_t first, std::uint32_t count) {
    const auto index = std::int32_t(nodes_.size());
    nodes_.emplace_back();
    BBox box, centres;
    for (std::uint32_t i = first; i < first + count; ++i) {
        const BBox& b = surfaces_[order_[i]].box;
        box.extend(b.lo);
        box.extend(b.hi);
        centres.extend(centre(b));
    }
    nodes_[std::size_t(index)].box = box;
    if (count <= 4) {
        nodes_[std::size_t(index)].first = first;
        nodes_[std::size_t(index)].count = count;
        return index;
    }
    const Vec3 extent = centres.hi - centres.lo;
    const int axis =
        extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const std::uint32_t half = count / 2;
    std::nth_element(order_.begin() + first, order_.begin() + first + half,
                     order_.begin() + first + count, [&](std::uint32_t a, std::uint32_t b) {
                         const double ca = centre(surfaces_[a].box)[std::size_t(axis)];
                         const double cb = centre(surfaces_[b].box)[std::size_t(axis)];
                         return ca < cb || (ca == cb && a < b);
                     });
    const std::int32_t left = build(first, half);
    const std::int32_t right = build(first + half, count - half);
    nodes_[std::size_t(index)].left = left;
    nodes_[std::size_t(index)].right = right;
    nodes_[std::size_t(index)].axis = std::uint8_t(axis);
    return index;
}

std::vector<std::uint32_t> SurfaceBvh::overlapping(const BBox& box) const {
    std::vector<std::uint32_t> out;
    if (nodes_.empty())
        return out;
    std::vector<std::int32_t> stack{0};
    while (!stack.empty()) {
        const Node& node = nodes_[std::size_t(stack.back())];
        stack.pop_back();
        if (!boxes_overlap(node.box, box))
            continue;
        if (node.left < 0) {
            for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
                if (boxes_overlap(surfaces_[order_[i]].box, box))
                    out.push_back(order_[i]);
            continue;
        }
        stack.push_back(node.left);
        stack.push_back(node.right);
    }
    std::sort(out.begin(), out.end());
    return out;
}

template <typename Visit>
void SurfaceBvh::traverse(const Vec3& origin, const Vec3& dir, double t0, double& t1,
                          Visit&& visit) const {
    if (nodes_.empty())
        return;
    const Vec3 inv(1.0 / dir.x, 1.0 / dir.y, 1.0 / dir.z);
    std::array<std::int32_t, 128> stack{};
    std::size_t top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const std::size_t index = std::size_t(stack[--top]);
        if (!ray_hits_box(ray_boxes_[index], origin, inv, t0, t1))
            continue;
        const Node& node = nodes_[index];
        if (node.left >= 0) {
            // The child nearer along the ray is popped first, so that t1 shrinks early: the
            // left one holds the lower half along the split axis.
            const bool left_first = dir[node.axis] >= 0;
            stack[top++] = left_first ? node.right : node.left;
            stack[top++] = left_first ? node.left : node.right;
            continue;
        }
        for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
            const Surface& s = surfaces_[order_[i]];
            const double denom = dot(s.normal, dir);
            if (denom == 0)
                continue;
            const double t = (s.offset - dot(s.normal, origin)) / denom;
            if (!(t > t0 && t <= t1) || !s.contains(origin + dir * t))
                continue;
            if (visit(order_[i], t, denom > 0))
                return;
        }
    }
}

SurfaceBvh::Hit SurfaceBvh::first_hit(const Vec3& origin, const Vec3& dir, double t0, double t1,
                                      std::span<const std::uint32_t> skip, Meets meets) const {
    Hit hit;
    const double t_end = t1;
    traverse(origin, dir, t0, t1, [&](std::uint32_t s, double t, bool back) {
        if (!(t < t_end) || ignored(s, skip, meets))
            return false;
        if (hit.surface < 0 || t < hit.t ||
            (t == hit.t && tie_rank_[s] < tie_rank_[std::size_t(hit.surface)])) {
            hit = {std::int32_t(s), t, back};
            t1 = t; // only closer hits, and equal ones for the tie rule, matter from now on
        }
        return false;
    });
    return hit;
}

bool SurfaceBvh::occluded(const Vec3& origin, const Vec3& dir, double t0, double t1,
                          std::span<const std::uint32_t> skip, Meets meets) const {
    bool blocked = false;
    traverse(origin, dir, t0, t1, [&](std::uint32_t s, double t, bool) {
        blocked = t < t1 && !ignored(s, skip, meets);
        return blocked;
    });
    return blocked;
}

} // namespace penumbra::mesher
