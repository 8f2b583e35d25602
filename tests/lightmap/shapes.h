#pragma once
// Generated test geometry for the lightmap suite.

#include <string>

#include "core/scene.h"

namespace penumbra::test {

/// Adds a UV sphere of \p rings × \p segments faces (quads, triangles at the poles) facing
/// outwards, as one object.
void add_sphere(Scene& scene, const std::string& name, std::uint32_t material, const Vec3& centre,
                double radius, int rings, int segments);

/// Adds the outside of a cylinder patch around the z axis: \p segments quads from angle 0 to
/// \p angle_rad, height \p height, as one object.
void add_cylinder_patch(Scene& scene, const std::string& name, std::uint32_t material,
                        double radius, double height, double angle_rad, int segments);

} // namespace penumbra::test
