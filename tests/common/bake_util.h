#pragma once
// Helpers of the end-to-end suites that run the whole pipeline (validation_tests).

#include <vector>

#include "app/pipeline.h"
#include "core/scene.h"

namespace penumbra::test {

/// \brief Bakes \p scene without the camera render, quietly, on \p threads (0 = all), from
///        \p reuse when given (a hierarchical re-solve).
app::BakeResult bake(const Scene& scene, int threads = 0,
                     const solver::HierarchicalState* reuse = nullptr);

/// The bundled Cornell box without its sensors, meshed with elements of \p max_edge metres.
Scene cornell_box(double max_edge);

/// Σ A |b − ref| / Σ A ref over the elements (summed over the channels).
double relative_l1(const std::vector<Rgb>& b, const std::vector<Rgb>& ref,
                   const std::vector<double>& area);

} // namespace penumbra::test
