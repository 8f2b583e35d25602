#pragma once
// State of a progressive shooting solve, per element (SoA).

#include <vector>

#include "core/mesh.h"
#include "core/rgb.h"

namespace penumbra::solver {

struct ShootingState {
    std::vector<Rgb> emission;         ///< E = πL, W/m²
    std::vector<Rgb> reflectance;      ///< ρ
    std::vector<Rgb> transmittance;    ///< τ, diffuse: passed to the twin
    std::vector<std::int32_t> twin;    ///< the other side's element, -1 if one-sided
    std::vector<Rgb> radiosity;        ///< B
    std::vector<Rgb> h_direct;         ///< irradiance from sources
    std::vector<Rgb> h_indirect;       ///< irradiance from reflected light
    std::vector<Rgb> unshot_emitted;   ///< emitted radiosity not yet shot
    std::vector<Rgb> unshot_reflected; ///< reflected radiosity not yet shot
    RgbD escaped;                      ///< W that left the scene
    RgbD emitted;                      ///< W emitted by elements and point lights

    explicit ShootingState(const RadiosityMesh& mesh);
    /// Adds irradiance to receiver j and its reflection to B and the unshot radiosity; what
    /// it passes to its other side is transmit()'s.
    void reflect(std::size_t j, const Rgb& direct, const Rgb& indirect) {
        h_direct[j] += direct;
        h_indirect[j] += indirect;
        Rgb reflected = reflectance[j] * (direct + indirect);
        radiosity[j] += reflected;
        unshot_reflected[j] += reflected;
    }
    /// Of irradiance \p h arriving at j, its twin sends τ h on (as it reflects: B and unshot).
    void transmit(std::size_t j, const Rgb& h) {
        const std::int32_t t = twin[j];
        if (t < 0 || transmittance[j].is_black())
            return;
        const Rgb passed = transmittance[j] * h;
        radiosity[std::size_t(t)] += passed;
        unshot_reflected[std::size_t(t)] += passed;
    }
    /// reflect() and transmit(): for serial callers (a twin is another element's slot).
    void receive(std::size_t j, const Rgb& direct, const Rgb& indirect) {
        reflect(j, direct, indirect);
        transmit(j, direct + indirect);
    }
    /// \brief Every element j receives \p direct[j] from a source at infinity (the sun, the
    ///        sky), whose power is what it delivers: Σ E A (W per channel), added to emitted
    ///        and returned.
    RgbD receive_from_afar(const std::vector<Rgb>& direct, const std::vector<double>& area);
};

} // namespace penumbra::solver
