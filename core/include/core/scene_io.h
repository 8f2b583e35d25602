#pragma once
// Scene file loading (format v1, docs/scene-format.md).

#include <string>

#include "core/scene.h"

namespace penumbra {

/// \brief Loads a scene file (JSON v1) with its geometry files (OBJ/MTL, glTF via assimp).
///        Converts units to metres and photometric quantities to radiometric ones, and
///        validates everything. Throws InputError naming the file and key on any problem.
Scene load_scene(const std::string& path);

/// \brief Parses a scene from JSON text; relative geometry paths resolve against \p base_dir.
///        \p file_name is used in messages.
Scene parse_scene(const std::string& json_text, const std::string& file_name,
                  const std::string& base_dir);

/// \brief Checks a scene built in code or loaded: finite coordinates, non-degenerate
///        polygons, materials in range, at least one emitter. Throws InputError.
void validate_scene(Scene& scene);

} // namespace penumbra
