#pragma once
// Per surface: the constraints it is triangulated with and which of its regions are hidden.

#include <memory>
#include <vector>

#include "contacts.h"
#include "discontinuity.h"
#include "surface_cdt.h"

namespace penumbra::mesher {

struct PreparedSurface {
    std::unique_ptr<SurfaceTriangulator> triangulator; ///< outline + contact lines, regions
    std::vector<Segment2> extra;                         ///< cleaned discontinuity constraints
};

/// \brief Builds each surface's region triangulation from its contact lines and cover
///        outlines, marks the hidden side(s) of every region (inside a cover, or enclosed by
///        EnclosureTest, repeated until stable so that a region whose probes only meet hidden
///        sides is hidden too) and cleans the discontinuity segments against the contacts.
std::vector<PreparedSurface> prepare_surfaces(
    const Scene& scene, const std::vector<Surface>& surfaces, const SurfaceBvh& bvh,
    const std::vector<SurfaceContacts>& contacts,
    const std::vector<std::vector<ReceiverSegment>>& discontinuities, const MeshParams& params,
    const Context& ctx);

} // namespace penumbra::mesher
