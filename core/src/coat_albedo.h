#pragma once
// Private to penumbra_core: the directional albedo of GGX reflection, tabulated once, for the
// plastic BSDF's diffuse weight (core/bsdf.h, PlasticLobe).

#include <vector>

#include "core/bsdf.h"

namespace penumbra {

/// \brief E(μ, α) = ∫ f_GGX cos θi dwi for a Fresnel factor a + b (1 − cos)⁵, as
///        a E₁(μ, α) + b E₅(μ, α): two tables over (μ, α) ∈ [0, 1]², interpolated
///        bilinearly, and their cosine-weighted averages over μ (exact for the interpolant, so
///        that the plastic's base integrates to exactly ρ (1 − E(μo))).
class CoatAlbedo {
public:
    /// The tables, built on first use (about 0.5 s on one core; immutable afterwards).
    static const CoatAlbedo& tables();

    /// E(μ) per channel.
    Rgb directional(double mu, double alpha, const LinearFresnel& fresnel) const;
    /// E_avg = 2 ∫ E(μ) μ dμ per channel.
    Rgb average(double alpha, const LinearFresnel& fresnel) const;

private:
    CoatAlbedo();

    static constexpr int k_nodes = 33; ///< nodes per axis, μ and α both i / 32
    double plain(int mu, int alpha) const { return plain_[mu * k_nodes + alpha]; }
    double fifth(int mu, int alpha) const { return fifth_[mu * k_nodes + alpha]; }

    std::vector<double> plain_, fifth_;                 ///< E₁ and E₅ at (μ, α) nodes
    std::vector<double> plain_average_, fifth_average_; ///< per α node
};

} // namespace penumbra
