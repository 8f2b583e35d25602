#pragma once
// Contact and intersection splitting: where other surfaces touch, cut or cover a surface.

#include <vector>

#include "surface_bvh.h"
#include "surfaces.h"

namespace penumbra::mesher {

/// A region of a surface covered by a coincident or nearly coincident surface, in the
/// surface's 2D frame. The side(s) of the surface facing the cover are hidden inside it.
struct Cover {
    std::vector<Vec2> polygon;
    bool front = false; ///< hides the front side
    bool back = false;  ///< hides the back side
};

struct SurfaceContacts {
    std::vector<Segment2> cuts; ///< lines where other surfaces touch or cross this one
    std::vector<Cover> covers;
};

/// \brief For every surface, the lines along which other surfaces touch or cross it (within
///        params.contact_tol) and the regions that coincident surfaces cover. Transversal
///        pairs meet on the line of intersection of their planes, over the parameter range
///        where both polygons come within the tolerance of the other's plane. Coincident
///        pairs (closer than the tolerance, parallel) cover the sides that face each other;
///        exactly coincident ones keep fronts over backs and the lower polygon index over
///        the higher (a duplicate is warned about, naming both surfaces).
std::vector<SurfaceContacts> find_contacts(const std::vector<Surface>& surfaces,
                                           const SurfaceBvh& bvh, const MeshParams& params,
                                           const Context& ctx);

} // namespace penumbra::mesher
