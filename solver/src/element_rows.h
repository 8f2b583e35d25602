#pragma once
// Element-to-element form factors of one shooter (a "row"), for progressive shooting.

#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "core/visibility.h"

namespace penumbra::solver {

/// Per-element geometry in double precision, precomputed once.
struct ElementGeometry {
    std::vector<std::array<Vec3, 3>> triangle;
    std::vector<Vec3> normal;
    std::vector<double> area;
    std::vector<std::int32_t> twin;
    double offset = 0; ///< ray-origin offset along normals, metres
    double diagonal = 0;

    explicit ElementGeometry(const RadiosityMesh& mesh);
    std::size_t size() const { return area.size(); }
    /// True if any vertex of element \p e lies strictly in front of element \p f's plane.
    bool in_front_of(std::uint32_t e, std::uint32_t f) const;
};

struct RowSettings {
    int quadrature_level = 1;      ///< 4^level points on the shooter for distant receivers
    int near_quadrature_level = 3; ///< for receivers within about two element sizes
    int visibility_rays = 16; ///< per receiver, spread over the quadrature points
    int escape_rays = 64;     ///< cosine rays per shooter that estimate the escaping fraction
    std::uint64_t seed = 0;
};

/// Non-zero form factors F_ij of shooter i, receivers in increasing order.
struct Row {
    std::vector<std::uint32_t> receiver;
    std::vector<float> form_factor;
    double escape = 0; ///< fraction of i's power leaving the scene, from its own rays
    std::size_t bytes() const { return receiver.capacity() * 4 + form_factor.capacity() * 4; }
};

/// \brief F_ij = (1/A_i) ∫_i F(x → j) V(x, j) dx by the equal-weight rule on i, analytic
///        point-to-triangle F and visibility from rays keyed by (i, j, seed). For every
///        quadrature point Σ_j F(x → j) = 1 in a closed unoccluded scene, so rows conserve
///        energy exactly there. Parallel over receivers, deterministic.
Row compute_row(const ElementGeometry& geo, const VisibilityQuery& visibility, std::uint32_t i,
                const RowSettings& settings);

} // namespace penumbra::solver
