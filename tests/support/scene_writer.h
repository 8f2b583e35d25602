#pragma once
// Writes a scene built in code as a scene file (docs/scene-format.md) that load_scene reads
// back: scene.json beside an OBJ/MTL pair holding the polygons and materials.

#include <string>

#include "core/scene.h"

namespace penumbra::bench {

/// \brief Writes \p dir/scene.json, \p dir/<stem>.obj and \p dir/<stem>.mtl (each atomically;
///        \p dir is created). Units are metres. The OBJ has one object (`o`) per run of
///        polygons with the same name and material and shares identical vertices; the MTL
///        holds reflectance (Kd) and emitted radiance (Ke); scene.json names the OBJ and holds
///        the material flags OBJ cannot carry, sensors, point lights, camera, and the mesher
///        and solver settings that differ from the defaults.
/// \throws ConfigError if \p dir cannot be written; ExternalError on I/O failure.
void write_scene(const Scene& scene, const std::string& dir, const std::string& stem);

} // namespace penumbra::bench
