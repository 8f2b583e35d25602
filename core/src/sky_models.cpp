// The relative luminance formulas of the CIE general skies (ISO 15469:2004 / CIE S 011/E:2003)
// and of Perez's all-weather sky (Perez, Seals & Michalsky 1993, "All-weather model for sky
// luminance distribution — preliminary configuration and validation", Solar Energy 50(3)
// 235–245, with its erratum, Solar Energy 51(5) 423). Near and below the horizon they follow
// Radiance's skybright.cal and perezlum.cal, so that the horizon blend matches Radiance's.

#include "sky_models.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace penumbra {

namespace {

// ISO 15469:2004 / CIE S 011/E:2003, Table 1: sky type → gradation group (a, b: I 4.0 −0.70,
// II 1.1 −0.80, III 0 −1.0, IV −1.0 −0.55, V −1.0 −0.32, VI −1.0 −0.15) and indicatrix group
// (c, d, e: 1 0 −1.0 0, 2 2 −1.5 0.15, 3 5 −2.5 0.30, 4 10 −3.0 0.45, 5 16 −3.0 0.30,
// 6 24 −2.8 0.15).
constexpr CieParameters k_cie_general[15] = {
    {4.0, -0.70, 0, -1.0, 0.00},   //  1 I.1   overcast, steep gradation, azimuthal uniformity
    {4.0, -0.70, 2, -1.5, 0.15},   //  2 I.2   overcast, steep gradation, slight brightening
    {1.1, -0.80, 0, -1.0, 0.00},   //  3 II.1  overcast, moderate gradation, uniform azimuth
    {1.1, -0.80, 2, -1.5, 0.15},   //  4 II.2  overcast, moderate gradation, slight brightening
    {0.0, -1.00, 0, -1.0, 0.00},   //  5 III.1 sky of uniform luminance
    {0.0, -1.00, 2, -1.5, 0.15},   //  6 III.2 partly cloudy, no gradation, slight brightening
    {0.0, -1.00, 5, -2.5, 0.30},   //  7 III.3 partly cloudy, no gradation, brighter circumsolar
    {0.0, -1.00, 10, -3.0, 0.45},  //  8 III.4 partly cloudy, no gradation, distinct corona
    {-1.0, -0.55, 2, -1.5, 0.15},  //  9 IV.2  partly cloudy, obscured sun
    {-1.0, -0.55, 5, -2.5, 0.30},  // 10 IV.3  partly cloudy, brighter circumsolar region
    {-1.0, -0.55, 10, -3.0, 0.45}, // 11 IV.4  white-blue sky, distinct solar corona
    {-1.0, -0.32, 10, -3.0, 0.45}, // 12 V.4   CIE standard clear sky, low turbidity
    {-1.0, -0.32, 16, -3.0, 0.30}, // 13 V.5   CIE standard clear sky, polluted atmosphere
    {-1.0, -0.15, 16, -3.0, 0.30}, // 14 VI.5  cloudless turbid sky, broad solar corona
    {-1.0, -0.15, 24, -2.8, 0.15}, // 15 VI.6  white-blue turbid sky, broad solar corona
};

// Perez, Seals & Michalsky 1993, Table 1: for each of the eight clearness bins (ε from 1,
// 1.065, 1.23, 1.5, 1.95, 2.8, 4.5, 6.2), the four coefficients x1 … x4 of each of a, b, c, d, e
// in x = x1 + x2 Z + Δ (x3 + x4 Z), Z the sun's zenith angle (rad); in the first bin c and d
// take the forms of eqs. 7–8 instead (perez_coefficients).
constexpr double k_perez_table[8][5][4] = {
    {{1.3525, -0.2576, -0.2690, -1.4366},
     {-0.7670, 0.0007, 1.2734, -0.1233},
     {2.8000, 0.6004, 1.2375, 1.0000},
     {1.8734, 0.6297, 0.9738, 0.2809},
     {0.0356, -0.1246, -0.5718, 0.9938}},
    {{-1.2219, -0.7730, 1.4148, 1.1016},
     {-0.2054, 0.0367, -3.9128, 0.9156},
     {6.9750, 0.1774, 6.4477, -0.1239},
     {-1.5798, -0.5081, -1.7812, 0.1080},
     {0.2624, 0.0672, -0.2190, -0.4285}},
    {{-1.1000, -0.2515, 0.8952, 0.0156},
     {0.2782, -0.1812, -4.5000, 1.1766},
     {24.7219, -13.0812, -37.7000, 34.8438},
     {-5.0000, 1.5218, 3.9229, -2.6204},
     {-0.0156, 0.1597, 0.4199, -0.5562}},
    {{-0.5484, -0.6654, -0.2672, 0.7117},
     {0.7234, -0.6219, -5.6812, 2.6297},
     {33.3389, -18.3000, -62.2500, 52.0781},
     {-3.5000, 0.0016, 1.1477, 0.1062},
     {0.4659, -0.3296, -0.0876, -0.0329}},
    {{-0.6000, -0.3566, -2.5000, 2.3250},
     {0.2937, 0.0496, -5.6812, 1.8415},
     {21.0000, -4.7656, -21.5906, 7.2492},
     {-3.5000, -0.1554, 1.4062, 0.3988},
     {0.0032, 0.0766, -0.0656, -0.1294}},
    {{-1.0156, -0.3670, 1.0078, 1.4051},
     {0.2875, -0.5328, -3.8500, 3.3750},
     {14.0000, -0.9999, -7.1406, 7.5469},
     {-3.4000, -0.1078, -1.0750, 1.5702},
     {-0.0672, 0.4016, 0.3017, -0.4844}},
    {{-1.0000, 0.0211, 0.5025, -0.5119},
     {-0.3000, 0.1922, 0.7023, -1.6317},
     {19.0000, -5.0000, 1.2438, -1.9094},
     {-4.0000, 0.0250, 0.3844, 0.2656},
     {1.0468, -0.3788, -2.4517, 1.4656}},
    {{-1.0500, 0.0289, 0.4260, 0.3590},
     {-0.3250, 0.1156, 0.7781, 0.0025},
     {31.0625, -14.5000, -46.1148, 55.3750},
     {-7.2312, 0.4050, 13.3500, 0.6234},
     {1.5000, -0.6426, 1.8564, 0.5636}},
};

double linear_in_zenith_and_brightness(const double x[4], double zenith, double brightness) {
    return x[0] + x[1] * zenith + brightness * (x[2] + x[3] * zenith);
}

} // namespace

