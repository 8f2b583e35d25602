#pragma once
// VTK XML output of the radiosity mesh and its solution.

#include <string>

#include "core/mesh.h"
#include "core/scene.h"

namespace penumbra::viewer {

/// \brief Writes \p path (.vtu, VTK XML unstructured grid, binary appended, zlib) atomically.
///        Cell data: radiosity, irradiance_direct, irradiance_indirect (RGB, W/m²),
///        illuminance_lx, luminance_cd_m2, reflectance, emission, surface_id, patch_id,
///        material_id, back_side. Point data: the same radiometric and photometric values
///        from the vertex solution, and surface_id.
/// \throws ExternalError if VTK cannot write the file.
void write_vtu(const std::string& path, const Scene& scene, const RadiosityMesh& mesh,
               const Solution& solution);

} // namespace penumbra::viewer
