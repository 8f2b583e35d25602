#pragma once
// The edges and vertices of all surfaces, merged where surfaces share them, with what the
// discontinuity mesher needs to know about their neighbourhood.

#include <cstdint>
#include <vector>

#include "surfaces.h"

namespace penumbra::mesher {

struct FeatureEdge {
    Vec3 a, b;
    std::vector<std::uint32_t> surfaces; ///< surfaces having this edge
    std::vector<Vec3> wings;             ///< per surface, its vertex farthest from the edge
};

struct FeatureVertex {
    Vec3 p;
    std::vector<std::uint32_t> surfaces; ///< surfaces having this vertex
    std::vector<Vec3> neighbours;        ///< the adjacent outline vertices in those surfaces
};

struct Features {
    std::vector<FeatureEdge> edges;
    std::vector<FeatureVertex> vertices;
};

/// Edges and vertices of \p surfaces; positions within \p merge of each other are one.
Features collect_features(const std::vector<Surface>& surfaces, double merge);

} // namespace penumbra::mesher
