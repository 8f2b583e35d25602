#include "hierarchy/hierarchy.h"

#include <algorithm>

namespace penumbra::solver {

Hierarchy::Hierarchy(const RadiosityMesh& mesh) {
    const std::size_t n = mesh.element_count();
    root_count = n;
    diagonal = mesh.scene_diagonal;
    for (std::size_t e = 0; e < n; ++e) {
        const auto& t = mesh.triangles[e];
        const Patch& p = mesh.patch_of(std::uint32_t(e));
        triangle.push_back({mesh.vertex(t[0]), mesh.vertex(t[1]), mesh.vertex(t[2])});
        normal.push_back(p.normal);
        area.push_back(mesh.element_area[e]);
        patch.push_back(mesh.element_patch[e]);
        parent.push_back(-1);
        first_child.push_back(-1);
        level.push_back(0);
        emission.push_back(p.emission);
        reflectance.push_back(p.reflectance);
        transmittance.push_back(p.diffuse_transmittance);
        twin.push_back(mesh.element_twin[e]);
        opaque.push_back(p.opaque() ? 1 : 0);
        specular_only.push_back(p.specular_only ? 1 : 0);
    }
}

void Hierarchy::subdivide(std::uint32_t n) {
    if (first_child[n] >= 0)
        return;
    // Midpoints as (a + b) · 0.5 with the operands in vertex order of the parent: the same
    // point computed from a neighbour is bitwise identical (addition commutes exactly), which
    // the leaf mesh relies on to find shared vertices.
    const auto t = triangle[n];
    auto mid = [](const Vec3& a, const Vec3& b) { return (a + b) * 0.5; };
    const Vec3 m01 = mid(t[0], t[1]), m12 = mid(t[1], t[2]), m20 = mid(t[2], t[0]);
    const std::array<std::array<Vec3, 3>, 4> kids{
        {{t[0], m01, m20}, {m01, t[1], m12}, {m20, m12, t[2]}, {m12, m20, m01}}};
    first_child[n] = std::int32_t(size());
    for (const auto& k : kids) {
        triangle.push_back(k);
        normal.push_back(normal[n]);
        area.push_back(area[n] * 0.25);
        patch.push_back(patch[n]);
        parent.push_back(std::int32_t(n));
        first_child.push_back(-1);
        level.push_back(level[n] + 1);
        emission.push_back(emission[n]);
        reflectance.push_back(reflectance[n]);
        transmittance.push_back(transmittance[n]);
        twin.push_back(-1); // paired by LinkSet::subdivide, which splits the twin too
        opaque.push_back(opaque[n]);
        specular_only.push_back(specular_only[n]);
    }
}

bool Hierarchy::any_transmittance() const {
    return std::any_of(transmittance.begin(), transmittance.end(),
                       [](const Rgb& t) { return !t.is_black(); });
}

std::vector<std::uint32_t> Hierarchy::root_of_nodes() const {
    std::vector<std::uint32_t> root(size());
    for (std::size_t n = 0; n < size(); ++n) // parents precede their children
        root[n] = parent[n] < 0 ? std::uint32_t(n) : root[std::size_t(parent[n])];
    return root;
}

std::vector<std::uint32_t> Hierarchy::leaves() const {
    std::vector<std::uint32_t> out, stack;
    for (std::size_t r = root_count; r-- > 0;)
        stack.push_back(std::uint32_t(r));
    while (!stack.empty()) {
        std::uint32_t n = stack.back();
        stack.pop_back();
        if (is_leaf(n)) {
            out.push_back(n);
            continue;
        }
        for (int c = 3; c >= 0; --c)
            stack.push_back(std::uint32_t(first_child[n] + c));
    }
    return out;
}

double Hierarchy::size_of(std::uint32_t n) const {
    const auto& t = triangle[n];
    return std::max({length(t[1] - t[0]), length(t[2] - t[1]), length(t[0] - t[2])});
}

} // namespace penumbra::solver
