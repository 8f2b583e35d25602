// Enclosure probes. A region of a surface side is hidden when it lies inside closed geometry:
// seen from just above it, every direction ends on the back of a surface (the inside of a box
// whose faces point outwards) and no source is in view. Probe directions are a fixed
// Fibonacci set over the hemisphere above 5° elevation, so the result is deterministic.
// Whether a source is in view is decided over a tree of the source points: a node whose box
// lies entirely behind one convex surface, as seen from the probe point, is dismissed without
// a ray per source (the central projection of the box onto the surface's plane is the convex
// hull of its corners' projections, and those lie inside the surface by a margin), so an
// enclosed point costs about as many rays as there are groups of sources at the edges of its
// enclosure's faces, not one per source in the scene. The outcome is the same as one ray per
// source. A convex blocker may be a set of coplanar surfaces that tile a convex region (the
// quads of a tessellated cabinet side): one small quad alone hides few sources, so without
// the groups an enclosed point under a tessellated cabinet cost about one ray per source.

#include "hidden.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <span>
#include <tuple>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_2.h>

#include "core/disjoint_sets.h"

namespace penumbra::mesher {

namespace {

constexpr int k_probe_count = 64;

// Probes and source rays are light: they pass through glazing, which neither encloses a
// region nor hides a source.
constexpr SurfaceBvh::Meets k_light = SurfaceBvh::Meets::opaque;

// Steepest first: a probe stops at the first direction that meets a front side, and the
// steep ones meet the ceiling or a desk above an open region at once, where grazing ones
// may run across a whole floor plate first (a cost that grows as √n per probe). The set, so
// the outcome, does not depend on the order.
std::vector<Vec3> probe_directions() {
    std::vector<Vec3> dirs;
    const double golden = k_pi * (3.0 - std::sqrt(5.0));
    const double z_min = std::sin(5.0 * k_pi / 180.0);
    for (int i = k_probe_count; i-- > 0;) {
        const double z = z_min + (1.0 - z_min) * (double(i) + 0.5) / k_probe_count;
        const double r = std::sqrt(1.0 - z * z), phi = golden * i;
        dirs.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
    }
    return dirs;
}

Vec3 centre(const BBox& b) {
    return (b.lo + b.hi) * 0.5;
}

// A simple convex outline: no right turn and one full turn in all (counter-clockwise).
bool convex_outline(const std::vector<Vec2>& outline) {
    double turning = 0;
    const std::size_t n = outline.size();
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 a = outline[(i + n - 1) % n], b = outline[i], c = outline[(i + 1) % n];
        const Vec2 u = b - a, v = c - b;
        const double x = cross(u, v);
        if (x < 0)
            return false;
        if (length(u) > 0 && length(v) > 0)
            turning += std::atan2(x, dot(u, v));
    }
    return std::abs(turning - 2 * k_pi) < 1e-6;
}

} // namespace

EnclosureTest::EnclosureTest(const Scene& scene, const std::vector<Surface>& surfaces,
                             const SurfaceBvh& bvh, const MeshParams& params)
    : surfaces_(surfaces), bvh_(bvh), params_(params), directions_(probe_directions()) {
    for (const Surface& s : surfaces) {
        if (!s.emits_front && !s.emits_back)
            continue;
        Vec3 centre;
        for (const Vec3& v : s.outline)
            centre += v / double(s.outline.size());
        sources_.push_back({centre, s.id});
        for (const Vec3& v : s.outline) // near the corners too, for non-convex emitters
            sources_.push_back({v + (centre - v) * 0.1, s.id});
    }
    for (const PointLight& light : scene.point_lights)
        sources_.push_back({light.position, std::nullopt});
    if (scene.sun && !scene.sun->irradiance.is_black())
        sun_direction_ = scene.sun->direction;
    if (!sources_.empty())
        build_sources(0, std::uint32_t(sources_.size()));
    build_blockers();
}

