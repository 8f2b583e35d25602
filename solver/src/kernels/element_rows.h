#pragma once
// Element-to-element form factors of one shooter (a "row"), for progressive shooting.

#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "core/visibility.h"

namespace penumbra::solver {

/// A triangle with the unit normal of the side it belongs to.
struct OrientedTriangle {
    std::array<Vec3, 3> v;
    Vec3 n;
};

/// \brief How far a ray toward a source at infinity (the sun, the sky) goes: out of the scene
///        from any point in it, whose diagonal is \p diagonal metres.
inline float distant_reach(double diagonal) {
    return float(2.0 * diagonal + 1.0);
}

/// Per-element geometry in double precision, precomputed once.
struct ElementGeometry {
    std::vector<std::array<Vec3, 3>> triangle;
    std::vector<Vec3> normal;
    std::vector<double> area;
    std::vector<std::int32_t> twin;
    std::vector<std::uint8_t> emitter; ///< the element emits light
    double offset = 0;                 ///< ray-origin offset along normals, metres
    double diagonal = 0;

    explicit ElementGeometry(const RadiosityMesh& mesh);
    std::size_t size() const { return area.size(); }
    /// True if any vertex of element \p e lies strictly in front of element \p f's plane.
    bool in_front_of(std::uint32_t e, std::uint32_t f) const;
    OrientedTriangle oriented(std::uint32_t e) const { return {triangle[e], normal[e]}; }
};

struct RowSettings {
    int quadrature_level = 1;       ///< 4^level points on the shooter for distant receivers
    int near_quadrature_level = 3;  ///< for receivers within about one element size
    int apart_quadrature_level = 3; ///< the same for such receivers that share no vertex
    int visibility_rays = 16;       ///< per receiver, spread over the quadrature points
    int escape_rays = 64;           ///< cosine rays per shooter that estimate the escaping fraction
    int escape_rays_emitter = 4096; ///< the same for emitters, which carry the direct power
    std::uint64_t seed = 0;
};

struct PairFormFactor {
    double f = 0;            ///< with visibility
    double f_unoccluded = 0; ///< without
    bool partial = false;    ///< the visibility rays disagreed (a penumbra)
    /// Spread of the point form factors over a's quadrature points (0 where a point lies
    /// behind b): how far F varies over a, the error of giving all of a one value.
    double f_spread = 0;
};

/// \brief F_ab = (1/A_a) ∫_a F(x → b) V(x, b) dx by the equal-weight rule of \p level on a,
///        analytic point-to-triangle F, and its visible fraction from rays that leave the
///        points in proportion to their share of the transfer, from a stream keyed by
///        (key_a, key_b, seed): as many probes as points (4 to 16), \p visibility_rays more
///        unless all were open. The caller checks that a and b face each other.
PairFormFactor triangle_form_factor(const OrientedTriangle& a, const OrientedTriangle& b, int level,
                                    const VisibilityQuery& visibility, double offset,
                                    std::uint64_t key_a, std::uint64_t key_b,
                                    const RowSettings& settings);

/// F_ab by the rule of \p level for a pair known to be fully visible (no rays): the part of a
/// fully visible link, whose own rays were all open.
PairFormFactor triangle_form_factor_visible(const OrientedTriangle& a, const OrientedTriangle& b,
                                            int level);

/// True if any vertex of \p a lies in front of \p b's plane by more than \p eps.
bool in_front(const OrientedTriangle& a, const OrientedTriangle& b, double eps);

/// Pairs whose centroids are closer than this many times the sum of their longest edges need
/// the fine rule: there F(x → b) varies fast over a (log-singular next to a shared edge) and
/// the coarse rule breaks reciprocity. Beyond it the rule follows a's size over the distance
/// (quadrature_level_for). 1 rather than 2: the validation results stay within their
/// tolerances, and solves are faster (docs/calibration.md#k_near_factor).
inline constexpr double k_near_factor = 1.0;

/// True if a and b are near in the sense of k_near_factor.
bool is_near(const OrientedTriangle& a, const OrientedTriangle& b);

/// \brief Quadrature level for integrating over \p a toward \p b: the near level within
///        k_near_factor sizes, else finer the larger a is relative to the distance (one level
///        above a tenth, two above 0.4), whatever b's size.
int quadrature_level_for(const OrientedTriangle& a, const OrientedTriangle& b,
                         const RowSettings& settings);

/// Non-zero form factors F_ij of shooter i, receivers in increasing order.
struct Row {
    std::vector<std::uint32_t> receiver;
    std::vector<float> form_factor;
    double escape = 0; ///< fraction of i's power leaving the scene, from its own rays
    std::size_t bytes() const { return receiver.capacity() * 4 + form_factor.capacity() * 4; }
};

/// \brief Fraction of element i's emitted power that leaves the scene, from its own cosine rays
///        (escape_rays, or escape_rays_emitter for emitters).
double escape_fraction(const ElementGeometry& geo, const VisibilityQuery& visibility,
                       std::uint32_t i, const RowSettings& settings);

/// \brief F_ij = (1/A_i) ∫_i F(x → j) V(x, j) dx by the equal-weight rule on i, analytic
///        point-to-triangle F and visibility from rays keyed by (i, j, seed). For every
///        quadrature point Σ_j F(x → j) = 1 in a closed unoccluded scene, so rows conserve
///        energy exactly there. Parallel over receivers, deterministic.
Row compute_row(const ElementGeometry& geo, const VisibilityQuery& visibility, std::uint32_t i,
                const RowSettings& settings);

} // namespace penumbra::solver
