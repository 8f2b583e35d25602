// Radiance's intermediate sky: skybright.cal's `intersky`, a gradation in the zenith angle η
// modulated by the sun's zenith angle Z_s, times an exponential fall-off in the angle γ from the
// sun. skybright.cal divides it by gensky's A4, an approximation of its zenith value; Penumbra's
// model divides it by its exact zenith value.

#include <cmath>

#include "core/sky.h"

#include "modifiers.h"

namespace penumbra {

namespace radiance {

double skybright_intersky(double eta, double gamma, double sun_zenith) {
    const double gradation =
        ((1.35 * std::sin(5.631 - 3.59 * eta) + 3.12) * std::sin(4.396 - 2.6 * sun_zenith) + 6.37 -
         eta) /
        2.326;
    return gradation * std::exp(gamma * -0.563 * ((2.629 - eta) * (1.562 - sun_zenith) + 0.812));
}

} // namespace radiance

double radiance_intermediate_sky(double zenith_angle, double sun_angle, double sun_zenith_angle) {
    return radiance::skybright_intersky(zenith_angle, sun_angle, sun_zenith_angle) /
           radiance::skybright_intersky(0, sun_zenith_angle, sun_zenith_angle);
}

} // namespace penumbra
