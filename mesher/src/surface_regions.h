#pragma once
// Per surface: the constraints it is triangulated with and which of its regions are hidden.

#include <memory>
#include <vector>

#include "contacts.h"
#include "discontinuity.h"
#include "surface_cdt.h"

namespace penumbra::mesher {

struct PreparedSurface {
    /// Outline + contact lines, with the regions between them. Built when the regions are
    /// classified (contact splitting on); else null, and the refinement builds it from the
    /// outline and the cuts one surface at a time, so that the region triangulations of half
    /// a million surfaces are never held at once.
    std::unique_ptr<SurfaceTriangulator> triangulator;
    std::vector<Segment2> cuts;  ///< cleaned contact lines and cover outlines
    std::vector<Segment2> extra; ///< cleaned discontinuity constraints
};

/// \brief Cleans each surface's contact lines and cover outlines and its discontinuity
///        segments (against the contacts); with contact splitting, builds its region
///        triangulation and marks the hidden side(s) of every region (inside a cover, or
///        enclosed by EnclosureTest, repeated until stable so that a region whose probes only
///        meet hidden sides is hidden too).
std::vector<PreparedSurface>
prepare_surfaces(const Scene& scene, const std::vector<Surface>& surfaces, const SurfaceBvh& bvh,
                 const std::vector<SurfaceContacts>& contacts,
                 const std::vector<std::vector<ReceiverSegment>>& discontinuities,
                 const MeshParams& params, const Context& ctx);

} // namespace penumbra::mesher
