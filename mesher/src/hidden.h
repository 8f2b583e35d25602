#pragma once
// Which parts of a surface are hidden inside other geometry (the floor under a box, the
// inside of a closed object): decided per region between contact lines, by probe rays.

#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "core/scene.h"
#include "surface_bvh.h"
#include "surfaces.h"

namespace penumbra::mesher {

class EnclosureTest {
public:
    /// \p surfaces and \p bvh must outlive the test.
    EnclosureTest(const Scene& scene, const std::vector<Surface>& surfaces, const SurfaceBvh& bvh,
                  const MeshParams& params);

    /// Whether side \p back of surface \p s is already known to be hidden at point \p p.
    using HiddenAt = std::function<bool(std::uint32_t s, const Vec3& p, bool back)>;

    /// \brief Whether the side with unit normal \p n of surface \p s is enclosed at \p p: every
    ///        one of 64 probe rays from just above p meets the back side of some opaque
    ///        surface (or a side that \p hidden_at, if given, reports hidden), and no source
    ///        (emitting side of an emissive surface, point light, the sun's centre) is visible
    ///        from there; a probe that leaves the scene sees the sky.
    ///        Probes and source rays pass through glazing (Surface::opaque false). \p inradius
    ///        bounds the distance from p to the region's boundary.
    bool enclosed(const Vec3& p, const Vec3& n, std::uint32_t s, double inradius,
                  const HiddenAt& hidden_at = nullptr) const;

private:
    struct SourcePoint {
        Vec3 position;
        std::optional<std::uint32_t> surface; ///< the emitting surface; none for a point light
    };
    /// A node of the tree over the source points: leaves hold sources_[first, first + count).
    struct SourceNode {
        BBox box;
        std::int32_t left = -1, right = -1;
        std::uint32_t first = 0, count = 0;
    };

    bool sees_a_source(const Vec3& q) const;
    bool sees(const Vec3& q, const SourcePoint& src) const;
    bool blocks(const Vec3& q, std::int32_t blocker, std::span<const Vec3> points) const;
    bool blocks(const Vec3& q, std::int32_t blocker, const BBox& box) const;
    /// Surfaces \p a and \p b (−1: none) block as one: the same surface or the same group.
    bool same_blocker(std::int32_t a, std::int32_t b) const;
    std::int32_t build_sources(std::uint32_t first, std::uint32_t count);

    const std::vector<Surface>& surfaces_;
    const SurfaceBvh& bvh_;
    MeshParams params_;
    std::vector<Vec3> directions_; ///< unit, around +z
    std::vector<SourcePoint> sources_;
    std::vector<SourceNode> source_nodes_;
    std::optional<Vec3> sun_direction_; ///< toward the sun, when it shines
    /// A convex region of one plane that occludes sources: an opaque non-emitting surface
    /// with a convex outline, or a connected set of coplanar ones that tiles its convex hull
    /// (the quads of a tessellated rectangle), in the 2D frame of one of them.
    struct Blocker {
        std::uint32_t frame = 0; ///< the surface whose plane and 2D frame the outline uses
        std::vector<Vec2> outline;
    };
    void build_blockers();

    std::vector<Blocker> blockers_;
    std::vector<std::int32_t> blocker_of_; ///< per surface: its Blocker, or −1
};

} // namespace penumbra::mesher
