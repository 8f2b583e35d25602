#include "mesher/mesh_checks.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <gtest/gtest.h>

namespace penumbra::test {

double longest_edge(const RadiosityMesh& mesh) {
    double longest = 0;
    for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k)
            longest = std::max(longest, length(mesh.vertex(t[k]) - mesh.vertex(t[(k + 1) % 3])));
    return longest;
}

double patch_area(const RadiosityMesh& mesh, std::uint32_t patch) {
    double a = 0;
    for (std::size_t e = 0; e < mesh.element_count(); ++e)
        if (mesh.element_patch[e] == patch)
            a += mesh.element_area[e];
    return a;
}

double smallest_angle_deg(const RadiosityMesh& mesh, std::uint32_t patch) {
    double smallest = 180;
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
        if (mesh.element_patch[e] != patch)
            continue;
        const auto& t = mesh.triangles[e];
        for (int k = 0; k < 3; ++k) {
            const Vec3 p = mesh.vertex(t[k]);
            const Vec3 u = normalize(mesh.vertex(t[(k + 1) % 3]) - p);
            const Vec3 v = normalize(mesh.vertex(t[(k + 2) % 3]) - p);
            smallest = std::min(smallest, std::acos(std::clamp(dot(u, v), -1.0, 1.0)) * 180 / k_pi);
        }
    }
    return smallest;
}

std::int32_t find_patch(const RadiosityMesh& mesh, std::uint32_t polygon, bool back) {
    for (std::size_t p = 0; p < mesh.patches.size(); ++p)
        if (mesh.patches[p].polygon == polygon && mesh.patches[p].back == back)
            return std::int32_t(p);
    return -1;
}

void expect_conforming(const RadiosityMesh& mesh, std::uint32_t patch, double boundary_length) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> half_edges;
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
        if (mesh.element_patch[e] != patch)
            continue;
        const auto& t = mesh.triangles[e];
        for (int k = 0; k < 3; ++k)
            ++half_edges[{t[k], t[(k + 1) % 3]}];
    }
    double boundary = 0;
    for (const auto& [edge, count] : half_edges) {
        EXPECT_EQ(count, 1) << "half-edge used twice";
        if (!half_edges.count({edge.second, edge.first}))
            boundary += length(mesh.vertex(edge.first) - mesh.vertex(edge.second));
    }
    EXPECT_NEAR(boundary, boundary_length, 1e-5 * boundary_length);
}

namespace {

double distance_to_line(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 d = normalize(b - a);
    const Vec3 off = (p - a) - d * dot(p - a, d);
    return length(off);
}

double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 d = b - a;
    const double t = std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0);
    return length(p - (a + d * t));
}

} // namespace

bool segment_on_element_edges(const RadiosityMesh& mesh, std::uint32_t patch, const Vec3& a,
                              const Vec3& b, double tol, int samples) {
    std::vector<std::pair<Vec3, Vec3>> edges; // element edges lying on the segment's line
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
        if (mesh.element_patch[e] != patch)
            continue;
        const auto& t = mesh.triangles[e];
        for (int k = 0; k < 3; ++k) {
            const Vec3 p = mesh.vertex(t[k]), q = mesh.vertex(t[(k + 1) % 3]);
            if (distance_to_line(p, a, b) <= tol && distance_to_line(q, a, b) <= tol)
                edges.emplace_back(p, q);
        }
    }
    for (int i = 0; i <= samples; ++i) {
        const Vec3 x = a + (b - a) * (double(i) / samples);
        const bool covered = std::any_of(edges.begin(), edges.end(), [&](const auto& edge) {
            return distance_to_segment(x, edge.first, edge.second) <= tol;
        });
        if (!covered)
            return false;
    }
    return true;
}

bool element_straddles(const RadiosityMesh& mesh, std::uint32_t patch, const Vec3& a, const Vec3& b,
                       double tol) {
    const Vec3 n = mesh.patches[patch].normal;
    const Vec3 side = normalize(cross(n, b - a));
    const Vec3 d = normalize(b - a);
    const double len = length(b - a);
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
        if (mesh.element_patch[e] != patch)
            continue;
        double lo = 1e300, hi = -1e300, along_lo = 1e300, along_hi = -1e300;
        for (std::uint32_t v : mesh.triangles[e]) {
            const Vec3 p = mesh.vertex(v);
            lo = std::min(lo, dot(p - a, side));
            hi = std::max(hi, dot(p - a, side));
            along_lo = std::min(along_lo, dot(p - a, d));
            along_hi = std::max(along_hi, dot(p - a, d));
        }
        if (lo < -tol && hi > tol && along_hi > tol && along_lo < len - tol)
            return true;
    }
    return false;
}

} // namespace penumbra::test
