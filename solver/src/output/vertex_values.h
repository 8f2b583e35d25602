#pragma once

#include <span>

#include "core/context.h"
#include "core/mesh.h"
#include "core/scene.h"
#include "core/visibility.h"
#include "kernels/element_rows.h"
#include "output/point_gather.h"

namespace penumbra::solver {

/// Element-level results of any solve method.
struct ElementResult {
    std::vector<Rgb> radiosity, h_direct, h_indirect;
};

/// The sources a point can gather direct light from: emitting elements, point lights and
/// the sun.
GatherSources direct_sources(const Scene& scene, const std::vector<Rgb>& element_emission);

/// \brief A cheap snapshot for progress: element values, and vertex values as area-weighted
///        means of the elements around each vertex.
Solution snapshot_solution(const RadiosityMesh& mesh, const ElementResult& result);

/// \brief Where each vertex of \p mesh gathers direct light in make_solution: the vertex
///        itself, or, on its surface's boundary, a point 10 ray offsets (\p ray_offset) inside
///        its elements (at most half way to their centroids): its surface's limit there. A
///        surface meeting it at a contact line would otherwise block its rays and be seen
///        edge-on.
std::vector<Vec3> vertex_gather_positions(const RadiosityMesh& mesh, double ray_offset);

/// Per element, a sorted list of emitting elements (CSR: element e's are
/// roots[first[e], first[e + 1])).
struct EmitterLists {
    std::vector<std::uint32_t> first{0};
    std::vector<std::uint32_t> roots;
    std::span<const std::uint32_t> of(std::size_t e) const {
        return std::span<const std::uint32_t>(roots).subspan(first[e], first[e + 1] - first[e]);
    }
};

/// \brief Packs element results and reconstructs vertex values: direct irradiance gathered at
///        each vertex itself (Wallace et al. 1989's vertex receivers), indirect as the
///        area-weighted mean of the vertex's elements, B = E + ρ H. A vertex on its
///        surface's boundary gathers from a point just inside its elements (its surface's
///        limit there: a surface meeting it at a contact line would block its rays).
/// \p emitters: where the vertices gather direct light from, if not \p mesh's own emitting
/// elements: the same surfaces in fewer elements (hierarchical radiosity passes the roots, so
/// that the rays per vertex do not grow with the emitters' refinement; emission is uniform
/// over a root, and analytic form factors add up over a partition).
/// \p near / \p far (optional, per element of the mesh, hierarchical radiosity): a vertex
/// gathers exactly from the union of its elements' near emitters only (indices into geo, in
/// increasing order), and adds the area-weighted mean of their far direct irradiance: the
/// light of emitters that reach the element through cluster links other than exact ones (a
/// vertex would otherwise
/// gather from every emitter in the scene, which grows with the scene's size squared).
struct DirectEmitters {
    const ElementGeometry& geo;
    GatherSources sources;
    const EmitterLists* near = nullptr;
    const std::vector<Rgb>* far = nullptr;
    /// Per vertex of the mesh, the sky's direct irradiance (sky_at_vertices); sources.sky is
    /// then unset, so that the vertices do not gather the sky themselves.
    const std::vector<Rgb>* sky = nullptr;
};

Solution make_solution(const Scene& scene, const RadiosityMesh& mesh, const ElementGeometry& geo,
                       ElementResult result, const VisibilityQuery& visibility,
                       const RowSettings& settings, const Context& ctx,
                       const DirectEmitters* emitters = nullptr);

} // namespace penumbra::solver
