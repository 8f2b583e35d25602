#pragma once
// Triangulation of one planar surface in its 2D frame with CGAL: a constrained Delaunay
// triangulation of outline + contact lines + discontinuity segments, refined to a size and
// angle bound (Delaunay_mesher_2). The only translation unit that includes CGAL.

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "geometry2d.h"

namespace penumbra::mesher {

/// A region of the surface between contact lines, with what is hidden there.
struct RegionInfo {
    Vec2 sample;         ///< a point well inside the region
    double inradius = 0; ///< of the triangle the sample is the centroid of
    double area = 0;
    bool hidden[2] = {false, false}; ///< front, back
};

struct RefineSettings {
    double max_edge = 0;       ///< longest element edge
    double near_factor = 1;    ///< size bound on the extra constraints, relative to max_edge
    double min_edge = 0;       ///< faces with a shorter edge are not refined for their angles
    double snap = 0;           ///< distance below which a point lies on a line
    double nudge = 0;          ///< vertex copies on a contact line move this far into their wedge
    std::size_t max_steps = 0; ///< refinement insertions before giving up
    bool two_sided = true;
};

/// One side of the triangulated surface: its own vertices (split along contact lines).
struct SideMesh {
    std::vector<Vec2> points;
    std::vector<std::array<std::uint32_t, 3>> triangles; ///< counter-clockwise in 2D
    std::vector<std::uint32_t> face; ///< the face of each triangle, shared by both sides
    double hidden_area = 0;          ///< m² of this side left without triangles
};

struct SurfaceTriangulation {
    SideMesh sides[2]; ///< front, back (empty for one-sided surfaces)
    std::size_t face_count = 0;
    bool capped = false; ///< refinement stopped at RefineSettings::max_steps
};

class SurfaceTriangulator {
public:
    /// \brief Triangulates \p outline (counter-clockwise) with the \p cuts (contact lines and
    ///        cover outlines, clipped to the outline) and finds the regions between them.
    ///        Constraints are noded with \p merge first (node_segments).
    SurfaceTriangulator(const std::vector<Vec2>& outline, const std::vector<Segment2>& cuts,
                        double merge);
    ~SurfaceTriangulator();
    SurfaceTriangulator(const SurfaceTriangulator&) = delete;
    SurfaceTriangulator& operator=(const SurfaceTriangulator&) = delete;

    /// The regions; set their hidden flags before refine().
    std::vector<RegionInfo>& regions();
    const std::vector<RegionInfo>& regions() const;

    /// The region containing \p p, or -1 outside the outline. Thread-safe.
    std::int32_t region_of(const Vec2& p) const;

    /// \brief Meshes the surface with the cuts and the \p extra constraints (discontinuity
    ///        segments), refined so that no edge exceeds max_edge and no angle is below 20.7°
    ///        (except near features shorter than min_edge and where constraints meet at
    ///        smaller angles). Faces in regions hidden on a side are left out of that side.
    SurfaceTriangulation refine(const std::vector<Segment2>& extra,
                                const RefineSettings& settings) const;

private:
    SurfaceTriangulation refine_impl(const std::vector<Segment2>& extra,
                                     const RefineSettings& settings) const;
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace penumbra::mesher
