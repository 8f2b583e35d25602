#pragma once
// Private to penumbra_pipeline: the annual metrics on every leaf element of the coefficients'
// system (`penumbra annual --mesh`, issue #31).

#include <vector>

#include "annual/metrics.h"
#include "annual/sky_matrix.h"
#include "app/annual.h"
#include "core/context.h"
#include "solver/daylight_coefficients.h"

namespace penumbra::app {

/// \brief Each element's year from \p coefficients and \p matrix (the sky through the patches,
///        the sun, direct and reflected, through the bin of each hour's sun in \p suns) and
///        its metrics over \p occupied. Hours are made a block of elements at a time: the
///        memory is the coefficients' and a few blocks × hours floats.
MeshMetrics mesh_metrics(const solver::ElementCoefficients& coefficients,
                         const annual::SkyMatrix& matrix, const SunBins& suns,
                         const std::vector<bool>& occupied,
                         const annual::MetricThresholds& thresholds, const Context& ctx);

} // namespace penumbra::app
