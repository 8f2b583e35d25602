#pragma once
// Critical surfaces of the visibility of a source (Heckbert 1992; Lischinski, Tampieri &
// Greenberg 1992): vertex–edge (VE) wedges through a source vertex and a blocker edge, and
// edge–vertex (EV) wedges through a source edge and a blocker vertex. Edge–edge–edge events
// (quadric critical surfaces) are not generated.
//
// The sun is a disc at infinity, so its features are directions. A blocker edge's VE events
// are exact: the two planes through the edge that touch the disc's cone of directions (the
// umbra and penumbra boundaries of a straight edge; a disc has no corners, so there are no
// others). Its EV events approximate the cone through a blocker vertex and the disc's rim by
// planes through the vertex and chords of a polygon inscribed in the rim: its corners are the
// touching directions of the vertex's own edges (so that the chords meet those edges' VE
// planes exactly), each arc between two split evenly into chords of at most 2π /
// k_sun_rim_sides (the regular polygon where no edge touches).

#include <cstdint>
#include <optional>
#include <vector>

#include "core/context.h"
#include "core/scene.h"
#include "scene_features.h"
#include "surface_bvh.h"
#include "surfaces.h"

namespace penumbra::mesher {

/// The sun's rim is approximated by chords of at most 2π / k_sun_rim_sides (EV events).
inline constexpr int k_sun_rim_sides = 16;

/// A light source as the discontinuity mesher sees it: a polygon emitting to one side, a
/// point, or the sun (a disc at infinity).
struct Source {
    LightSource light = SunSource{};      ///< DiscontinuitySegment::source
    std::optional<std::uint32_t> surface; ///< the emitting surface of an area source
    /// The polygon's corners or the point; the sun: unit directions toward the corners of a
    /// regular polygon inscribed in its rim (its centre alone for a disc of no size).
    std::vector<Vec3> vertices;
    Vec3 normal;       ///< of the emitting side
    double offset = 0; ///< dot(normal, p) on the source plane
    /// A spot: it lights only the directions x − p with cos θ to this unit axis above
    /// cos_cutoff (-1, every direction, for other sources).
    Vec3 axis;
    double cos_cutoff = -1;
    /// The sun: at infinity toward the unit `axis`, its disc's angular radius r with
    /// sin r = sin_radius.
    double sin_radius = 0;
    bool at_infinity() const { return penumbra::at_infinity(light); }
    bool in_front(const Vec3& x, double eps) const {
        return !surface || dot(normal, x) - offset > eps;
    }
};

/// The emissive surfaces (each emitting side), the point lights and the sun of the scene.
std::vector<Source> collect_sources(const Scene& scene, const std::vector<Surface>& surfaces);

enum class EventKind { vertex_edge, edge_vertex };

struct HalfPlane {
    Vec3 m, q; ///< points x with dot(m, x − q) ≥ 0
};

/// One critical wedge: the part of a plane swept by the lines through a source feature and a
/// blocker feature, beyond the blocker.
struct Event {
    EventKind kind = EventKind::vertex_edge;
    std::uint32_t source = 0;   ///< index into the sources
    std::uint32_t feature = 0;  ///< blocker edge (VE) or vertex (EV) in Features
    std::uint32_t source_k = 0; ///< source vertex (VE) or first vertex of the source edge (EV)
    int order = 2;              ///< 0 for point lights, 1 for parallel edges, else 2
    /// VE: the source vertex (the sun: a point of the blocker edge); EV: the blocker vertex
    Vec3 apex;
    Vec3 toward;         ///< the sun's VE: unit direction of the disc point touched
    Vec3 near_a, near_b; ///< VE: the blocker edge (the part in front of the source)
    Vec3 normal;         ///< unit normal of the wedge's plane
    std::vector<HalfPlane> bounds;
    BBox box; ///< bounds the wedge inside the scene
};

/// \brief The VE and EV events of every source whose blocker feature is a silhouette seen
///        from the source feature and is not entirely hidden from it. A spot's VE wedges are
///        cut to the parts of blocker edges inside its cut-off cone, so that it makes no
///        shadow boundaries where it sends no light. The sun's events are for every blocker
///        feature that some part of the disc lights.
std::vector<Event> critical_events(const std::vector<Source>& sources, const Features& features,
                                   const SurfaceBvh& bvh, const MeshParams& params,
                                   const Context& ctx);

} // namespace penumbra::mesher
