#pragma once
// State of a progressive shooting solve, per element (SoA).

#include <vector>

#include "core/mesh.h"
#include "core/rgb.h"

namespace penumbra::solver {

struct ShootingState {
    std::vector<Rgb> emission;         ///< E = πL, W/m²
    std::vector<Rgb> reflectance;      ///< ρ
    std::vector<Rgb> radiosity;        ///< B
    std::vector<Rgb> h_direct;         ///< irradiance from sources
    std::vector<Rgb> h_indirect;       ///< irradiance from reflected light
    std::vector<Rgb> unshot_emitted;   ///< emitted radiosity not yet shot
    std::vector<Rgb> unshot_reflected; ///< reflected radiosity not yet shot
    RgbD escaped;                      ///< W that left the scene
    RgbD emitted;                      ///< W emitted by elements and point lights

    explicit ShootingState(const RadiosityMesh& mesh);
    /// Adds irradiance to receiver j and its reflection to B and the unshot radiosity.
    void receive(std::size_t j, const Rgb& direct, const Rgb& indirect) {
        h_direct[j] += direct;
        h_indirect[j] += indirect;
        Rgb reflected = reflectance[j] * (direct + indirect);
        radiosity[j] += reflected;
        unshot_reflected[j] += reflected;
    }
    /// \brief Every element j receives \p direct[j] from a source at infinity (the sun, the
    ///        sky), whose power is what it delivers: Σ E A (W per channel), added to emitted
    ///        and returned.
    RgbD receive_from_afar(const std::vector<Rgb>& direct, const std::vector<double>& area);
};

} // namespace penumbra::solver
