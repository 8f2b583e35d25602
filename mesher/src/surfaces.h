#pragma once
// Planar surfaces: the mesher's unit of work. Each planar input polygon is one surface; a
// non-planar polygon is fan-triangulated from its first vertex, each fan triangle a surface.
// Before that, vertices within the contact tolerance of another surface's plane are moved
// onto it inside their own plane, which closes near-contacts (a wall floating 1 mm above the
// floor) in the geometry itself.

#include <cstdint>
#include <string>
#include <vector>

#include "core/context.h"
#include "core/scene.h"
#include "geometry2d.h"

namespace penumbra::mesher {

/// Settings of one meshing run, resolved to metres.
struct MeshParams {
    double diagonal = 0;    ///< scene bounding-box diagonal
    double max_edge = 0;    ///< longest element edge
    double min_edge = 0;    ///< faces with a shorter edge are not refined for their angles
    double contact_tol = 0; ///< gaps up to this are contacts
    double snap = 0;        ///< points closer than this are merged (2e-7 × diagonal)
    double merge = 0;       ///< constraint points, and parallel lines, closer than this merge
    double nudge = 0;       ///< vertex copies on a contact line move this far off it
    bool split_contacts = true;
    int max_order = 2;       ///< highest discontinuity order inserted; -1 = none
    std::int64_t budget = 0; ///< most elements; 0 = no limit
};

/// One planar surface with its plane and 2D frame: p = origin + x·axis_u + y·axis_v.
struct Surface {
    std::uint32_t polygon = 0;
    std::uint32_t id = 0;
    Vec3 normal;       ///< unit, front side
    double offset = 0; ///< dot(normal, p) for p on the plane
    Vec3 origin, axis_u, axis_v;
    std::vector<Vec3> outline;   ///< counter-clockwise around normal
    std::vector<Vec2> outline2d; ///< the same in the 2D frame
    BBox box;
    double area = 0;
    bool two_sided = true;
    bool emits_front = false, emits_back = false;
    bool opaque = true; ///< blocks all light (not glazing): the hidden-region test counts it
    std::string name;   ///< "'name' (source)" for messages

    double distance(const Vec3& p) const { return dot(normal, p) - offset; }
    Vec2 to_2d(const Vec3& p) const { return {dot(p - origin, axis_u), dot(p - origin, axis_v)}; }
    Vec3 to_3d(const Vec2& q) const { return origin + axis_u * q.x + axis_v * q.y; }
    /// Whether the point (assumed on or near the plane) lies inside the outline.
    bool contains(const Vec3& p) const { return point_in_polygon(to_2d(p), outline2d); }
};

/// Newell's normal (not normalised: its length is twice the area for planar polygons).
Vec3 newell_normal(const std::vector<Vec3>& outline);

/// Builds a surface from a planar outline; returns false for a zero-area outline.
bool make_surface(const std::vector<Vec3>& outline, Surface& out);

/// \p scene's mesher settings resolved to metres (mesher.cpp).
MeshParams resolve_params(const Scene& scene);

/// About the elements a size bound makes: two triangles per square of its side on every side
/// of every surface. Delaunay refinement makes fewer on open surfaces; contacts and shadow
/// boundaries add more, most at coarse sizes (the Cornell box meshes into 3.7 times the
/// estimate at 0.1 m, 1.5 times at 0.025 m, 1.2 times at 0.005 m).
double estimated_elements(const std::vector<Surface>& surfaces, double max_edge);

/// The memory estimate counts this many elements per estimated_elements(): a bound for the
/// Cornell box at every size (tests/mesher/memory_estimate_test.cpp).
inline constexpr double k_elements_per_estimate = 4.0;

/// The planar surfaces of \p scene, near-contacts closed when params.split_contacts.
/// Polygons that degenerate to zero area are skipped with a warning naming them.
std::vector<Surface> build_surfaces(const Scene& scene, const MeshParams& params,
                                    const Context& ctx);

} // namespace penumbra::mesher
