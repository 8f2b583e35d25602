#pragma once
// Bounded memory (issue #32): the most a run may use, and the check each stage makes of its
// estimate before it allocates in bulk. A scene or flag that asks for more than the machine
// has (an element size of a micrometre, solver.epsilon 1e-12) ends in one line that names the
// setting to change, not in minutes of swapping or the kernel's OOM killer. docs/memory.md
// lists the bytes each stage counts per element, node, link, texel and matrix entry.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "core/context.h"
#include "core/image.h"
#include "core/mesh.h"

namespace penumbra {

/// The default limit is this fraction of available_memory_bytes(): room for the process's
/// fixed part (libraries, Embree's BVH, the allocator's slack) that the estimates leave out.
inline constexpr double k_default_memory_fraction = 0.8;

namespace memory_detail {
template <typename Vector> constexpr std::size_t item = sizeof(typename Vector::value_type);
} // namespace memory_detail

/// Vertices a mesh has per element, counted high: Delaunay refinement gives about one per
/// two elements (0.51 on the Cornell box), patch borders and two-sided surfaces add some.
inline constexpr std::size_t k_vertices_per_element = 1;

/// Bytes of a RadiosityMesh and its Solution per element: the per-element arrays, and the
/// per-vertex ones at k_vertices_per_element.
inline constexpr std::size_t k_mesh_bytes_per_element = [] {
    using namespace memory_detail;
    using M = RadiosityMesh;
    using S = Solution;
    const std::size_t element =
        item<decltype(M::triangles)> + item<decltype(M::element_patch)> +
        item<decltype(M::element_twin)> + item<decltype(M::element_area)> +
        item<decltype(M::element_level)> + item<decltype(M::geometry_elements)> +
        item<decltype(S::radiosity)> + item<decltype(S::irradiance_direct)> +
        item<decltype(S::irradiance_indirect)>;
    const std::size_t vertex = item<decltype(M::positions)> + item<decltype(M::vertex_patch)> +
                               item<decltype(S::vertex_radiosity)> +
                               item<decltype(S::vertex_irradiance_direct)> +
                               item<decltype(S::vertex_irradiance_indirect)>;
    return element + k_vertices_per_element * vertex;
}();

/// Bytes the mesher's triangulations hold per element while the mesh is assembled from
/// them (CGAL's faces and vertices; measured: the peak RSS of meshing the Cornell box with
/// 0.37 M and 1.4 M elements grew by 92 bytes per element, k_mesh_bytes_per_element of it
/// the mesh).
inline constexpr std::size_t k_triangulation_bytes_per_element = 64;

/// Bytes per pixel of a render: the final gather's first samples of every pixel, kept for
/// edge refinement (two RGB sums in double and the seen part's least and greatest RGB:
/// raytrace's FirstSamples, which asserts it), the image, and the written file's copy (EXR
/// halves, PNG bytes) counted as one more image.
inline constexpr std::size_t k_render_bytes_per_pixel =
    2 * sizeof(RgbD) + 2 * sizeof(Rgb) + 2 * memory_detail::item<decltype(Image::pixels)>;

/// \brief Physical memory, or the cgroup's limit where lower (cgroup v2 memory.max, v1
///        memory.limit_in_bytes, of this process's cgroup or the namespace's root).
std::uint64_t available_memory_bytes();

/// \brief k_default_memory_fraction of available_memory_bytes().
std::uint64_t default_memory_limit_bytes();

/// \brief A size as `--max-memory` takes it: a number with an optional unit K, M, G or T
///        (powers of 1024; "B", "iB" may follow, any case), e.g. "4G", "500M", "1.5GiB",
///        "1048576"; 0 (no limit). Nothing for anything else: negative, a fraction of a
///        byte, over 4 EiB.
std::optional<std::uint64_t> parse_memory_size(std::string_view text);

/// \brief \p bytes in the largest binary unit that keeps it at least 1: "1.5 GiB", "200 MiB".
std::string format_bytes(double bytes);

/// \brief Throws ConfigError when \p estimate_bytes exceeds \p limit_bytes (0 = no limit):
///        "{what} needs about {estimate}, over the memory limit of {limit} (--max-memory):
///        {advice}, or raise --max-memory". \p what names the stage and its size.
void check_memory(std::uint64_t limit_bytes, std::string_view what, double estimate_bytes,
                  std::string_view advice);

/// \brief check_memory with the context's limit (Context::max_memory_bytes).
inline void check_memory(const Context& ctx, std::string_view what, double estimate_bytes,
                         std::string_view advice) {
    check_memory(ctx.max_memory_bytes, what, estimate_bytes, advice);
}

} // namespace penumbra
