#pragma once
// Private to penumbra_core: the scene key `grids` expanded into sensors on a square lattice (a
// work plane over a floor, or points on a wall), and the checks of Scene::grids.

#include <vector>

#include "core/scene.h"

#include "scene_json.h"

namespace penumbra {

/// \brief Appends the sensors of each grid of \p specs to scene.sensors (named
///        "GRID:ROW:COLUMN") and its lattice to scene.grids. Polygon names refer to
///        scene.polygons, so the geometry files must be read first. Throws InputError naming
///        the grid's key.
void add_sensor_grids(Scene& scene, const std::vector<GridSpec>& specs);

/// \brief Checks scene.grids for scenes built in code as well: names usable in file names and
///        unique, lattices whose sensor indices lie within scene.sensors. Throws InputError.
void validate_sensor_grids(const Scene& scene);

} // namespace penumbra
