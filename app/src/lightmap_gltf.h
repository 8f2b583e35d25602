#pragma once
// The glTF 2.0 copy of a lightmap bake (issue #29): scene.gltf + scene.bin, each object a mesh
// with its lightmap UVs as TEXCOORD_1 and its materials carrying MOZ_lightmap, which points at
// the atlases' lightmap_N.png. docs/lightmaps.md, "glTF", describes the file.

#include <string>
#include <vector>

#include "app/lightmap.h"
#include "core/image.h"
#include "core/scene.h"

namespace penumbra::app {

/// \brief The MOZ_lightmap `intensity` of each atlas: its largest channel value of
///        179 lm/W × irradiance (lux), so that lightmap_N.png (lux / intensity) never clips;
///        1 for a black atlas.
std::vector<double> lightmap_intensities(const std::vector<Image>& atlases);

/// \brief Writes \p dir/lightmap_N.png per atlas: 8-bit sRGB of 179 lm/W × irradiance /
///        \p intensities[N] (MOZ_lightmap's encoding), atomically.
void write_moz_lightmaps(const std::string& dir, const std::vector<Image>& atlases,
                         const std::vector<double>& intensities);

/// \brief Writes \p dir/scene.bin, then \p dir/scene.gltf (each atomically): metres, +Y up
///        (Scene::up turned onto +Y), a node and mesh per object (Chart::object) with POSITION,
///        NORMAL (flat), TEXCOORD_0 = TEXCOORD_1 = the packed lightmap UVs and indices, one
///        primitive per material and atlas; a material per (scene material, atlas) with
///        baseColorFactor = diffuse reflectance, metallic 0, emission (KHR_materials_emissive_
///        strength) in cd/m² and MOZ_lightmap {texture lightmap_N.png, texCoord 1, intensity};
///        the scene's camera as a perspective camera. Throws ExternalError if tinygltf fails.
void write_lightmap_gltf(const std::string& dir, const Scene& scene, const LightmapResult& r,
                         const std::vector<double>& intensities);

} // namespace penumbra::app
