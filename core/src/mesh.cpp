#include "core/mesh.h"

#include <cmath>

namespace penumbra {

Vec3 RadiosityMesh::centroid(std::uint32_t e) const {
    const auto& t = triangles[e];
    return (vertex(t[0]) + vertex(t[1]) + vertex(t[2])) / 3.0;
}

std::optional<Rgb> interpolate_at(const RadiosityMesh& mesh, const std::vector<Rgb>& values,
                                  const Vec3& point, const Vec3& normal, double tolerance) {
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
        const Patch& patch = mesh.patch_of(std::uint32_t(e));
        if (dot(patch.normal, normal) < 1.0 - 1e-3)
            continue;
        const auto& t = mesh.triangles[e];
        Vec3 a = mesh.vertex(t[0]), b = mesh.vertex(t[1]), c = mesh.vertex(t[2]);
        if (std::abs(dot(point - a, patch.normal)) > tolerance)
            continue;
        // Barycentrics in the patch plane; accept points on edges (small negative slack).
        Vec3 n = cross(b - a, c - a);
        double area2 = dot(n, n);
        if (area2 <= 0)
            continue;
        double w1 = dot(cross(point - a, c - a), n) / area2;
        double w2 = dot(cross(b - a, point - a), n) / area2;
        double w0 = 1.0 - w1 - w2;
        const double slack = -1e-9;
        if (w0 < slack || w1 < slack || w2 < slack)
            continue;
        return values[t[0]] * float(w0) + values[t[1]] * float(w1) + values[t[2]] * float(w2);
    }
    return std::nullopt;
}

} // namespace penumbra
