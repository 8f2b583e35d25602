#pragma once
// Private to penumbra_core: what a Radiance modifier primitive means to Penumbra (issue #30):
// a surface material, or skybright.cal's sky brightness function (a `brightfunc`), or a `glow`
// that such a function drives (the sky and ground hemispheres of gensky's scenes).

#include <optional>
#include <variant>

#include "core/material.h"
#include "core/sky.h"

#include "syntax.h"
#include "transform.h"

namespace penumbra::radiance {

/// \brief A material primitive: plastic, metal, glass, trans, light, glow or illum.
struct SurfaceMaterial {
    Material material;
    /// light, glow or illum: a `source` of this modifier is the sun or a uniform hemisphere.
    bool emitter = false;
};

/// \brief A skybright.cal `brightfunc`, resolved to Penumbra's sky model in the scene's axes.
struct SkyFunction {
    SkyModel model;
    double zenith_radiance = 0; ///< W/(sr·m²)
    double ground_radiance = 0; ///< skybright.cal's A3, W/(sr·m²)
    Compass compass;            ///< Radiance's z up and y north, after `!xform`
    Vec3 sun_direction;         ///< unit; the zenith when the function has none (overcast)
};

/// \brief A `glow` whose modifier is a SkyFunction: its colour scales the function.
struct SkyGlow {
    SkyFunction function;
    Rgb colour;
};

using Modifier = std::variant<SurfaceMaterial, SkyFunction, SkyGlow>;

/// \brief \p p as a material if its type is one (modifier `void` checked by the caller); throws
///        InputError at \p p's line on a wrong argument count or value. nullopt for other types.
std::optional<SurfaceMaterial> material_from(const Primitive& p);

/// \brief \p p, a `brightfunc`, as a SkyFunction with its directions moved by \p xf. Throws
///        InputError at \p p's line for anything but skybright.cal's `skybr` with sky types 1
///        (CIE clear), 2 (CIE overcast), 3 (uniform) or 4 (intermediate), or perezlum.cal's
///        `skybright` (PerezCoefficientsSky), and their argument counts.
SkyFunction sky_function_from(const Primitive& p, const Affine& xf);

/// \brief skybright.cal's `intersky` without its A2 / A4: the intermediate sky's luminance at
///        zenith angle \p eta and angle \p gamma from the sun, for the sun at zenith angle
///        \p sun_zenith (radians), in units of its own.
double skybright_intersky(double eta, double gamma, double sun_zenith);

/// \brief Throws InputError at \p p's line unless it has \p strings string arguments, no
///        integer arguments and one of the real argument counts \p reals (\p names lists what
///        they are, for the message).
void expect_arguments(const Primitive& p, std::size_t strings,
                      std::initializer_list<std::size_t> reals, const char* names);

} // namespace penumbra::radiance
