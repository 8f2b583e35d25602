#pragma once
// Private to penumbra_core: the luminance formulas of the CIE general skies and of Perez's
// all-weather sky, and the Perez weather relations (core/src/sky_models.cpp, perez_sky.cpp).
// Angles in radians.

#include "core/sky.h"

namespace penumbra {

/// \brief The five parameters of a CIE general sky: gradation a, b; indicatrix c, d, e.
struct CieParameters {
    double a, b, c, d, e;
};

/// \brief ISO 15469:2004 / CIE S 011/E:2003 Table 1, sky \p type in [1, 15].
/// \throws InternalError outside that range.
const CieParameters& cie_general_parameters(int type);

/// \brief φ(Z) = 1 + a exp(b / cos Z); its horizon value 1 (every b is negative) at and below
///        the horizon (cos Z ≤ 0).
double cie_gradation(const CieParameters& p, double cos_zenith);

/// \brief f(χ) = 1 + c [exp(d χ) − exp(d π/2)] + e cos² χ, χ the angle to the sun.
double cie_indicatrix(const CieParameters& p, double chi);

/// \brief The clearness bin of ε, 0 … 7 (upper bounds 1.065, 1.23, 1.5, 1.95, 2.8, 4.5, 6.2, ∞):
///        the row of Perez's luminance and efficacy tables.
int perez_clearness_bin(double clearness);

/// \brief Perez et al. 1993's a … e for one sky and sun zenith angle (clamped to [0, π/2]).
struct PerezCoefficients {
    double a, b, c, d, e;
};
PerezCoefficients perez_coefficients(const PerezSky& sky, double sun_zenith);

/// \brief Perez's l_v = (1 + a exp(b / cos Z)) (1 + c exp(d γ) + e cos² γ), with cos Z taken
///        ≥ 0.01 (perezlum.cal) and the result ≥ 0 (gendaymtx).
double perez_luminance(const PerezCoefficients& k, double cos_zenith, double gamma);

/// \brief ε and Δ (Perez et al. 1990, eqs. 1–2) of one hour's irradiance, clamped to
///        ε ∈ [1, 12.01), Δ ∈ [0.01, 0.6] as gendaylit does; no diffuse light: ε at its top.
PerezSky perez_clearness_and_brightness(const SolarIrradiance& irradiance, double sun_zenith,
                                        int day_of_year);

/// \brief Perez et al. 1990's diffuse-horizontal luminous efficacy (Table 4, eq. 7), lm/W, with
///        gendaylit's 2 cm of precipitable water.
double perez_diffuse_efficacy(const PerezSky& sky, double sun_zenith);

/// \brief Perez et al. 1990's direct-normal luminous efficacy (Table 4, eq. 8), lm/W, ≥ 0.
double perez_direct_efficacy(const PerezSky& sky, double sun_zenith);

} // namespace penumbra
