#pragma once

#include <span>

#include "core/context.h"
#include "core/mesh.h"
#include "core/scene.h"
#include "core/visibility.h"
#include "kernels/element_rows.h"
#include "solver/solver.h"

namespace penumbra::solver {

/// \brief Power balance of a gathered solution: escape estimated per element by its own rays.
///        \p distant_delivered is what the sun's and the sky's direct light brought to the
///        surfaces (Σ E A over their links) and what specular surfaces passed on to them
///        (HierarchicalSystem::specular_power), counted as emitted; none of it escapes.
PowerBalance hierarchical_balance(const Scene& scene, const RadiosityMesh& mesh,
                                  const ElementGeometry& geo, const Solution& solution,
                                  const VisibilityQuery& visibility, const RowSettings& rows,
                                  double unconverged_fraction, const RgbD& distant_delivered);

/// \brief Hierarchical radiosity on the mesh's elements as roots; returns the leaf mesh and
///        its solution. \p specular: solve()'s (null: none).
SolveResult solve_hierarchical(const Scene& scene, const RadiosityMesh& mesh,
                               const VisibilityQuery& visibility, const Context& ctx,
                               SolveStats* stats, const SolveObserver* observer,
                               const HierarchicalState* reuse, const SpecularLight* specular);

} // namespace penumbra::solver
