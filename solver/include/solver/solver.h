#pragma once
// The radiosity solver: the light every mesh element reflects, from the scene's emissive
// polygons, point lights and sun. By default hierarchical radiosity (Hanrahan et al. 1991,
// with clusters: solver/src/hierarchical.cpp), which refines the mesh elements and the links
// between them until the refinement oracle is under ε; the fixed-element methods (progressive
// shooting, Jacobi, Gauss–Seidel, a dense matrix solve) solve on the mesh as it is. Form
// factors are analytic polygon form factors times ray-traced visibility (core/visibility.h);
// docs/architecture.md shows the solver's parts.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/context.h"
#include "core/mesh.h"
#include "core/scene.h"
#include "core/visibility.h"

namespace penumbra::solver {

/// \brief Power bookkeeping of a solve, W per channel. emitted = absorbed + escaped + glazing
///        + residual up to discretisation error (reported as imbalance).
struct PowerBalance {
    /// By emissive elements and point lights, and by the sun and the sky: the power their
    /// direct light delivers to the scene's surfaces (Σ E_direct A), none of which escapes.
    RgbD emitted;
    RgbD absorbed; ///< Σ (1 − ρ − τ) H A over opaque elements (τ: diffuse transmittance)
    /// Leaving the scene through openings and (T(θ) of it) through glazing, estimated by
    /// its own rays.
    RgbD escaped;
    /// What panes of glazing absorb and reflect of the light that reaches them from inside:
    /// Σ (1 − T_h) H A over their elements, T_h their hemispherical transmittance (the part
    /// they let through is in escaped).
    RgbD glazing;
    RgbD residual; ///< unshot power left when the solve stopped
    /// (emitted − absorbed − escaped − glazing − residual) / emitted, luminance-weighted.
    double relative_imbalance() const;
    /// \brief Books irradiance \p h (W/m²) on \p area m² of a surface of \p patch: absorbed
    ///        by an opaque one (1 − ρ − τ of it: the rest it reflects or passes to its other
    ///        side), glazing's for a pane.
    void receive(const Patch& patch, const RgbD& h, double area);
};

struct SolveStats {
    std::int64_t shots = 0;  ///< shots (shooting) or sweeps (gathering, hierarchical)
    std::uint64_t links = 0; ///< hierarchical: links at the end
    std::uint64_t rays = 0;
    double seconds_form_factors = 0;
    double seconds_total = 0;
    PowerBalance power;
    std::vector<double>
        residual_history; ///< relative unshot power after every N shots (N = elements)
};

/// \brief Watches a solve: called with a snapshot every \p every_shots shots (shooting) or
///        sweeps (gathering, hierarchical) and once at the end (final = true). Snapshots are
///        on the input mesh (hierarchical: the roots' pulled values), with vertex values
///        averaged from the elements; the final call of shooting carries the full solution.
struct SolveObserver {
    std::int64_t every_shots = 0; ///< 0 = only the final call
    std::function<void(const Solution& snapshot, std::int64_t shots, double relative_unshot,
                       bool final)>
        on_pass;
};

/// \brief A solve's output: the solution, and for hierarchical radiosity the leaf mesh it
///        lives on (without T-vertices); otherwise the solution is on the input mesh.
/// The hierarchy, links and radiosities of a hierarchical solve (opaque): a re-solve after a
/// change of reflectances or emissions (same geometry) starts from it.
struct HierarchicalState;

struct SolveResult {
    std::optional<RadiosityMesh> refined_mesh;
    Solution solution;
    std::shared_ptr<const HierarchicalState> state; ///< hierarchical only
};

/// \brief Writes \p state to \p path (binary, versioned; atomically).
void write_hierarchical_state(const HierarchicalState& state, const std::string& path);

/// \brief Reads a state written by write_hierarchical_state.
/// \throws InputError naming \p path if it is missing, truncated or not a state file.
std::shared_ptr<const HierarchicalState> read_hierarchical_state(const std::string& path);

/// \brief Solves with scene.solver.method (SolverMethod). Hierarchical: with \p reuse, keeps
///        its hierarchy and links, takes reflectances and emissions from \p scene, re-runs
///        the refinement oracle and iterates from its radiosities.
///        \p specular (null or empty: none; per element of \p mesh): light that reaches
///        elements through specular surfaces (caustic photons, issue #28): the sources' part
///        a fixed source whose reflection ρ H the solve spreads like any light, the transfers
///        between diffuse elements (given, or traced by SpecularLight::trace_transfers from
///        the first cycle's exitance) applied to the radiosities of every sweep, so that light
///        crossing specular surfaces any number of times converges with the rest. It is in
///        the elements' indirect irradiance, not in their emission, and the balance books it
///        as emitted (delivered) power. The hierarchical method only: the others warn and
///        leave it out.
/// \throws ConfigError for a scene too large for SolverMethod::matrix, or a \p reuse
///         state of another geometry or with another method.
SolveResult solve(const Scene& scene, const RadiosityMesh& mesh, const VisibilityQuery& visibility,
                  const Context& ctx, SolveStats* stats = nullptr,
                  const SolveObserver* observer = nullptr, const HierarchicalState* reuse = nullptr,
                  const SpecularLight* specular = nullptr);

/// \brief Solves the radiosity of \p mesh by progressive shooting until the unshot power falls
///        below SolverSettings::residual of the emitted power.
///        Deterministic: the result does not depend on ctx.threads.
Solution solve_shooting(const Scene& scene, const RadiosityMesh& mesh,
                        const VisibilityQuery& visibility, const Context& ctx,
                        SolveStats* stats = nullptr, const SolveObserver* observer = nullptr);

using penumbra::SensorReading;

/// \brief Irradiance at each sensor, gathered at the point itself from the sources (direct)
///        and from every element's radiosity (indirect), with analytic form factors and
///        visibility rays.
std::vector<SensorReading> evaluate_sensors(const Scene& scene, const RadiosityMesh& mesh,
                                            const Solution& solution,
                                            const VisibilityQuery& visibility, const Context& ctx);

/// \brief Which sources direct_irradiance_at() gathers from (issue #29's mixed lighting).
struct DirectLightOptions {
    /// Unset: every source; else only those for which it returns true (an emitting element
    /// is the AreaSource of its patch's polygon). Called before the gather, never per point.
    std::function<bool(const LightSource&)> include;
    /// Empty: every point gathers from all emitting elements. Else point i gathers only from
    /// those listed (increasing element indices) in emitter_lists[list_of_point[i]]; point
    /// lights, the sun and the sky as before. A point's value is bitwise the full gather's
    /// when the emitters left out are those its probe rays find wholly hidden (the stream is
    /// drawn only for emitters in its penumbra, in element order).
    std::span<const std::uint32_t> list_of_point;
    std::span<const std::vector<std::uint32_t>> emitter_lists; ///< see list_of_point
};

/// \brief Direct irradiance (W/m²) at each of \p points on a surface facing \p normals (unit),
///        gathered as the sensors gather it: analytic form factors to the emitting elements
///        of \p sources (any mesh of the scene's surfaces: the one before hierarchical
///        refinement has the fewest, and the cost grows with them), point lights, the sun and
///        the sky (the vertices' sky quadrature), with \p visibility's rays leaving one ray
///        offset above the point. Each point draws from a stream named by its coordinates and
///        normal (RngPurpose::texel_visibility): a point's value depends neither on the thread
///        count nor on the other points. Parallel in an arena from \p ctx. For lightmap
///        texels (issue #29). \p options may leave sources out (mixed lighting) or narrow
///        the emitting elements per point (the polygons' lists of emitters they may see).
std::vector<Rgb> direct_irradiance_at(const Scene& scene, const RadiosityMesh& sources,
                                      const VisibilityQuery& visibility,
                                      std::span<const Vec3> points, std::span<const Vec3> normals,
                                      const Context& ctx, const DirectLightOptions& options = {});

} // namespace penumbra::solver
