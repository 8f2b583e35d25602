#pragma once
// A hierarchical radiosity system built once and solved for many source terms. Building
// refines the links for a set of sources (refine → solve cycles, hierarchical_system.cpp);
// solving iterates on those fixed links for other emissions and light links, without
// refinement: daylight coefficients take one solve per sky patch on links refined for all.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/context.h"
#include "core/mesh.h"
#include "core/scene.h"
#include "core/visibility.h"
#include "hierarchy/hierarchy.h"
#include "iteration/transport.h"
#include "links/link_set.h"
#include "links/link_store.h"
#include "solver/solver.h"

namespace penumbra::solver {

/// \brief The hierarchy, links, leaf weights and clusters of a built system, and the node
///        values of its last solve. Its cluster tables refer to its hierarchy and clusters:
///        it does not move. solve_hierarchical's output stage takes it apart (its tables are
///        freed, its links and hierarchy move into the saved state).
struct HierarchicalSystem {
    /// The roots of \p mesh (or \p reuse's saved hierarchy, with the scene's materials) and
    /// no links yet.
    HierarchicalSystem(const Scene& scene, const RadiosityMesh& mesh, const Context& ctx,
                       const HierarchicalState* reuse);
    HierarchicalSystem(const HierarchicalSystem&) = delete;
    HierarchicalSystem& operator=(const HierarchicalSystem&) = delete;

    Hierarchy h;
    RefineSettings settings;
    LinkStore links;
    /// The cluster tree, its values and tables, when clustering.
    Clusters clusters;
    /// Radiosities and irradiances per node of the last solve, and the leaf weights of the
    /// links.
    NodeValues values;
    Iteration iteration = Iteration::jacobi;
    /// Whether values hold the radiosities of a solve with the scene's materials (the leaf
    /// weights' reflected part is weighed by them).
    bool solved = false;
    /// W, largest channel: the power of the sources solved last, what the residual is
    /// relative to.
    double emitted = 0;
    /// The specular transfers traced during the build (SpecularLight::trace_transfers), which
    /// NodeValues::specular_transfers then views.
    std::vector<SpecularLight::Transfer> traced_transfers;

    /// What the sun's and the sky's links deliver (W per channel): their power in the balance.
    RgbD distant_power() const { return links.distant_power(h); }
    /// What the roots' specular light (NodeValues::specular) delivers, W per channel.
    RgbD specular_power() const;
};

/// \brief Throws ConfigError unless \p state was saved by a solve of \p mesh's geometry.
void check_reusable(const RadiosityMesh& mesh, const HierarchicalState& state);

/// \brief Source terms on a system's fixed links.
struct SourceTerms {
    std::vector<Rgb> emission;          ///< per root (element of the input mesh), W/m²
    std::vector<LightLink> light_links; ///< of point lights and the sun, to the system's nodes
};

/// \brief Builds the system for the scene's sources: links the roots (or takes \p reuse's
///        saved links, re-running the oracle on them), then refines and solves in turn
///        until refinement settles. The system's values are then the scene's solution.
///        \p progress moves over the cycles; sweeps are reported to \p log. \p specular
///        (or null): light that reaches the elements of \p mesh through specular surfaces
///        (NodeValues::specular).
std::unique_ptr<HierarchicalSystem>
build_hierarchical(const Scene& scene, const RadiosityMesh& mesh, const VisibilityQuery& visibility,
                   const Context& ctx, ProgressStage& progress, SweepLog& log,
                   const HierarchicalState* reuse, const SpecularLight* specular = nullptr);

/// \brief The source terms \p system is solved for now (after a build: the scene's).
SourceTerms current_sources(const HierarchicalSystem& system);

/// \brief Solves \p system for \p sources on its fixed links (no refinement): the nodes
///        take their roots' emission, the iteration starts from it and runs to
///        settings.residual of the sources' power (Σ E A and what the light links deliver).
///        Two solves for the same sources give the same values, bit for bit.
Solved solve_sources(HierarchicalSystem& system, const SourceTerms& sources,
                     const SolverSettings& settings, SweepLog& log);

} // namespace penumbra::solver
