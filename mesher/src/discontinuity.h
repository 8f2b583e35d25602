#pragma once
// Discontinuity meshing: the shadow boundaries that each source casts on each surface.

#include <cstdint>
#include <vector>

#include "core/context.h"
#include "core/scene.h"
#include "surface_bvh.h"
#include "surfaces.h"

namespace penumbra::mesher {

/// A discontinuity segment on one surface, in the surface's 2D frame.
struct ReceiverSegment {
    Segment2 segment;
    int order = 2;                    ///< 0, 1 or 2
    LightSource source = SunSource{}; ///< as DiscontinuitySegment::source
};

/// \brief Per surface, the visible parts of the intersections of the critical wedges of every
///        source (critical.h) with the surface: D0 where the blocker feature lies on the
///        surface (a contact) and for point lights, D1 where source and blocker edges are
///        parallel, D2 otherwise. Parts of a segment from whose points the critical line to
///        the source feature is blocked by other geometry are not real boundaries and are
///        dropped (sampled along the segment, transitions found by bisection). Only orders up
///        to params.max_order are kept; collinear overlapping segments of one source and order
///        are merged. The sun's boundaries (D2 but at contacts) are finer than the merge
///        distance: ends of its segments near another of them are moved onto it (see
///        fit_sun_ends in the .cpp).
std::vector<std::vector<ReceiverSegment>>
find_discontinuities(const Scene& scene, const std::vector<Surface>& surfaces,
                     const SurfaceBvh& bvh, const MeshParams& params, const Context& ctx);

} // namespace penumbra::mesher
