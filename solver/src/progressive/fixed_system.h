#pragma once
// The radiosity system on fixed elements, B = E + ρ (L + K B) + τ (L + K B)_twin (τ the
// diffuse transmittance, twin the other side's element), with K_ji = F_ij A_i / A_j
// assembled from the shooting rows (so shooting, Jacobi, Gauss–Seidel and the dense matrix
// solve all solve the same system), and its gathering and direct solvers.

#include <cstdint>
#include <vector>

#include "core/context.h"
#include "core/scene.h"
#include "core/visibility.h"
#include "kernels/element_rows.h"
#include "output/vertex_values.h"
#include "solver/solver.h"

namespace penumbra::solver {

struct FixedSystem {
    std::vector<std::uint32_t> offset; ///< CSR by receiver: entries offset[j] .. offset[j+1]
    std::vector<std::uint32_t> source;
    std::vector<float> k;       ///< K_ji
    std::vector<double> escape; ///< per source element, fraction of its power escaping
    std::vector<Rgb> emission, reflectance, transmittance;
    std::vector<std::int32_t> twin;      ///< the other side's element, -1 if one-sided
    std::vector<Rgb> light_direct;       ///< irradiance from point lights, per element
    RgbD light_emitted, light_escaped;   ///< W
    const RadiosityMesh* mesh = nullptr; ///< outlives the system
    std::size_t size() const { return emission.size(); }
    const Patch& patch(std::size_t e) const { return mesh->patch_of(std::uint32_t(e)); }
};

FixedSystem build_fixed_system(const Scene& scene, const RadiosityMesh& mesh,
                               const ElementGeometry& geo, const VisibilityQuery& visibility,
                               const RowSettings& settings, const Context& ctx);

/// \brief Jacobi (or in-place Gauss–Seidel, in element order) sweeps until the power changing
///        per sweep falls below settings.residual of the emitted power.
ElementResult solve_gathering(const FixedSystem& system, const ElementGeometry& geo,
                              const SolverSettings& settings, bool gauss_seidel, const Context& ctx,
                              SolveStats* stats);

/// \brief Dense LU (Eigen) of (I − ρK − τK_twin) B = E + ρL + τL_twin per channel. For small
///        scenes and tests.
/// \throws ConfigError above 6000 elements.
ElementResult solve_matrix(const FixedSystem& system, const ElementGeometry& geo,
                           const Context& ctx, SolveStats* stats);

/// \brief The power balance of an element result under \p system.
PowerBalance fixed_balance(const FixedSystem& system, const ElementGeometry& geo,
                           const ElementResult& result, double unconverged_power_fraction);

} // namespace penumbra::solver
