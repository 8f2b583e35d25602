#pragma once
// Occlusion certificates for links (shaft culling, Haines & Wallace 1994, with the planar
// occluders of cell-and-portal visibility, Teller & Hanrahan 1993): the scene's roots grouped
// by plane, each plane with the boundary of the union of its triangles. Every segment between
// two point sets on opposite sides of a plane crosses it inside the convex hull of the
// crossings of the segments between their points; where that hull lies inside the union, the
// plane blocks them all, which no finite number of rays can prove. An office's partition
// blocks every link between the rooms on its two sides, except through its door. Only opaque
// roots (Hierarchy::opaque) occlude: glazing, which the visibility query lets light through
// (VisibilityQuery::transmittance), is left out of the unions, so that a window is a hole in
// its wall's plane as a door is.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/vec.h"
#include "hierarchy/hierarchy.h"

namespace penumbra::solver {

class OccluderPlanes {
public:
    OccluderPlanes() = default;
    /// The planes of the roots of \p h, each with the union of its opaque roots' triangles;
    /// a two-sided surface (root r with h.twin[r] >= 0) counts once.
    explicit OccluderPlanes(const Hierarchy& h);

    std::size_t size() const { return planes_.size(); }
    /// The plane root \p r lies in (also for a root that does not occlude).
    std::uint32_t plane_of_root(std::uint32_t r) const { return root_plane_[r]; }
    /// Signed distance of \p x from plane \p p (along its normal), metres.
    double distance(std::uint32_t p, const Vec3& x) const {
        return dot(planes_[p].n, x) - planes_[p].d;
    }
    const Vec3& normal(std::uint32_t p) const { return planes_[p].n; }
    /// Distances below this count as on a plane (metres).
    double tolerance() const { return tolerance_; }
    /// True if plane \p p blocks every segment between a point of the convex hull of \p a and
    /// one of the convex hull of \p b, which must lie on its two sides (a point may lie on the
    /// plane, but not one of each). Segments crossing within tolerance() of the union's edge
    /// count as blocked.
    bool blocks(std::uint32_t p, std::span<const Vec3> a, std::span<const Vec3> b) const;

private:
    struct Point2 {
        double x = 0, y = 0;
    };
    struct Plane {
        Vec3 n, u, v;    ///< unit normal and an orthonormal frame of the plane
        double d = 0;    ///< n · (a point of the plane)
        Point2 lo, hi;   ///< the triangles' bounds in the frame (lo: the grid's origin)
        double cell = 1; ///< grid cell size
        std::uint32_t nx = 1, ny = 1;
        std::uint32_t cell_begin = 0; ///< first cell in cell_*_begin_ (nx · ny cells)
    };
    Point2 project(const Plane& p, const Vec3& x) const {
        const Vec3 r = x - p.n * p.d;
        return {dot(r, p.u), dot(r, p.v)};
    }
    bool inside_triangle(std::uint32_t t, Point2 x) const;
    /// Adds the plane's triangles (\p roots), their grid and the boundary of their union;
    /// \p unit: the quantum of positions that tells lines apart.
    void add_plane(Plane& plane, const Hierarchy& h, const std::vector<std::uint32_t>& roots,
                   double unit);
    /// Adds the parts of the edge \p a–\p b of the plane's triangles that no triangle covers
    /// on its side \p out (a unit vector) as boundary segments.
    void add_uncovered(const Plane& plane, Point2 a, Point2 b, Point2 out);
    /// The grid cells (x0, y0, x1, y1) over the box lo–hi, widened by the tolerance.
    std::array<std::uint32_t, 4> cells_of(const Plane& plane, Point2 lo, Point2 hi) const;
    /// Appends the grid of \p plane to \p begin / \p items (CSR) with items
    /// [first, last), item i in the cells box_of(i) returns.
    template <typename BoxOf>
    static void fill_cells(const Plane& plane, std::vector<std::uint32_t>& begin,
                           std::vector<std::uint32_t>& items, std::size_t first, std::size_t last,
                           BoxOf&& box_of);

    std::vector<Plane> planes_;
    std::vector<std::uint32_t> root_plane_;
    double tolerance_ = 0;
    /// Per plane's grid cell (CSR): the boundary segments and the triangles it overlaps.
    std::vector<std::uint32_t> cell_segments_begin_, cell_segments_;
    std::vector<std::uint32_t> cell_triangles_begin_, cell_triangles_;
    std::vector<std::array<Point2, 2>> segments_;  ///< boundary edges, in their plane's frame
    std::vector<std::array<Point2, 3>> triangles_; ///< in their plane's frame
};

} // namespace penumbra::solver