// Coplanar opaque non-emitting surfaces (the same plane up to rounding, either orientation)
// that share outline vertices form groups; a group whose members' areas add up to its convex
// hull's tiles the hull, which then blocks as one surface. Other convex surfaces block alone;
// glazing never blocks.
void EnclosureTest::build_blockers() {
    const std::size_t n = surfaces_.size();
    blocker_of_.assign(n, -1);
    const double length_step = 1e-9 * std::max(params_.diagonal, 1e-6);
    auto rounded = [](double x, double step) { return std::int64_t(std::llround(x / step)); };
    using PlaneKey = std::tuple<std::int64_t, std::int64_t, std::int64_t, std::int64_t>;
    std::map<PlaneKey, std::vector<std::uint32_t>> planes;
    for (std::uint32_t i = 0; i < n; ++i) {
        const Surface& s = surfaces_[i];
        if (s.emits_front || s.emits_back || !s.opaque)
            continue;
        // One orientation per plane: the first clearly non-zero normal component positive.
        const Vec3 nn = s.normal;
        const double lead = std::abs(nn.x) > 1e-6 ? nn.x : (std::abs(nn.y) > 1e-6 ? nn.y : nn.z);
        const double sign = lead < 0 ? -1.0 : 1.0;
        planes[{rounded(sign * nn.x, 1e-9), rounded(sign * nn.y, 1e-9), rounded(sign * nn.z, 1e-9),
                rounded(sign * s.offset, length_step)}]
            .push_back(i);
    }
    DisjointSets sets(n);
    using VertexKey = std::tuple<std::int64_t, std::int64_t, std::int64_t>;
    for (const auto& [key, members] : planes) {
        if (members.size() < 2)
            continue;
        std::map<VertexKey, std::uint32_t> first_at;
        for (std::uint32_t i : members)
            for (const Vec3& v : surfaces_[i].outline) {
                const VertexKey vk{rounded(v.x, length_step), rounded(v.y, length_step),
                                   rounded(v.z, length_step)};
                const auto [it, fresh] = first_at.emplace(vk, i);
                if (!fresh)
                    sets.unite(i, it->second);
            }
    }
    std::map<std::uint32_t, std::vector<std::uint32_t>> groups; // by root, members ascending
    for (const auto& [key, members] : planes)
        for (std::uint32_t i : members)
            groups[sets.find(i)].push_back(i);
    using K = CGAL::Exact_predicates_inexact_constructions_kernel;
    for (const auto& [root, members] : groups) {
        std::vector<Vec2> hull;
        if (members.size() > 1) {
            const Surface& frame = surfaces_[root];
            std::vector<K::Point_2> points, hull_points;
            double area = 0;
            for (std::uint32_t i : members) {
                area += surfaces_[i].area;
                for (const Vec3& v : surfaces_[i].outline) {
                    const Vec2 x = frame.to_2d(v);
                    points.emplace_back(x.x, x.y);
                }
            }
            CGAL::convex_hull_2(points.begin(), points.end(), std::back_inserter(hull_points));
            for (const K::Point_2& p : hull_points)
                hull.push_back({p.x(), p.y()});
            const double hull_area = std::abs(signed_area(hull));
            if (hull.size() >= 3 && std::abs(hull_area - area) <= 1e-7 * hull_area) {
                const auto b = std::int32_t(blockers_.size());
                blockers_.push_back({root, std::move(hull)});
                for (std::uint32_t i : members)
                    blocker_of_[i] = b;
                continue;
            }
        }
        for (std::uint32_t i : members) // alone
            if (convex_outline(surfaces_[i].outline2d)) {
                blocker_of_[i] = std::int32_t(blockers_.size());
                blockers_.push_back({i, surfaces_[i].outline2d});
            }
    }
}

std::int32_t EnclosureTest::build_sources(std::uint32_t first, std::uint32_t count) {
    const auto index = std::int32_t(source_nodes_.size());
    source_nodes_.emplace_back();
    BBox box;
    for (std::uint32_t i = first; i < first + count; ++i)
        box.extend(sources_[i].position);
    source_nodes_[std::size_t(index)].box = box;
    if (count <= 4) {
        source_nodes_[std::size_t(index)].first = first;
        source_nodes_[std::size_t(index)].count = count;
        return index;
    }
    const Vec3 extent = box.hi - box.lo;
    const std::size_t axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                             : extent.y >= extent.z                       ? 1
                                                                          : 2;
    const std::uint32_t half = count / 2;
    std::nth_element(sources_.begin() + first, sources_.begin() + first + half,
                     sources_.begin() + first + count,
                     [&](const SourcePoint& a, const SourcePoint& b) {
                         return a.position[axis] < b.position[axis];
                     });
    const std::int32_t left = build_sources(first, half);
    const std::int32_t right = build_sources(first + half, count - half);
    source_nodes_[std::size_t(index)].left = left;
    source_nodes_[std::size_t(index)].right = right;
    return index;
}

