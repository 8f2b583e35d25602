#pragma once
// Private to penumbra_core: assimp materials to Materials, with the lobes that OBJ/MTL and
// glTF describe (docs/scene-format.md, "Materials of geometry files").

#include <string>

#include "core/material.h"

struct aiMaterial;

namespace penumbra {

/// \brief Which convention a geometry file's materials follow.
enum class MaterialConvention {
    mtl,  ///< OBJ's material library: illum, Kd, Ks, Ke, Ns, Pr, Ni, Tf, d/Tr
    gltf, ///< glTF 2.0 metallic-roughness, KHR_materials_transmission, _ior, _volume
    other ///< any other format: the diffuse and emissive colours only
};

/// \brief The extension of \p path in lower case, with its dot (".gltf"; "" for none).
std::string lowercase_extension(const std::string& path);

/// \brief The convention of the geometry file \p path, by its extension.
MaterialConvention material_convention(const std::string& path);

/// \brief The material of \p source (assimp's material \p index of \p path). Throws InputError
///        naming \p path and the material's key (e.g. 'glass.Ni') for a value out of range.
Material import_material(const aiMaterial& source, unsigned index, MaterialConvention convention,
                         const std::string& path);

} // namespace penumbra
