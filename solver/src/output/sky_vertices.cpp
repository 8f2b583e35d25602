// The sky at the leaf mesh's vertices, from the roots' vertices.

#include "output/sky_vertices.h"

#include <algorithm>
#include <array>

#include "core/parallel.h"
#include "output/vertex_values.h"
#include "sources/sky_light.h"

namespace penumbra::solver {

namespace {

/// Barycentric weights of \p p (in the triangle's plane) in the triangle \p t, clamped into it.
std::array<double, 3> barycentric(const std::array<Vec3, 3>& t, const Vec3& p) {
    const Vec3 n = cross(t[1] - t[0], t[2] - t[0]);
    const double area2 = dot(n, n);
    if (!(area2 > 0))
        return {1.0, 0.0, 0.0};
    std::array<double, 3> w{};
    for (int i = 0; i < 3; ++i) {
        const Vec3& a = t[std::size_t((i + 1) % 3)];
        const Vec3& b = t[std::size_t((i + 2) % 3)];
        w[std::size_t(i)] = std::max(0.0, dot(cross(b - a, p - a), n) / area2);
    }
    const double sum = w[0] + w[1] + w[2];
    for (double& x : w)
        x /= sum;
    return w;
}

std::vector<Rgb> sky_at_root_vertices(const Sky& sky, const RadiosityMesh& roots,
                                      const ElementGeometry& geo, const VisibilityQuery& visibility,
                                      std::uint64_t seed) {
    const std::vector<Vec3> at = vertex_gather_positions(roots, geo.offset);
    std::vector<Rgb> out(roots.vertex_count());
    parallel_for_index(out.size(), 16, [&](std::size_t v) {
        const Vec3& n = roots.patches[roots.vertex_patch[v]].normal;
        Pcg32 rng = Pcg32::for_stream(RngPurpose::sky_visibility, v, 3,
                                      std::uint64_t(RngPurpose::vertex_visibility), seed);
        const RgbD e = sky_point_irradiance(sky, at[v] + n * geo.offset, n, geo.diagonal,
                                            visibility, k_sky_vertex_quadrature, rng);
        out[v] = Rgb(float(e.r), float(e.g), float(e.b));
    });
    return out;
}

} // namespace

std::vector<Rgb> sky_at_vertices(const Sky& sky, const RadiosityMesh& roots,
                                 const ElementGeometry& root_geo, const RadiosityMesh& leaves,
                                 std::span<const std::uint32_t> leaf_root,
                                 const VisibilityQuery& visibility, std::uint64_t seed) {
    const std::vector<Rgb> at_roots = sky_at_root_vertices(sky, roots, root_geo, visibility, seed);
    if (&leaves == &roots)
        return at_roots;
    // A leaf vertex lies in the root of any of its elements (on a shared edge, both roots
    // interpolate the same two root vertices).
    std::vector<std::uint32_t> root_of(leaves.vertex_count(), 0);
    for (std::size_t e = 0; e < leaves.element_count(); ++e)
        for (std::uint32_t v : leaves.triangles[e])
            root_of[v] = leaf_root[e];
    std::vector<Rgb> out(leaves.vertex_count());
    parallel_for_index(out.size(), 256, [&](std::size_t v) {
        const auto& corners = roots.triangles[root_of[v]];
        const std::array<Vec3, 3> t = {roots.vertex(corners[0]), roots.vertex(corners[1]),
                                       roots.vertex(corners[2])};
        const std::array<double, 3> w = barycentric(t, leaves.vertex(std::uint32_t(v)));
        RgbD sum;
        for (int i = 0; i < 3; ++i)
            sum += RgbD(at_roots[corners[std::size_t(i)]]) * w[std::size_t(i)];
        out[v] = Rgb(float(sum.r), float(sum.g), float(sum.b));
    });
    return out;
}

} // namespace penumbra::solver