// Whether every segment from q to a point of the convex hull of \p points crosses the convex
// blocker of surface \p blocker (build_blockers) at least a margin inside its outline and
// away from both ends: then each source there is occluded by it, as sees() would find (the
// central projection of the hull onto the blocker's plane is the convex hull of the points'
// projections). Emitting surfaces have no blocker: a source's own surface never occludes it.
bool EnclosureTest::blocks(const Vec3& q, std::int32_t blocker,
                           std::span<const Vec3> points) const {
    if (blocker < 0 || blocker_of_[std::size_t(blocker)] < 0)
        return false;
    const Blocker& b = blockers_[std::size_t(blocker_of_[std::size_t(blocker)])];
    const Surface& p = surfaces_[b.frame];
    const double margin = 1e-8 * (params_.diagonal + length(q));
    const double dq = p.distance(q);
    if (std::abs(dq) <= margin)
        return false;
    for (const Vec3& c : points) {
        const double dc = p.distance(c);
        if (!(dq > 0 ? dc < -margin : dc > margin))
            return false;
        const double t = dq / (dq - dc);
        if (!(t > 1e-6 && t < 1.0 - 1e-6))
            return false;
        const Vec2 x = p.to_2d(q + (c - q) * t);
        if (!point_in_polygon(x, b.outline) || distance_to_boundary(x, b.outline) <= margin)
            return false;
    }
    return true;
}

bool EnclosureTest::same_blocker(std::int32_t a, std::int32_t b) const {
    if (a == b)
        return true;
    return a >= 0 && b >= 0 && blocker_of_[std::size_t(a)] >= 0 &&
           blocker_of_[std::size_t(a)] == blocker_of_[std::size_t(b)];
}

bool EnclosureTest::blocks(const Vec3& q, std::int32_t blocker, const BBox& box) const {
    std::array<Vec3, 8> corners;
    for (std::size_t k = 0; k < 8; ++k)
        corners[k] = Vec3((k & 1) ? box.hi.x : box.lo.x, (k & 2) ? box.hi.y : box.lo.y,
                          (k & 4) ? box.hi.z : box.lo.z);
    return blocks(q, blocker, std::span<const Vec3>(corners));
}

bool EnclosureTest::sees(const Vec3& q, const SourcePoint& src) const {
    if (src.surface) {
        const Surface& e = surfaces_[*src.surface];
        const double d = e.distance(q);
        if (!((d > 0 && e.emits_front) || (d < 0 && e.emits_back)))
            return false;
    }
    // The probed surface itself is not skipped: a source on its other side is behind it.
    const std::array<std::uint32_t, 1> skip{src.surface.value_or(0)};
    const std::span<const std::uint32_t> skips(skip.data(), src.surface ? 1 : 0);
    return !bvh_.occluded(q, src.position - q, 1e-9, 1.0 - 1e-9, skips, k_light);
}

bool EnclosureTest::sees_a_source(const Vec3& q) const {
    if (source_nodes_.empty())
        return false;
    struct Item {
        std::int32_t node, blocker; ///< blocker: the surface that hid the parent's centre
    };
    std::vector<Item> stack{{0, -1}};
    while (!stack.empty()) {
        const Item item = stack.back();
        stack.pop_back();
        const SourceNode& node = source_nodes_[std::size_t(item.node)];
        if (blocks(q, item.blocker, node.box))
            continue;
        if (node.left < 0) {
            for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
                if (!blocks(q, item.blocker, std::span(&sources_[i].position, 1)) &&
                    sees(q, sources_[i]))
                    return true;
            continue;
        }
        const std::int32_t blocker =
            bvh_.first_hit(q, centre(node.box) - q, 0.0, 1.0, {}, k_light).surface;
        // The parent's blocker was tried on this box above; another tile of its group would
        // be the same test.
        if (!same_blocker(blocker, item.blocker) && blocks(q, blocker, node.box))
            continue;
        stack.push_back({node.right, blocker});
        stack.push_back({node.left, blocker});
    }
    return false;
}

bool EnclosureTest::enclosed(const Vec3& p, const Vec3& n, std::uint32_t s, double inradius,
                             const HiddenAt& hidden_at) const {
    const double lift =
        std::min(0.1 * inradius, std::max(10 * params_.snap, 1e-5 * params_.diagonal));
    const Vec3 q = p + n * lift;
    const Frame frame = Frame::from_normal(n);
    const std::array<std::uint32_t, 1> skip{s};
    for (const Vec3& local : directions_) {
        const Vec3 dir = frame.to_world(local);
        const SurfaceBvh::Hit hit =
            bvh_.first_hit(q, dir, 0.0, 4.0 * params_.diagonal + 1.0, skip, k_light);
        if (hit.surface < 0)
            return false;
        if (!hit.back &&
            !(hidden_at && hidden_at(std::uint32_t(hit.surface), q + dir * hit.t, false)))
            return false;
    }
    if (sun_direction_ && dot(*sun_direction_, n) > 0 &&
        bvh_.first_hit(q, *sun_direction_, 0.0, 4.0 * params_.diagonal + 1.0, skip, k_light)
                .surface < 0)
        return false; // the sun shines on it (through a window the probes missed)
    return !sees_a_source(q);
}

} // namespace penumbra::mesher
