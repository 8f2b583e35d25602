#pragma once
// The making and refinement of the links of hierarchical radiosity (Hanrahan, Salzman &
// Aupperle 1991): element links between elements, light links from point lights and the
// sun, cluster links and exact links (links/cluster_links.cpp, links/exact_links.cpp), split
// where the refinement oracle (oracle/oracle.h) says so. The links live in a LinkStore.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <span>
#include <utility>
#include <vector>

#include "core/rng.h"
#include "core/scene.h"
#include "core/visibility.h"
#include "hierarchy/cluster_tree.h"
#include "hierarchy/hierarchy.h"
#include "kernels/element_rows.h"
#include "links/cluster_tables.h"
#include "links/link_store.h"
#include "memory/memory_use.h"
#include "oracle/oracle.h"

namespace penumbra::solver {

/// The oracle's settings, and how form factors and visibility are computed.
struct RefineSettings : OracleSettings {
    RowSettings rows;
    double offset = 0;
    /// The memory limit the system's nodes and links are checked against before each pass
    /// makes its links (memory/memory_use.h), bytes; 0 = no limit.
    std::uint64_t max_memory_bytes = 0;
};

/// What refine() reports after each of its passes (a pass refines every link once).
struct RefinePass {
    const char* kind = ""; ///< "light", "cluster" or "element" links
    int pass = 0;          ///< passes of refine() so far, from 1
    std::size_t element_links = 0, cluster_links = 0, light_links = 0, nodes = 0;
};

/// \brief Makes and refines the links of \p store over hierarchy \p h (which refinement
///        subdivides), with the cluster tables \p tables when clustering (else null).
///        Lives as long as refinement: \p h, \p store, \p tables and \p sun
///        (may be null) outlive it.
class LinkSet {
public:
    LinkSet(Hierarchy& h, LinkStore& store, ClusterTables* tables,
            const VisibilityQuery& visibility, const std::vector<PointLight>& lights,
            const Sun* sun, const Sky* sky, RefineSettings settings);

    /// Links between all pairs of roots that face each other, and from every light to every
    /// root it can see.
    void link_roots();
    /// With clusters: one link of the top cluster to itself, which refinement splits, and the
    /// lights' links to every root they see.
    void link_clusters();
    /// Takes saved links (a re-solve) and links the lights anew (their intensities may have
    /// changed).
    void restore(std::span<const Link> links, std::span<const ClusterLink> cluster_links);
    /// Sets the refinement threshold (W/m²).
    void set_threshold(double threshold) { settings_.threshold = threshold; }
    /// Sets the cluster links' refinement threshold (W/m²).
    void set_cluster_threshold(double threshold) { settings_.cluster_threshold = threshold; }
    /// Refines every link whose oracle says so, given node radiosities \p b and their ranges
    /// over each node's leaves \p b_range (largest channel), until none does. New nodes get
    /// their parent's values. Returns true if anything changed.
    /// \p on_pass (may be empty) is called after every pass, on the calling thread (it may
    /// throw Cancelled): a big scene's first refinement makes hundreds of millions of links
    /// over many passes.
    bool refine(std::vector<Rgb>& b, std::vector<float>& b_range,
                const std::function<void(const RefinePass&)>& on_pass = {});

