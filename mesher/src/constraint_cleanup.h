#pragma once
// Clean-up of the constraint segments of one surface before triangulation. Constraints that
// nearly coincide, nearly meet or nearly lie on the outline would force the refinement down
// to their tiny separation; within the snap distance (≈ 2e-7 × scene diagonal) they are
// merged instead.

#include <vector>

#include "geometry2d.h"

namespace penumbra::mesher {

/// \brief Merges segments that are nearly parallel, lie within \p tol of each other's line
///        and overlap or touch into one segment on the longest one's line. Output order
///        follows the first input of each group.
std::vector<Segment2> merge_collinear(const std::vector<Segment2>& segments, double tol);

/// \brief \p segments clipped to \p outline, merged where nearly parallel and closer than
///        \p merge, without the parts lying (within \p merge) on an outline edge or on a
///        \p fixed segment; pieces shorter than a few \p snap distances are dropped. Parallel
///        constraints closer than the element size would make the refinement split both
///        alternately down to their distance.
std::vector<Segment2> clean_segments(const std::vector<Vec2>& outline,
                                     const std::vector<Segment2>& segments,
                                     const std::vector<Segment2>& fixed, double snap, double merge);

/// \brief The outline edges and the segments as a noded set ready for a constrained
///        triangulation: segment endpoints within \p merge of the outline move onto it, points
///        closer than \p merge are merged (outline vertices stay put), every segment is split at
///        its crossings with the others and at every vertex closer than \p merge to it,
///        duplicates removed. Afterwards segments meet only at shared endpoints and no vertex
///        lies within merge of a segment it does not end, so refinement never has to resolve
///        a near-degeneracy.
struct NodedSegment {
    Segment2 segment;
    bool outline = false; ///< a piece of an outline edge
};
std::vector<NodedSegment> node_segments(const std::vector<Vec2>& outline,
                                        const std::vector<Segment2>& segments, double merge);

} // namespace penumbra::mesher
