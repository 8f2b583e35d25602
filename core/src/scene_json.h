#pragma once
// Private to penumbra_core: the JSON half of the scene loader (format v1,
// docs/scene-format.md). It type-checks every key, converts lengths to metres and photometric
// values to radiometric ones; files it names (geometry, .pts) are read by scene_io.cpp.

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/scene.h"

namespace penumbra {

/// \brief A `materials` entry: only the keys the file gives are set.
struct MaterialSpec {
    std::string name;
    std::optional<Rgb> reflectance;
    std::optional<Rgb> diffuse_transmittance;
    std::optional<Rgb> emission; ///< W/(sr·m²)
    std::optional<double> emission_flux_lm;
    std::optional<Rgb> emission_color; ///< only with emission_flux_lm
    std::optional<bool> two_sided;
    std::optional<bool> emission_two_sided;
    /// Set when the entry gives `type`: the material's lobe (none for "diffuse").
    std::optional<std::optional<Lobe>> lobe;
    std::optional<LightmapMode> lightmap_mode; ///< `lightmap_mode` (issue #29)
};

/// \brief A `polygons` entry, vertices already in metres.
struct PolygonSpec {
    std::string key; ///< "polygons[3]", for messages
    std::string name;
    std::string material;
    std::vector<Vec3> vertices;
};

/// \brief A `grids` entry: its polygon is looked up once the geometry files are read.
struct GridSpec {
    std::string key; ///< "grids.workplane", for messages
    std::string name;
    GridKind kind = GridKind::work_plane;
    /// The name of the scene's polygon(s) (`floor` or `wall` as a string), or inline vertices
    /// in metres.
    std::variant<std::string, std::vector<Vec3>> polygon;
    /// Metres: work plane, `height` above the floor along `up`; wall, `distance` in front.
    double offset_m = 0;
    double spacing_m = 0;
    double wall_offset_m = 0;
    Vec3 up{0, 0, 1}; ///< the scene's `up`, unit
};

/// \brief Everything the scene file says, before its files are read.
struct SceneSpec {
    /// name, file, point_lights, sun, inline sensors, camera, mesher, solver, render,
    /// lightmap and background are final.
    Scene scene;
    double metres_per_unit = 1.0;
    std::vector<std::string> geometry;      ///< as written, relative to the scene folder
    std::optional<std::string> sensor_file; ///< `sensors.file`, as written
    std::vector<MaterialSpec> materials;
    std::vector<MaterialSpec> blinds; ///< `annual.blinds`: overrides of scene materials
    /// Top-level `emission_two_sided`: for every material that does not give its own.
    std::optional<bool> emission_two_sided;
    /// `smooth_objects`: the object names whose polygons keep their vertex normals; unset =
    /// every polygon that has them.
    std::optional<std::vector<std::string>> smooth_objects;
    std::vector<PolygonSpec> polygons;
    std::vector<GridSpec> grids;
};

/// \brief Parses and type-checks the text of a scene file. Throws InputError naming
///        \p file_name and the dotted key (or the line, for malformed JSON).
SceneSpec parse_scene_json(const std::string& text, const std::string& file_name);

} // namespace penumbra
