#pragma once
// What a lightmap bakes of a light (issue #29's mixed lighting): scene key `lightmap_mode` on
// point lights, the sun, the sky and emitting materials.

#include <span>

#include "core/enum_names.h"

namespace penumbra {

/// \brief What a lightmap bakes of one light, as engines split it (Unity's "Baked" and
///        "Mixed" light modes, Godot's "Static" and "Dynamic" bake modes).
enum class LightmapMode {
    all,      ///< its direct and its indirect light: the engine draws nothing of it live
    indirect, ///< only the light it sends by reflection: the engine draws its direct light
};
inline constexpr EnumName<LightmapMode> k_lightmap_mode_names[] = {
    {"all", LightmapMode::all},
    {"indirect", LightmapMode::indirect},
};
template <>
inline constexpr std::span<const EnumName<LightmapMode>> k_enum_names<LightmapMode> =
    k_lightmap_mode_names;

} // namespace penumbra