    /// The exact link from planar end \p q to planar end \p p (one a face cluster) as the
    /// refinement would make it (with cluster tables): for tests.
    ClusterLink exact_link(NodeRef q, NodeRef p) const { return make_exact_link(q, p); }
    /// The exact links q ← p and p ← q as the refinement makes a pair linked both ways in one
    /// pass: for tests.
    std::pair<ClusterLink, ClusterLink> exact_pair(NodeRef q, NodeRef p) const {
        std::pair<ClusterLink, ClusterLink> out;
        make_exact_pair(q, p, out.first, out.second);
        return out;
    }
    /// What the sun's and the sky's links deliver, Σ irradiance × receiver area (W per channel).
    RgbD distant_power() const { return store_.distant_power(h_); }

private:
    Link make_link(std::uint32_t receiver, std::uint32_t source) const;
    /// The link of \p l's pair the other way (F_pq A_p = F_qp A_q, the same visibility).
    /// Its spread is computed only where the oracle reads it (an end above min_area).
    Link reverse_link(const Link& l) const;
    /// Makes the links links_[first, end) name (placeholders), one computation per pair
    /// linked both ways, and drops those that carry nothing. Reorders them. \p indexed:
    /// links_[0, first) are as receiver_offsets() indexed them, and a pair's link the other
    /// way found there is used too.
    void make_pair_links(std::size_t first, bool indexed);
    LightLink make_light_link(std::uint32_t receiver, LightId light) const;
    LightLink make_sun_link(std::uint32_t receiver) const;
    LightLink make_sky_link(std::uint32_t receiver) const;
    void subdivide(std::uint32_t node, std::vector<Rgb>& b, std::vector<float>& b_range);
    bool refine_pass(std::vector<Rgb>& b, std::vector<float>& b_range);
    bool refine_light_pass(std::vector<Rgb>& b, std::vector<float>& b_range);
    void sort_and_index() { store_.sort_and_index(h_.size(), tree_); }
    void link_lights();
    /// Throws ConfigError if the nodes now and \p element_links and \p cluster_links links
    /// would exceed settings_.max_memory_bytes; \p when names the step, \p advice the
    /// settings to change.
    void check_growth(std::size_t element_links, std::size_t cluster_links, const char* when,
                      std::string_view advice = k_refinement_advice) const;
    /// Refuses, before link_roots() makes them, links of every pair of roots that would not
    /// fit the memory limit.
    void check_root_links() const;
    /// Elements q and p may exchange light: distinct, not twins, p radiates, they face.
    bool linkable(std::uint32_t q, std::uint32_t p) const;
    // Clusters (links/cluster_links.cpp).
    ClusterLink make_cluster_link(NodeRef receiver, NodeRef source) const;
    /// Whether rays between nodes \p q and \p p that hit the elements \p hits first (-1: none,
    /// -2: unnamed) met a plane that blocks every segment between the two (visibility/occluders.h);
    /// planes in \p tried are not tried again, and those tried are added to it.
    bool certified_occluded(NodeRef q, NodeRef p, std::span<const std::int32_t> hits,
                            std::vector<std::uint32_t>& tried) const;
    /// Whether rays \p segments from q to p, all blocked, are proved dark by a plane they
    /// first hit: from q's end (\p hits where \p traced, else traced into it), else traced
    /// again from p's (which overwrites both arrays).
    bool certified_blocked(NodeRef q, NodeRef p, std::vector<Segment>& segments,
                           std::vector<std::int32_t>& hits, bool traced) const;
    /// The same for the segment between their centres, traced one way and where need be the
    /// other (one or two rays): a proof that a pair is dark before its form factor is
    /// computed or its parts linked.
    bool centres_occluded(NodeRef q, NodeRef p) const;
    /// Whether node \p n (as far as it may exchange light with \p other) lies on side \p side
    /// (±1) of occluder plane \p plane, every surface of it facing the other side strictly so
    /// (what it exchanges with that side then crosses the plane); appends points whose convex
    /// hull holds that part of it to \p points.
    bool shaft_end(NodeRef n, NodeRef other, std::uint32_t plane, double side,
                   std::vector<Vec3>& points) const;
    /// Casts \p count more rays for \p link (a stream keyed by its ends and the rays it has),
    /// updating its visibility and distance term.
    /// Returns false if no ray could be cast (no surface of one end faces the other).
    bool cast_cluster_rays(ClusterLink& link, int count) const;
    /// Casts more rays for links all of whose rays were blocked but whose error is above the
    /// threshold only for that uncertainty. Returns true if any changed.
    bool resample_occluded(const std::vector<Rgb>& b);
    bool refine_cluster_pass(std::vector<Rgb>& b, std::vector<float>& b_range);
    double cluster_link_error(const ClusterLink& link, const std::vector<Rgb>& b) const;
    struct PairGeometry {
        double r = 0;     ///< distance between the ends' centres
        double radii = 0; ///< sum of their bounding radii
    };
    PairGeometry pair_geometry(const ClusterLink& link) const;
    /// What the oracle weighs: what the link would bring to a surface facing its source were
    /// it unoccluded (W/m²), its reflected part divided by oracle::k_reflected_slack.
    double weighed_irradiance(const ClusterLink& link, const std::vector<Rgb>& b,
                              const PairGeometry& g) const;
    /// The source's intensity × π toward the receiver (largest channel), its elements
    /// radiating \p element per unit area and its clusters \p lobes, relaxed by \p spread.
    double intensity_toward(const ClusterLink& link, const std::vector<Lobes>& lobes,
                            const std::vector<Rgb>& element, double spread) const;
    Vec3 node_centre(NodeRef n) const;
    double node_radius(NodeRef n) const;
    double node_area(NodeRef n) const;
    /// Whether refinement may split node \p n: an element above the minimum area or with
    /// children; a cluster, except for an \p exact link a face cluster no larger than the
    /// minimum area (light between planar ends is not resolved below it, as an element's).
    bool splittable(NodeRef n, bool exact = false) const;
    /// Some surface of cluster \p c may face some point of \p other (by its axis lobes and
    /// the bounding boxes: conservative).
    bool faces_box(std::uint32_t c, NodeRef other) const;
    /// The index in dfs_roots_ of the root of cluster \p c whose share of the running sum
    /// \p running (dfs_area_ or dfs_exitance_) holds the fraction \p u in [0, 1).
    std::size_t draw_root(std::uint32_t c, double u, const std::vector<double>& running) const;
    Vec3 sample_facing_point(NodeRef n, const Vec3& toward, Pcg32& rng, Vec3& normal,
                             const std::vector<double>& running) const;
    template <typename Fn> void for_each_child(NodeRef n, Fn&& fn) const;
    using Plane = ClusterTables::Plane;
    using ContourEdge = ClusterTables::ContourEdge;
    // Exact links (links/exact_links.cpp).
    struct WeightedPoint {
        Vec3 x;
        double w = 0;
    };
    /// An element or a face cluster: an end of exact links.
    bool planar_end(NodeRef n) const;
    /// A planar end whose surfaces all emit alike (none, or one emission): the source of
    /// exact links (their vertices gather an emitting one exactly, leaf_direct in
    /// hierarchical.cpp).
    bool exact_source(NodeRef n) const;
    Plane node_plane(NodeRef n) const;
    /// Distance between the bounds of two nodes (0 where they overlap).
    double box_gap(NodeRef a, NodeRef b) const;
    /// An element's vertices, or the corners of a cluster's bounds.
    template <typename Fn> void for_each_corner(NodeRef n, Fn&& fn) const;
    /// Whether all of planar end \p p lies in front of the tangent plane (normal \p n) of
    /// \p x: its form factor from x is then the contour sum of p's boundary alone.
    bool sees_whole(const Vec3& x, const Vec3& n, NodeRef p) const;
    /// Calls \p fn(a, b) for each edge of p's boundary (a face cluster's straight runs).
    template <typename Fn> void for_each_contour_edge(NodeRef p, Fn&& fn) const;
    /// F from a point \p x of normal \p n, in front of planar end \p p of plane \p plane,
    /// where x's tangent plane cuts p; sets \p unresolved where p is a cluster too large to
    /// clip to x's hemisphere.
    double cut_form_factor(const Vec3& x, const Vec3& n, NodeRef p, const Plane& plane,
                           bool& unresolved) const;
    /// One end of an exact link's pair: quadrature points over it and the point form factors
    /// from them toward the other end, their mean, least and greatest.
    struct ExactEnd {
        std::vector<WeightedPoint> points;
        std::vector<double> values;
        double f = 0, lo = 0, hi = 0;
        bool unresolved = false; ///< the other end is a cluster too large to clip
    };
    /// Points over planar end \p q (at most \p count) and their form factors toward \p p.
    void exact_end(NodeRef q, NodeRef p, const Plane& pq, const Plane& pp, int count,
                   ExactEnd& end) const;
    /// How many points over receiver \p q an exact link from \p p takes.
    int exact_point_count(NodeRef q, NodeRef p, const Plane& pp) const;
    /// Some of each end faces the other, and no plane between their centres proves them dark.
    bool exact_ends_open(NodeRef q, NodeRef p, const Plane& pq, const Plane& pp) const;
    /// How far along planar_direction(p, q) the part of face cluster \p p that \p q sees
    /// most of lies from p's centroid (ClusterLink::d.y), from the points \p end over p.
    double seen_offset(NodeRef p, NodeRef q, const ExactEnd& end) const;
    /// Sets an exact link's form factor, spread, slope and (given its \p source end, a
    /// cluster's) offset from its \p receiver end; false if it carries nothing.
    bool set_exact_form_factor(ClusterLink& link, const ExactEnd& receiver,
                               const ExactEnd* source) const;
    /// Casts an exact link's rays: its visible fraction, or its proof of darkness (g = 0).
    void exact_visibility(ClusterLink& link, const Plane& pq, const Plane& pp) const;
    static ClusterLink exact_placeholder(NodeRef q, NodeRef p);
    static constexpr std::uint32_t k_no_reverse = ~std::uint32_t(0);
    /// Per pair of \p pairs (receiver, source), the index of its reverse where both are
    /// exact links (make_exact_pair makes them together), else k_no_reverse.
    std::vector<std::uint32_t>
    exact_reverses(const std::vector<std::pair<NodeRef, NodeRef>>& pairs) const;
    /// The exact links q ← p and p ← q, as make_exact_link makes them but for the points
    /// each end takes (the larger of its own count and what the other's offset asks).
    void make_exact_pair(NodeRef q, NodeRef p, ClusterLink& qp, ClusterLink& pq) const;
    /// F from a point \p x of normal \p n to the part of face cluster \p c (of plane normal
    /// \p normal) in front of x's tangent plane, by the contour of that part; \p ok is false
    /// where its crossings of the plane do not pair up (then the roots are clipped one by
    /// one).
    double clipped_contour(const Vec3& x, const Vec3& n, std::uint32_t c, const Vec3& normal,
                           bool& ok) const;
    /// Σ of the point form factors from \p x to the roots dfs_roots_[begin, end).
    double root_form_factors(const Vec3& x, const Vec3& n, std::uint32_t begin,
                             std::uint32_t end) const;
    /// Quadrature points over planar end \p q (at most \p count), weights summing to 1.
    void receiver_points(NodeRef q, int count, std::vector<WeightedPoint>& out) const;
    /// A point of planar end \p n, its root drawn by the running sum \p running (dfs_area_
    /// or dfs_exitance_), uniform within the root.
    Vec3 sample_point(NodeRef n, Pcg32& rng, const std::vector<double>& running) const;
    ClusterLink make_exact_link(NodeRef q, NodeRef p) const;
    /// Sets an exact link's slope (cluster receivers) and its spread about that plane, from
    /// the point form factors \p values at \p points (mean \p f).
    void fit_slope(ClusterLink& link, const std::vector<WeightedPoint>& points,
                   const std::vector<double>& values, double f) const;
    /// The oracle's estimate for an exact link (oracle::exact_link_error), with the source's
    /// mean radiosity and its range over the source (clusters: their departure from the
    /// linear fit).
    double exact_link_error(const ClusterLink& link, const std::vector<Rgb>& b,
                            const std::vector<float>& b_range) const;

    Hierarchy& h_;
    LinkStore& store_;
    /// The store's links, which refinement rewrites in place.
    MappedArray<Link>& links_;
    std::vector<LightLink>& light_links_;
    const std::vector<std::uint32_t>& offsets_;
    MappedArray<ClusterLink>& cluster_links_;
    ClusterTables* tables_ = nullptr;
    const ClusterTree* tree_ = nullptr; ///< of tables_, null without clusters
    const VisibilityQuery& visibility_;
    const std::vector<PointLight>& lights_;
    const Sun* sun_ = nullptr; ///< null without a sun
    const Sky* sky_ = nullptr; ///< null without a sky
    RefineSettings settings_;
    /// Within one refine(), per link: its oracle already said keep. Radiosities do not change
    /// during refine() and new nodes take their parent's values, so it would say keep again:
    /// each pass weighs only the links made by the one before (same decisions, a fraction of
    /// the work; a refine() takes about as many passes as the hierarchies are deep).
    std::vector<std::uint8_t> kept_, cluster_kept_;
};

} // namespace penumbra::solver
