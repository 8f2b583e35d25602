// Enclosure probes. A region of a surface side is hidden when it lies inside closed geometry:
// seen from just above it, every direction ends on the back of a surface (the inside of a box
// whose faces point outwards) and no source is in view. Probe directions are a fixed
// Fibonacci set over the hemisphere above 5° elevation, so the result is deterministic.

#include "hidden.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace penumbra::mesher {

namespace {

constexpr int k_probe_count = 64;

std::vector<Vec3> probe_directions() {
    std::vector<Vec3> dirs;
    const double golden = k_pi * (3.0 - std::sqrt(5.0));
    const double z_min = std::sin(5.0 * k_pi / 180.0);
    for (int i = 0; i < k_probe_count; ++i) {
        const double z = z_min + (1.0 - z_min) * (double(i) + 0.5) / k_probe_count;
        const double r = std::sqrt(1.0 - z * z), phi = golden * i;
        dirs.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
    }
    return dirs;
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
        sources_.push_back({centre, std::int32_t(s.id)});
        for (const Vec3& v : s.outline) // near the corners too, for non-convex emitters
            sources_.push_back({v + (centre - v) * 0.1, std::int32_t(s.id)});
    }
    for (const PointLight& light : scene.point_lights)
        sources_.push_back({light.position, -1});
}

bool EnclosureTest::sees_a_source(const Vec3& q) const {
    for (const SourcePoint& src : sources_) {
        if (src.surface >= 0) {
            const Surface& e = surfaces_[std::size_t(src.surface)];
            const double d = e.distance(q);
            if (!((d > 0 && e.emits_front) || (d < 0 && e.emits_back)))
                continue;
        }
        // The probed surface itself is not skipped: a source on its other side is behind it.
        const std::array<std::uint32_t, 1> skip{std::uint32_t(std::max(src.surface, 0))};
        const std::span<const std::uint32_t> skips(skip.data(), src.surface >= 0 ? 1 : 0);
        if (!bvh_.occluded(q, src.position - q, 1e-9, 1.0 - 1e-9, skips))
            return true;
    }
    return false;
}

bool EnclosureTest::enclosed(const Vec3& p, const Vec3& n, std::uint32_t s, double inradius,
                             const HiddenAt& hidden_at) const {
    const double lift = std::min(0.1 * inradius, std::max(10 * params_.snap,
                                                           1e-5 * params_.diagonal));
    const Vec3 q = p + n * lift;
    const Frame frame = Frame::from_normal(n);
    const std::array<std::uint32_t, 1> skip{s};
    for (const Vec3& local : directions_) {
        const Vec3 dir = frame.to_world(local);
        const SurfaceBvh::Hit hit =
            bvh_.first_hit(q, dir, 0.0, 4.0 * params_.diagonal + 1.0, skip);
        if (hit.surface < 0)
            return false;
        if (!hit.back &&
            !(hidden_at && hidden_at(std::uint32_t(hit.surface), q + dir * hit.t, false)))
            return false;
    }
    return !sees_a_source(q);
}

} // namespace penumbra::mesher
