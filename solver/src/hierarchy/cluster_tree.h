#pragma once
// Volume clusters over the roots of the element hierarchy (Smits, Arvo & Greenberg 1994;
// Sillion 1995): a binary tree of bounding boxes whose leaves hold a few root elements, so
// that distant groups of surfaces exchange light through one link and the number of links
// grows about linearly with the number of input polygons.
//
// A cluster's light leaves and arrives through six axis lobes (+x, −x, +y, −y, +z, −z): a
// surface of normal n and exitance B puts B·A·max(0, ±n_a) into lobe ±a, and radiates toward
// the unit direction ω with intensity (1/π) Σ_a |ω_a| lobe[a, sign ω_a]; irradiance arriving
// from direction d is stored in the lobes the same way and read back by each surface with its
// own normal. Both are exact for axis-aligned surfaces (walls, floors, ceilings, furniture
// boxes) and approximate for tilted ones, whose links the refinement oracle splits when the
// transfer matters.

#include <array>
#include <cstdint>
#include <vector>

#include "core/parallel.h"
#include "core/rgb.h"
#include "core/vec.h"
#include "hierarchy/hierarchy.h"

namespace penumbra::solver {

/// A node of hierarchical radiosity: an element (triangle) of the Hierarchy, or a cluster
/// (the top bit set; the rest is the index in the ClusterTree).
using NodeRef = std::uint32_t;
inline constexpr NodeRef k_cluster_bit = 0x80000000u;
constexpr bool is_cluster(NodeRef n) {
    return (n & k_cluster_bit) != 0;
}
constexpr NodeRef cluster_ref(std::uint32_t c) {
    return c | k_cluster_bit;
}
constexpr std::uint32_t cluster_index(NodeRef n) {
    return n & ~k_cluster_bit;
}

/// Values in the six axis lobes, index 2a for +a and 2a + 1 for −a.
using Lobes = std::array<Rgb, 6>;

/// A linear function's gradient over a plane: per world axis, its change per metre.
using Slope = std::array<Rgb, 3>;

/// The change of a function of gradient \p s along \p d.
inline Rgb slope_along(const Slope& s, const Vec3& d) {
    return s[0] * float(d.x) + s[1] * float(d.y) + s[2] * float(d.z);
}

/// \brief The gradient, in the plane of \p frame's s and t axes, of the least-squares linear
///        fit to values at points whose offsets have covariances \p css, \p ctt, \p cst and
///        the values' covariances with them \p bs, \p bt. A ridge keeps points along one line
///        (a strip) from a gradient across it; zero where the points coincide.
inline Vec3 fit_gradient(const Frame& frame, double css, double ctt, double cst, double bs,
                         double bt) {
    const double ridge = 1e-6 * (css + ctt);
    css += ridge;
    ctt += ridge;
    const double det = css * ctt - cst * cst;
    if (!(det > 0))
        return {};
    return frame.s * ((ctt * bs - cst * bt) / det) + frame.t * ((css * bt - cst * bs) / det);
}

/// Index of the lobe along axis \p a that holds direction component \p component.
constexpr int lobe_index(int a, double component) {
    return 2 * a + (component < 0 ? 1 : 0);
}

/// Σ_a |v_a| · lobes[a, sign v_a]: a surface (or cluster) of lobes \p lobes seen along v.
Rgb lobe_projection(const Lobes& lobes, const Vec3& v);

/// Adds value · |d_a| to lobe [a, sign d_a] for each axis.
void lobe_deposit(Lobes& lobes, const Vec3& d, const Rgb& value);

/// The lobes of a surface of normal \p n carrying \p value per unit area over \p area.
Lobes surface_lobes(const Vec3& n, double area, const Rgb& value);

/// \brief Clusters by depth: those of depth d are order[begin[d] .. begin[d + 1]).
struct ClusterLevels {
    std::vector<std::uint32_t> order, begin;
};

struct ClusterTree {
    std::vector<Vec3> lo, hi;         ///< bounds of the elements' vertices
    std::vector<double> area;         ///< summed area of the elements
    std::vector<Vec3> centroid;       ///< area-weighted centroid of the elements
    std::vector<std::int32_t> parent; ///< −1 for the top cluster (index 0)
    /// Children of cluster c are children[child_begin[c] .. child_begin[c + 1]): clusters, or
    /// root elements in leaf clusters. Parents precede their children.
    std::vector<std::uint32_t> child_begin;
    std::vector<NodeRef> children;
    /// The cluster's roots are of one planar group (one oriented plane, connected): a face
    /// cluster, which may exchange light through exact links (links/link_store.h) like an element.
    std::vector<std::uint8_t> planar;
    std::vector<Vec3> normal; ///< of a planar cluster's plane (zero for the others)
    ClusterLevels levels;     ///< for the passes over the tree (for_each_cluster_by_level)

    std::size_t size() const { return area.size(); }
    Vec3 centre(std::uint32_t c) const { return (lo[c] + hi[c]) * 0.5; }
    double radius(std::uint32_t c) const { return 0.5 * length(hi[c] - lo[c]); }
};

/// \brief Clusters over the roots of \p h, face clusters below volume clusters: roots of one
///        plane connected through shared vertices form planar groups, cut into items of at
///        most 32 roots; median splits along the longest axis of the centroids' bounds divide
///        sets of whole items, then each item's roots, until a cluster holds at most
///        \p leaf_size roots. Deterministic.
ClusterTree build_cluster_tree(const Hierarchy& h, std::size_t leaf_size = 8);

/// \brief Calls \p fn(c) for every cluster, children before their parents (\p up) or
///        parents before their children: in parallel over the clusters of each depth, which
///        read only their children's (their parent's) results. The passes over the whole tree
///        each sweep made were a third of the sweeps' time, on one core.
template <typename Fn> void for_each_cluster_by_level(const ClusterTree& tree, bool up, Fn&& fn) {
    const ClusterLevels& levels = tree.levels;
    const std::size_t depths = levels.begin.size() - 1;
    for (std::size_t i = 0; i < depths; ++i) {
        const std::size_t d = up ? depths - 1 - i : i;
        const std::uint32_t first = levels.begin[d];
        parallel_for_index(levels.begin[d + 1] - first, 64,
                           [&](std::size_t k) { fn(levels.order[first + k]); });
    }
}

/// \brief Per cluster, the summed lobes of its roots, root r carrying \p value[r] per unit
///        area (its radiosity for exitance lobes, 1 for area lobes). \p out is resized.
void pull_lobes(const ClusterTree& tree, const Hierarchy& h, const std::vector<Rgb>& value,
                std::vector<Lobes>& out);

/// \brief Per face cluster, the gradient of the least-squares linear fit, over its plane, of
///        the values \p value[r] of its roots (at their centroids, weighted by area): the
///        first-order part of how its radiosity varies. Zero for volume clusters. \p out is
///        resized. \p departure (optional, resized): per face cluster, twice the largest
///        departure of a root's value from the fit (largest channel), 0 for the others.
void planar_gradients(const ClusterTree& tree, const Hierarchy& h, const std::vector<Rgb>& value,
                      std::vector<Slope>& out, std::vector<float>* departure = nullptr);

} // namespace penumbra::solver
