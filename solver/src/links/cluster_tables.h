#pragma once
// What the cluster links' refinement and gather read besides the links themselves: the
// cluster tree and its exitance lobes, the face clusters' boundaries, the roots in
// depth-first order (to draw points by area or exitance), the occluder planes and the
// clusters' lobe bounds. Built when a clustered system is first linked and freed with the
// clusters, after the last gather (RAII: nothing attaches or detaches it by hand).

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/mesh.h"
#include "hierarchy/cluster_tree.h"
#include "hierarchy/hierarchy.h"
#include "links/link_store.h"
#include "visibility/occluders.h"

namespace penumbra::solver {

/// Normal components below this do not put a surface in an axis lobe's bounds, nor make it
/// face a plane's side (occlusion certificates): it radiates nothing that way to speak of.
inline constexpr double k_lobe_component = 1e-6;

class ClusterTables {
public:
    /// Tables of \p tree over \p h. \p exitance is the clusters' exitance lobes (Σ B A cos)
    /// and \p peak their brightest root's radiosity, read by the oracle at every refinement;
    /// \p emitted is their emitted exitance lobes (Σ E A cos): the oracle holds the direct
    /// light a link brings to a tighter bound than the reflected. All must outlive the tables.
    ClusterTables(const Hierarchy& h, const ClusterTree& tree, const std::vector<Lobes>& exitance,
                  const std::vector<Lobes>& emitted, const std::vector<float>& peak,
                  const std::vector<float>& departure);
    ClusterTables(const ClusterTables&) = delete;
    ClusterTables& operator=(const ClusterTables&) = delete;

    const ClusterTree& tree() const { return *tree_; }
    /// Whether node \p n (an element or a face cluster) emits.
    bool emits(NodeRef n) const;
    /// Whether node \p n (an element or a cluster) is specular only (all its roots are).
    bool specular_only(NodeRef n) const {
        return is_cluster(n) ? specular_only_[cluster_index(n)] != 0 : h_.specular_only[n] != 0;
    }
    /// The roots of cluster \p c.
    std::span<const std::uint32_t> cluster_roots(std::uint32_t c) const {
        return std::span<const std::uint32_t>(dfs_roots_)
            .subspan(root_begin_[c], root_end_[c] - root_begin_[c]);
    }
    /// The mean radiosity of face cluster \p c from its exitance \p lobes.
    Rgb face_mean(std::uint32_t c, const std::vector<Lobes>& lobes) const;
    /// The radiosity an exact link from a face cluster sends: its \p mean (face_mean) plus
    /// its \p gradient (planar_gradients; empty for none) times the link's offset
    /// (ClusterLink::d.y), at least 0. (An element source sends its own radiosity.)
    Rgb exact_source_radiosity(const ClusterLink& link, const Rgb& mean,
                               const std::vector<Slope>& gradient) const;
    /// The gradient (per metre, in its plane) of the form factor of an exact link over its
    /// cluster receiver, which takes F + gradient · (x − centroid); zero for an element.
    Vec3 exact_slope(const ClusterLink& link) const;
    /// The same given the frame of the receiver's plane (Frame::from_normal of its normal).
    static Vec3 exact_slope(const ClusterLink& link, const Frame& frame) {
        return frame.s * double(link.d.z) + frame.t * double(link.slope_t);
    }
    /// The unit direction from an exact link's cluster source's centroid toward its
    /// receiver, in the source's plane (zero where the receiver is nearly straight above):
    /// link.d.y is how far along it the part of the source the receiver sees lies.
    Vec3 exact_source_direction(const ClusterLink& link) const;
    /// The unit direction from face cluster \p from's centroid toward \p toward's, in
    /// from's plane; zero for an element, or where toward is nearly straight above.
    Vec3 planar_direction(NodeRef from, NodeRef toward) const;
    /// Area centroid of a node.
    Vec3 node_centroid(NodeRef n) const;
    /// Rebuilds the running sum source ends are drawn by from the roots' radiosities \p b.
    void weigh_sources(const std::vector<Rgb>& b);

    struct Plane {
        Vec3 n;
        double d = 0; ///< n · (a point of the plane)
    };
    /// An edge of a face cluster's boundary: from corner \p from to corner \p to of a root.
    struct BoundaryEdge {
        std::uint32_t root = 0;
        std::uint8_t from = 0, to = 0;
    };
    /// A straight run of a face cluster's boundary edges: from corner \p from of root
    /// \p from_root to corner \p to of root \p to_root. Collinear edges in a row add up to
    /// the one edge in the contour sum (their terms share the plane through the point).
    struct ContourEdge {
        std::uint32_t from_root = 0, to_root = 0;
        std::uint8_t from = 0, to = 0;
    };

private:
    friend class LinkSet; // the cluster and exact links' refinement reads the tables

    /// The face clusters' boundaries (boundary_) and which are exact sources.
    void build_boundaries();
    /// Appends the boundary \p edges of a face cluster to \p out, collinear edges in a row
    /// as one.
    void merge_collinear(const std::vector<BoundaryEdge>& edges,
                         std::vector<ContourEdge>& out) const;

    const Hierarchy& h_;
    const ClusterTree* tree_ = nullptr;
    const std::vector<Lobes>* exitance_ = nullptr;
    const std::vector<Lobes>* emitted_ = nullptr;
    const std::vector<float>* peak_ = nullptr;
    const std::vector<float>* departure_ = nullptr; ///< ClusterValues::departure
    /// Per face cluster c, its boundary boundary_[boundary_begin_[c], boundary_begin_[c + 1]).
    std::vector<ContourEdge> boundary_;
    std::vector<std::uint32_t> boundary_begin_;
    std::vector<std::uint8_t> exact_source_;  ///< per cluster (LinkSet::exact_source)
    std::vector<std::uint8_t> specular_only_; ///< per cluster: all its roots are
    std::vector<Lobes> area_lobes_;           ///< per cluster: Σ A max(0, ±n_a)
    /// The roots in depth-first order of the cluster tree, where every cluster is a range
    /// [root_begin_[c], root_end_[c]), and the running sum of their areas (one longer): a
    /// root is drawn by area with one binary search.
    std::vector<std::uint32_t> dfs_roots_, root_begin_, root_end_;
    std::vector<double> dfs_area_;
    /// The same running sum of area × radiosity (with a floor): source ends are drawn by it.
    std::vector<double> dfs_exitance_;
    std::vector<Plane> dfs_plane_; ///< of each root in dfs_roots_, for the facing test
    OccluderPlanes occluders_;
    /// Per cluster and axis lobe (lobe_index), the bounds of its roots with a normal component
    /// in that lobe (lo xyz, hi xyz, rounded outward; empty where lo > hi): which part of a
    /// cluster faces a plane's side.
    std::vector<std::array<std::array<float, 6>, 6>> lobe_bounds_;
};

} // namespace penumbra::solver
