#pragma once
// A bounding-volume hierarchy over the planar surfaces, for the mesher's own geometric
// queries (box overlaps, segment occlusion, probe rays). Double precision; the solver's
// Embree scene is built later from the finished mesh.

#include <cstdint>
#include <span>
#include <vector>

#include "surfaces.h"

namespace penumbra::mesher {

class SurfaceBvh {
public:
    /// \p surfaces must outlive the hierarchy.
    explicit SurfaceBvh(const std::vector<Surface>& surfaces);

    /// Ids of the surfaces whose bounding box overlaps \p box, ascending.
    std::vector<std::uint32_t> overlapping(const BBox& box) const;

    /// Which surfaces a ray query meets: every one (the geometry), or only those that block
    /// light (Surface::opaque; a ray passes through glazing).
    enum class Meets { any, opaque };

    struct Hit {
        std::int32_t surface = -1; ///< -1 if nothing was hit
        double t = 0;
        bool back = false; ///< the ray met the surface's back side
    };
    /// Closest surface crossed by origin + t·dir for t in (t0, t1), ignoring \p skip and
    /// what \p meets leaves out; of surfaces crossed at exactly the same t, the one of lowest
    /// tie rank (a fixed order).
    Hit first_hit(const Vec3& origin, const Vec3& dir, double t0, double t1,
                  std::span<const std::uint32_t> skip = {}, Meets meets = Meets::any) const;
    /// Whether any surface but those in \p skip (and what \p meets leaves out) crosses
    /// origin + t·dir for t in (t0, t1).
    bool occluded(const Vec3& origin, const Vec3& dir, double t0, double t1,
                  std::span<const std::uint32_t> skip = {}, Meets meets = Meets::any) const;

private:
    struct Node {
        BBox box;
        std::int32_t left = -1, right = -1; ///< children, -1 for a leaf
        std::uint32_t first = 0, count = 0; ///< leaf range in order_
        std::uint8_t axis = 0;              ///< split axis: left holds the lower half
    };
    std::int32_t build(std::uint32_t first, std::uint32_t count);
    bool ignored(std::uint32_t s, std::span<const std::uint32_t> skip, Meets meets) const;
    template <typename Visit>
    void traverse(const Vec3& origin, const Vec3& dir, double t0, double& t1, Visit&& visit) const;

    const std::vector<Surface>& surfaces_;
    std::vector<Node> nodes_;
    std::vector<BBox> ray_boxes_; ///< per node, padded for the slab test
    std::vector<std::uint32_t> order_;
    std::vector<std::uint32_t> tie_rank_; ///< per surface
};

} // namespace penumbra::mesher
