#pragma once
// Scenes built in code for the mesher's validation tests.

#include <array>
#include <vector>

#include "core/scene.h"

namespace penumbra::test {

/// A 1 × 1 m light (radiance 10 W/(sr·m²) per channel, facing down, 1 cm under the ceiling)
/// in room A = [0, 4.1] × [0, 4] × [0, 3] of two rooms side by side, [0, 8] × [0, 4] × [0, 3],
/// separated by a wall at x = 4.1 that starts \p gap above the floor (0 or 1 mm). Floor,
/// ceiling and the long walls are single polygons spanning both rooms. Reflectance 0.5.
Scene two_rooms(double gap);

/// A square light above a box standing on a 4 × 4 m floor (issue #5's error metric scene).
struct BoxUnderLight {
    Scene scene;
    std::uint32_t floor = 0, light = 0;
    double radiance = 0;              ///< of the light, W/(sr·m²) per channel
    std::vector<Vec3> light_vertices; ///< counter-clockwise seen from below
    std::vector<Vec3> box_vertices;   ///< the box's eight corners
    std::array<double, 4> footprint;  ///< x0, y0, x1, y1
};
BoxUnderLight box_under_light(double max_edge);

} // namespace penumbra::test
