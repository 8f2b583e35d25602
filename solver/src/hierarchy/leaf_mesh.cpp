#include "hierarchy/leaf_mesh.h"

#include <numeric>

#include <bit>
#include <map>

namespace penumbra::solver {

namespace {

using Key = std::array<std::uint64_t, 3>;

Key key_of(const Vec3& p) {
    return {std::bit_cast<std::uint64_t>(p.x), std::bit_cast<std::uint64_t>(p.y),
            std::bit_cast<std::uint64_t>(p.z)};
}

// Vertices of one patch by exact position. Midpoints are computed bitwise identically from
// either side (hierarchy/hierarchy.cpp), so a shared or hanging vertex is found by its position.
class PatchVertices {
public:
    std::uint32_t get(const Vec3& p, std::uint32_t patch, RadiosityMesh& mesh) {
        auto [it, inserted] = index_.try_emplace(key_of(p), std::uint32_t(mesh.positions.size()));
        if (inserted) {
            mesh.positions.push_back(Vec3f(p));
            mesh.vertex_patch.push_back(patch);
        }
        return it->second;
    }
    bool has(const Vec3& p) const { return index_.count(key_of(p)) != 0; }

private:
    std::map<Key, std::uint32_t> index_;
};

// Points strictly inside edge a→b that are vertices of the patch (recursive midpoints).
void hanging_points(const PatchVertices& verts, const Vec3& a, const Vec3& b, int depth,
                    std::vector<Vec3>& out) {
    if (depth > 40)
        return;
    const Vec3 m = (a + b) * 0.5;
    if (!verts.has(m))
        return;
    hanging_points(verts, a, m, depth + 1, out);
    out.push_back(m);
    hanging_points(verts, m, b, depth + 1, out);
}

// The leaf's outline with its hanging vertices, counter-clockwise.
std::vector<Vec3> leaf_outline(const PatchVertices& verts, const std::array<Vec3, 3>& t) {
    std::vector<Vec3> poly;
    for (int k = 0; k < 3; ++k) {
        poly.push_back(t[std::size_t(k)]);
        hanging_points(verts, t[std::size_t(k)], t[std::size_t((k + 1) % 3)], 0, poly);
    }
    return poly;
}

double tri_area(const Vec3& a, const Vec3& b, const Vec3& c) {
    return 0.5 * length(cross(b - a, c - a));
}

} // namespace

LeafMesh build_leaf_mesh(const RadiosityMesh& base, const Hierarchy& h) {
    const std::vector<std::int32_t>& twin = h.twin;
    LeafMesh out;
    RadiosityMesh& m = out.mesh;
    m.patches = base.patches;
    m.scene_diagonal = base.scene_diagonal;
    m.discontinuities = base.discontinuities;
    const std::vector<std::uint32_t> leaves = h.leaves();
    std::vector<PatchVertices> verts(base.patches.size());
    for (std::uint32_t n : leaves)
        for (const Vec3& p : h.triangle[n])
            verts[h.patch[n]].get(p, h.patch[n], m);
    auto emit = [&](std::uint32_t node, const Vec3& a, const Vec3& b, const Vec3& c) {
        const std::uint32_t patch = h.patch[node];
        m.triangles.push_back({verts[patch].get(a, patch, m), verts[patch].get(b, patch, m),
                               verts[patch].get(c, patch, m)});
        m.element_patch.push_back(patch);
        m.element_twin.push_back(-1);
        m.element_area.push_back(tri_area(a, b, c));
        m.element_level.push_back(h.level[node]);
        out.element_node.push_back(node);
    };
    for (std::uint32_t n : leaves) {
        if (base.patches[h.patch[n]].back)
            continue; // emitted with its front twin below
        const std::vector<Vec3> poly = leaf_outline(verts[h.patch[n]], h.triangle[n]);
        const Vec3 centre = (h.triangle[n][0] + h.triangle[n][1] + h.triangle[n][2]) / 3.0;
        const std::size_t count = poly.size() == 3 ? 1 : poly.size();
        for (std::size_t k = 0; k < count; ++k) {
            const std::size_t front = m.triangles.size();
            const Vec3& a = poly.size() == 3 ? poly[0] : centre;
            const Vec3& b = poly.size() == 3 ? poly[1] : poly[k];
            const Vec3& c = poly.size() == 3 ? poly[2] : poly[(k + 1) % poly.size()];
            emit(n, a, b, c);
            m.geometry_elements.push_back(std::uint32_t(front));
            if (twin[n] >= 0) {
                emit(std::uint32_t(twin[n]), a, c, b);
                m.element_twin[front] = std::int32_t(front + 1);
                m.element_twin[front + 1] = std::int32_t(front);
            }
        }
    }
    return out;
}

LeafMesh leaf_elements(const RadiosityMesh& base, const Hierarchy& h) {
    if (h.size() > h.root_count) {
        LeafMesh leaf = build_leaf_mesh(base, h);
        leaf.subdivided = true;
        return leaf;
    }
    LeafMesh leaf;
    leaf.element_node.resize(h.root_count);
    std::iota(leaf.element_node.begin(), leaf.element_node.end(), 0u);
    return leaf;
}

} // namespace penumbra::solver
