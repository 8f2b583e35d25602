#pragma once
// Helpers of the end-to-end suites that run the whole pipeline (validation_tests).

#include <cstdint>
#include <optional>
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

/// \brief Σ over the patches of A |B̄ − B̄_ref| / Σ A B̄_ref, B̄ a patch's area-weighted mean
///        radiosity (summed over the channels): two solves on different leaf meshes compare
///        patch by patch. Patches of material \p skip_material (if any) are left out; 1 if
///        \p r lacks a patch of \p ref.
double relative_patch_l1(const app::BakeResult& r, const app::BakeResult& ref,
                         std::optional<std::uint32_t> skip_material = {});

/// Σ A |b − ref| / Σ A ref over the elements (summed over the channels).
double relative_l1(const std::vector<Rgb>& b, const std::vector<Rgb>& ref,
                   const std::vector<double>& area);

} // namespace penumbra::test
