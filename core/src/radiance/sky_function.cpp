// skybright.cal's `skybr` (the function gensky's skies call) as Penumbra's sky models. Its
// arguments: A1 the sky type (1 clear, 2 overcast, 3 uniform, 4 intermediate), A2 the zenith
// brightness, A3 the ground's, and for the clear and intermediate skies A4 a normalisation and
// A5–A7 the direction toward the sun. And perezlum.cal's `skybright` (gendaylit's): A1 the
// diffuse normalisation (the radiance is A1 l_v), A2 the ground's brightness, A3–A7 Perez's
// a … e, A8–A10 the direction toward the sun.

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "modifiers.h"
#include "sky_models.h"

namespace penumbra::radiance {

namespace {

constexpr double k_pi = 3.14159265358979323846;

/// ISO 15469 / CIE S 011 indicatrix of sky type 12 (c = 10, d = −3, e = 0.45) at the angle
/// \p chi from the sun.
double cie_clear_indicatrix(double chi) {
    const double c = std::cos(chi);
    return 1 + 10 * (std::exp(-3 * chi) - std::exp(-3 * k_pi / 2)) + 0.45 * c * c;
}

/// The CIE clear sky's zenith radiance from skybright.cal's arguments. skybright.cal's
/// clear sky is ISO 15469 type 12 (gradation a = −1, b = −0.32; indicatrix c = 10, d = −3,
/// e = 0.45) written as A2 · f(γ) · φ(θ) / A4 with gensky's A4 = 0.274 f(Z_s): its indicatrix
/// constant 0.91 is the standard's 1 − 10 e^(−3π/2) = 0.91009 rounded, and it divides by
/// 0.274 where the standard's φ(0) = 1 − e^(−0.32) = 0.27385, so its zenith radiance is
/// A2 · 0.99945, not A2. Penumbra's model is L_z f(γ) φ(θ) / (f(Z_s) φ(0)); equal to
/// skybright.cal's (to 1e-4) with the L_z below.
double clear_sky_zenith(double a2, double a4, double sun_zenith_angle) {
    const double phi_zenith = 1 - std::exp(-0.32);
    return a2 * cie_clear_indicatrix(sun_zenith_angle) * phi_zenith / a4;
}

bool calls(const Primitive& p, const char* function, const char* file) {
    return p.strings.size() == 2 && p.strings[0] == function &&
           std::filesystem::path(p.strings[1]).filename() == file;
}

/// perezlum.cal's sky: A1 l_v(dir), so its zenith radiance is A1 l_v(zenith).
SkyFunction perez_sky_function(const Primitive& p, const Affine& xf) {
    expect_arguments(p, 2, {10}, "diffuse-normalisation ground a b c d e sun-x sun-y sun-z");
    const std::vector<double>& a = p.reals;
    const Vec3 sun(a[7], a[8], a[9]);
    if (!(a[0] >= 0 && a[1] >= 0) || !(length(sun) > 0))
        fail(p.where, fmt::format("brightfunc '{}': the diffuse normalisation and the ground "
                                  "brightness must be >= 0 and the sun direction non-zero",
                                  p.id));
    const PerezCoefficients k{a[2], a[3], a[4], a[5], a[6]};
    const double sun_angle_at_zenith = std::acos(std::clamp(normalize(sun).z, -1.0, 1.0));
    SkyFunction f;
    f.model = PerezCoefficientsSky{k.a, k.b, k.c, k.d, k.e};
    f.compass = {.up = xf.direction({0, 0, 1}), .north = xf.direction({0, 1, 0})};
    f.sun_direction = xf.direction(normalize(sun));
    f.zenith_radiance = a[0] * perez_luminance(k, 1.0, sun_angle_at_zenith);
    f.ground_radiance = a[1];
    return f;
}

} // namespace

SkyFunction sky_function_from(const Primitive& p, const Affine& xf) {
    if (calls(p, "skybright", "perezlum.cal"))
        return perez_sky_function(p, xf);
    if (!calls(p, "skybr", "skybright.cal"))
        fail(p.where, fmt::format("brightfunc '{}': only skybright.cal's 'skybr' (2 skybr "
                                  "skybright.cal) and perezlum.cal's 'skybright' (2 skybright "
                                  "perezlum.cal) are supported",
                                  p.id));
    const double type = p.reals.empty() ? 0 : p.reals[0];
    if (type != 1 && type != 2 && type != 3 && type != 4)
        fail(p.where, fmt::format("brightfunc '{}': the sky type (first real argument) must be "
                                  "1 (CIE clear), 2 (CIE overcast), 3 (uniform) or 4 "
                                  "(intermediate), got {}",
                                  p.id, type));
    const bool with_sun = type == 1 || type == 4;
    expect_arguments(p, 2, {with_sun ? std::size_t(7) : std::size_t(3)},
                     with_sun ? "type zenith ground normalisation sun-x sun-y sun-z"
                              : "type zenith ground");
    SkyFunction f;
    f.compass = {.up = xf.direction({0, 0, 1}), .north = xf.direction({0, 1, 0})};
    f.sun_direction = f.compass.up;
    f.ground_radiance = p.reals[2];
    if (!(p.reals[1] >= 0 && f.ground_radiance >= 0))
        fail(p.where,
             fmt::format("brightfunc '{}': the zenith and ground brightness must be >= 0", p.id));
    if (!with_sun) {
        f.model = type == 2 ? SkyModel{CieOvercastSky{}} : SkyModel{UniformSky{}};
        f.zenith_radiance = p.reals[1]; // (1 + 2 cos θ)/3 and 1 at the zenith: A2 exactly
        return f;
    }
    const Vec3 sun(p.reals[4], p.reals[5], p.reals[6]);
    if (!(length(sun) > 0) || !(p.reals[3] > 0))
        fail(p.where, fmt::format("brightfunc '{}': the normalisation must be > 0 and the sun "
                                  "direction non-zero",
                                  p.id));
    const double sun_zenith = std::acos(std::clamp(normalize(sun).z, -1.0, 1.0));
    if (type == 1) {
        f.model = CieGeneralSky{12};
        f.zenith_radiance = clear_sky_zenith(p.reals[1], p.reals[3], sun_zenith);
    } else {
        // skybright.cal: A2 × intersky / A4; radiance_intermediate_sky is intersky over its
        // zenith value, of which gensky's A4 is an approximation.
        f.model = RadianceIntermediateSky{};
        f.zenith_radiance = p.reals[1] * skybright_intersky(0, sun_zenith, sun_zenith) / p.reals[3];
    }
    f.sun_direction = xf.direction(sun);
    return f;
}

} // namespace penumbra::radiance
