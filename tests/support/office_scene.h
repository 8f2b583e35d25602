#pragma once
// Generated open-plan office floors for the tests and benchmarks (issues #4 and #5): nx × ny
// offices with partitions (one door each), desks on legs, cabinets, windows cut into the exterior
// walls and a ceiling panel light per office. Every rectangle can be pre-tessellated into
// k × k quads, as exported CAD models are, so the input triangle count can be dialled from
// about a thousand to millions.

#include <cstdint>

#include "core/scene.h"

namespace penumbra::bench {

/// \brief Layout of a generated office floor. Offices are 4 × 3.5 m, 2.8 m high; floor and
///        ceiling are single rectangles spanning the floor plate, partitions run across it.
struct OfficeParams {
    int rooms_x = 2;           ///< offices along x, ≥ 1
    int rooms_y = 2;           ///< offices along y, ≥ 1
    int desks_per_room = 2;    ///< 0 to 4; a desk is a top and four legs (26 rectangles)
    int cabinets_per_room = 1; ///< 0 to 2; a cabinet is an open-bottom box (5 rectangles)
    /// Window openings per office in each exterior wall, 0.9 to 2.1 m above the floor; the
    /// wall is split into rectangles around them. 0 = closed walls.
    int windows_per_room = 1;
    int tessellation = 1; ///< every rectangle is split into k × k quads (2k² triangles)
};

/// \brief Builds the floor: materials "wall" (ρ 0.7), "desk" (ρ 0.4) and an emissive "panel"
///        (30 W/(sr·m²) from its front; its black back absorbs), a camera in the first
///        office and a work-plane sensor (0.8 m) in the middle of every office. Mesher and
///        solver settings are the defaults.
/// \throws ConfigError for parameters out of range.
Scene office_floor(const OfficeParams& params);

/// \brief Input triangles of a scene: a polygon with n vertices counts n − 2.
std::int64_t input_triangle_count(const Scene& scene);

/// \brief Parameters whose floor has about \p target input triangles: the tessellation grows
///        as target^¼ (1 up to 15 999 triangles, 5 at a million) and the offices, in a nearly
///        square layout, make up the rest. Furniture and windows are taken from \p base.
OfficeParams office_params_for_triangles(std::int64_t target, const OfficeParams& base = {});

/// \brief Mesher settings that keep the input tessellation as far as the mesher allows: no
///        contact splitting, no discontinuity meshing, no element budget and an element size
///        of 75 × the shortest input edge (at most the longest). The mesher merges outline
///        points closer than 1 % of the element size, so a larger size would collapse the
///        thinnest quads, and a smaller one refines the large ones; thin quads with no edge
///        below 5 % of it are still refined to a 20.7° minimum angle. The office floors get
///        about 1.3 elements per input triangle and side at every size.
void mesh_input_as_is(Scene& scene);

} // namespace penumbra::bench