int perez_clearness_bin(double clearness) {
    constexpr double upper[7] = {1.065, 1.230, 1.500, 1.950, 2.800, 4.500, 6.200};
    return int(std::upper_bound(std::begin(upper), std::end(upper), clearness) - std::begin(upper));
}

const CieParameters& cie_general_parameters(int type) {
    if (type < 1 || type > 15)
        throw InternalError("CIE general sky type " + std::to_string(type) + " is outside [1, 15]");
    return k_cie_general[type - 1];
}

double cie_gradation(const CieParameters& p, double cos_zenith) {
    return cos_zenith > 0 ? 1 + p.a * std::exp(p.b / cos_zenith) : 1.0;
}

double cie_indicatrix(const CieParameters& p, double chi) {
    const double cos_chi = std::cos(chi);
    return 1 + p.c * (std::exp(p.d * chi) - std::exp(p.d * k_pi / 2)) + p.e * cos_chi * cos_chi;
}

PerezCoefficients perez_coefficients(const PerezSky& sky, double sun_zenith) {
    const double z = std::clamp(sun_zenith, 0.0, k_pi / 2);
    double delta = sky.brightness;
    // Perez et al. 1993 (as gendaylit applies it): intermediate skies with a dark sky take
    // Δ ≥ 0.2, where the fit had no data.
    if (sky.clearness > 1.065 && sky.clearness < 2.8)
        delta = std::max(delta, 0.2);
    const int bin = perez_clearness_bin(sky.clearness);
    const auto& x = k_perez_table[bin];
    PerezCoefficients k{};
    k.a = linear_in_zenith_and_brightness(x[0], z, delta);
    k.b = linear_in_zenith_and_brightness(x[1], z, delta);
    k.e = linear_in_zenith_and_brightness(x[4], z, delta);
    if (bin == 0) { // eqs. 7 and 8 of the paper for the overcast bin
        k.c = std::exp(std::pow(delta * (x[2][0] + x[2][1] * z), x[2][2])) - x[2][3];
        k.d = -std::exp(delta * (x[3][0] + x[3][1] * z)) + x[3][2] + delta * x[3][3];
    } else {
        k.c = linear_in_zenith_and_brightness(x[2], z, delta);
        k.d = linear_in_zenith_and_brightness(x[3], z, delta);
    }
    return k;
}

double perez_luminance(const PerezCoefficients& k, double cos_zenith, double gamma) {
    const double cos_gamma = std::cos(gamma);
    const double gradation = 1 + k.a * std::exp(k.b / std::max(cos_zenith, 0.01));
    const double indicatrix = 1 + k.c * std::exp(k.d * gamma) + k.e * cos_gamma * cos_gamma;
    return std::max(0.0, gradation * indicatrix);
}

} // namespace penumbra
