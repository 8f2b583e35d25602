#pragma once
// Private to penumbra_core: geometry files (OBJ/MTL, glTF/GLB, anything assimp reads) to
// polygons and materials. The scene loader merges the result into a Scene.

#include <string>
#include <vector>

#include "core/scene.h"

namespace penumbra {

/// \brief Polygons and materials of one geometry file; Polygon::material indexes `materials`.
struct ImportedGeometry {
    std::vector<Material> materials;
    std::vector<Polygon> polygons;
};

/// \brief Reads \p path with assimp and keeps its polygons as written (no triangulation).
///        Node transforms are applied (a mirroring transform reverses the vertex order so the
///        front side stays the front), then every coordinate is multiplied by
///        \p metres_per_unit. Polygon::name is the node name (the OBJ `o`/`g` name), else the
///        mesh name; Polygon::source is "<label>:face N", N counting polygons from 1 in the
///        file's order. Points and lines are skipped. Materials no face uses (among them
///        assimp's default material) are dropped. Throws InputError naming \p path and the key
///        'geometry'.
ImportedGeometry import_geometry(const std::string& path, const std::string& label,
                                 double metres_per_unit);

} // namespace penumbra
