#pragma once
// Private to penumbra_core: `!gendaylit` lines (issue #30), read as Radiance's gendaylit(1)
// reads its arguments and turned into the primitives it would print: the `skyfunc` brightfunc
// of perezlum.cal and, for a sun above the horizon, the `solar` light and its `sun` source. The
// sky and sun are Penumbra's Perez sky (perez_sky_and_sun(), core/sky.h); the sun's position is
// gensky's (solar_position_gensky), so that a scene keeps Radiance's sun.

#include <vector>

#include "syntax.h"

namespace penumbra::radiance {

/// \brief Interprets \p command ("gendaylit month day [+]hour -W|-L|-G direct diffuse
///        options") into the primitives gendaylit prints, at the command's line. Options: -a,
///        -o, -m (as gensky's: west-positive longitude and meridian), -g, -s. Anything else
///        (-ang, -P, -E, -O, -i, time-zone names) and malformed arguments are InputErrors at
///        the command's line.
std::vector<Primitive> gendaylit_primitives(const Command& command);

} // namespace penumbra::radiance
