#pragma once
// Scene file loading (format v1, docs/scene-format.md).

#include <string>

#include "core/scene.h"

namespace penumbra {

/// \brief Where a scene's light comes from, for validation.
enum class SceneLight {
    own,     ///< its emitters, lights, sun or sky: a scene without any is an error
    weather, ///< a weather file (`penumbra annual`): the scene needs none of its own
};

/// \brief Loads a scene file (JSON v1) with its geometry files (OBJ/MTL, glTF via assimp).
///        Converts units to metres and photometric quantities to radiometric ones, and
///        validates everything. Throws InputError naming the file and key on any problem.
Scene load_scene(const std::string& path, SceneLight light = SceneLight::own);

/// \brief Parses a scene from JSON text; relative geometry paths resolve against \p base_dir.
///        \p file_name is used in messages.
Scene parse_scene(const std::string& json_text, const std::string& file_name,
                  const std::string& base_dir, SceneLight light = SceneLight::own);

/// \brief Checks a scene built in code or loaded: finite coordinates, non-degenerate
///        polygons, materials in range, at least one emitter (with SceneLight::own). Throws
///        InputError.
void validate_scene(Scene& scene, SceneLight light = SceneLight::own);

} // namespace penumbra
