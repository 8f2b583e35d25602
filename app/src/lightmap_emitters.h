#pragma once
// Which area emitters each polygon can see at all, for the lightmap fill's direct light
// (issue #29): on a floor of many rooms each texel sample would otherwise cast probe rays to
// every lamp of every room, nearly all of them blocked by walls.

#include <cstdint>
#include <vector>

#include "core/context.h"
#include "core/mesh.h"
#include "core/visibility.h"

namespace penumbra::app {

/// \brief Per input polygon of \p mesh (indexed by Patch::polygon), the emitting elements of
///        \p sources (increasing) that its front side may see: those facing it, and in front of
///        it, with at least one open line from the polygon's probe points (each element's
///        centroid and one of its corners pulled a fifth of the way in) to the emitter's
///        centroid and corners (in turn). An emitter left out is one whose every probe line a
///        wall or other surface blocks (a lamp in another room). A polygon whose elements face
///        different ways (curved) keeps every emitter. Deterministic (no random numbers);
///        parallel in \p ctx's arena.
std::vector<std::vector<std::uint32_t>> emitters_seen_by_polygons(const RadiosityMesh& mesh,
                                                                  const RadiosityMesh& sources,
                                                                  const VisibilityQuery& visibility,
                                                                  const Context& ctx);

} // namespace penumbra::app
