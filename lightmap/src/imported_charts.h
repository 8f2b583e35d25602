#pragma once
// Charts from an object's own lightmap UV set (glTF TEXCOORD_1, Polygon::lightmap_uv).

#include <cstdint>
#include <optional>
#include <vector>

#include "core/scene.h"
#include "lightmap/charts.h"

namespace penumbra::lightmap {

/// \brief The object's polygons as one chart with their own lightmap UVs, scaled uniformly so
///        that the chart's uv area equals its 3D area (the texel density then holds on average
///        over the object). None when a triangle has no uv area or two overlap: the caller
///        generates charts instead. Every polygon must have lightmap_uv.
std::optional<Chart> imported_chart(const Scene& scene, const std::string& object,
                                    const std::vector<std::uint32_t>& polygons);

} // namespace penumbra::lightmap
