#pragma once
// The element hierarchy of hierarchical radiosity: every mesh triangle is the root of a
// 1-to-4 midpoint subdivision tree. Stored flat (SoA); children of a node are contiguous.

#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh.h"

namespace penumbra::solver {

struct Hierarchy {
    std::vector<std::array<Vec3, 3>> triangle;
    std::vector<Vec3> normal;
    std::vector<double> area;
    std::vector<std::uint32_t> patch;
    std::vector<std::int32_t> parent;      ///< -1 for roots
    std::vector<std::int32_t> first_child; ///< -1 for leaves; children are first_child + 0..3
    std::vector<std::int32_t> level;
    std::vector<Rgb> emission, reflectance;
    /// Diffuse transmittance τ (Patch::diffuse_transmittance): a leaf's radiosity gains τ
    /// times its twin's irradiance.
    std::vector<Rgb> transmittance;
    /// The other side's node of a two-sided surface, -1 if one-sided. Refinement subdivides
    /// twins together (LinkSet), so the children of twins are twins.
    std::vector<std::int32_t> twin;
    std::vector<std::uint8_t> opaque; ///< 1 where the surface blocks all light (Patch::opaque)
    /// 1 where the surface is specular only (Patch::specular_only): its links are refined
    /// less (oracle::receiver_settings).
    std::vector<std::uint8_t> specular_only;
    std::size_t root_count = 0;
    double diagonal = 0;

    Hierarchy() = default;
    /// Roots = the mesh's elements, in element order.
    explicit Hierarchy(const RadiosityMesh& mesh);
    std::size_t size() const { return area.size(); }
    bool is_leaf(std::uint32_t n) const { return first_child[n] < 0; }
    /// Whether any node passes light to its twin (a diffusely transmitting material).
    bool any_transmittance() const;
    /// Creates the four children of leaf \p n (midpoint subdivision); no-op if it has them.
    void subdivide(std::uint32_t n);
    /// All leaves in depth-first order of the roots (deterministic).
    std::vector<std::uint32_t> leaves() const;
    /// The root above every node (its own index for a root).
    std::vector<std::uint32_t> root_of_nodes() const;
    /// Longest edge of node \p n.
    double size_of(std::uint32_t n) const;
    Vec3 centroid(std::uint32_t n) const {
        return (triangle[n][0] + triangle[n][1] + triangle[n][2]) / 3.0;
    }
};

} // namespace penumbra::solver
