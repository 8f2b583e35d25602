#pragma once
// Links of hierarchical radiosity (Hanrahan, Salzman & Aupperle 1991): energy transfer from a
// source node to a receiver node with a form factor and a visibility class, refined by a
// power oracle.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "core/light.h"
#include "core/rng.h"
#include "core/scene.h"
#include "core/visibility.h"
#include "hierarchy/cluster_tree.h"
#include "hierarchy/hierarchy.h"
#include "kernels/element_rows.h"
#include "links/mapped_array.h"
#include "visibility/occluders.h"

namespace penumbra::solver {

/// 16 bytes: a big scene's links are most of the solve's memory (the 1M office floor would
/// make hundreds of millions), so the occlusion flag is the sign bit of the spread.
struct Link {
    std::uint32_t receiver = 0, source = 0;
    float ff = 0; ///< F from receiver to source: H_receiver += ff · B_source

    Link() = default;
    Link(std::uint32_t q, std::uint32_t p, float f, float spread_, bool partial_)
        : receiver(q), source(p), ff(f), spread_bits(partial_ ? -spread_ : spread_) {}
    /// Variation of the point form factor over the receiver (≥ 0).
    float spread() const { return std::abs(spread_bits); }
    /// Partly occluded.
    bool partial() const { return std::signbit(spread_bits); }

private:
    float spread_bits = 0; ///< the spread, negative (−0 for 0) for a partly occluded link
};
static_assert(sizeof(Link) == 16);

struct LightLink {
    std::uint32_t receiver = 0;
    LightId light{SunSource{}}; ///< a point light or the sun
    /// I Ω V / A of the receiver, W/m² (Ω weighted by a spot's profile); the sun's
    /// irradiance · cos θ · V
    Rgb irradiance;
    /// Variation of I·profile·cos θ / d² over the receiver (largest channel), W/m²
    float spread = 0;
    std::uint8_t partial = 0; ///< partly occluded, or across a spot's hard cone edge
};
static_assert(sizeof(LightLink) == 28);

/// The spread of an exact link that ClusterLink::unresolved().
inline constexpr float k_unresolved = std::numeric_limits<float>::max();

/// A link with a cluster at one end or both (Smits et al. 1994): the source is seen as a point
/// of intensity (1/π) Σ B A cos toward the receiver, the receiver as a point at its centre.
///
/// An exact link joins two planar ends (face clusters or elements, one of them a cluster) as
/// an element link joins two elements: g is the form factor F from the receiver to the
/// source, averaged over the receiver, v its visible fraction, and the receiver's plane takes
/// F · v · B (B what the source sends it, exact_source_radiosity) whatever the direction
/// between the ends, spread over a cluster receiver by the slope of F. So a
/// tessellated wall and the floor it stands on exchange light through one link until the
/// oracle asks for more, as two untessellated polygons would.
struct ClusterLink {
    NodeRef receiver = 0, source = 0;
    /// Lobe links: mean 1 / (π d²) over the open rays between the two ends (all if none),
    /// scaled to their true cosines (cast_cluster_rays). Exact links: F without occlusion.
    float g = 0;
    /// Lobe links: unit direction from the receiver's centre to the source's centre. Exact
    /// links: x the spread of the point form factors over the receiver (of a cluster
    /// receiver: twice their largest departure from the plane of z and slope_t), y (of a cluster
    /// source) the offset along LinkSet::exact_source_direction of the F-weighted centroid
    /// of the source (where the receiver sees most of it) from its area centroid: the source
    /// sends the radiosity of its linear fit there (LinkSet::exact_source_radiosity),
    /// z (of a cluster receiver) the slope of F per metre along the s axis of its plane's
    /// Frame (LinkSet::exact_slope).
    Vec3f d;
    float slope_t = 0; ///< exact links: the same along the t axis
    /// Visible fraction from the link's rays, in 1/65535 (a link with any light open keeps
    /// at least 1): 2 bytes rather than a float's 4 keep the link at 32 bytes.
    std::uint16_t v_bits = 0;
    /// Visibility rays cast (0 where no surface of one end faces the other): 4, more for a
    /// link all of whose rays were blocked while the oracle was unsure of it (at most
    /// k_max_link_rays).
    std::uint16_t rays : 13 = 0;
    std::uint16_t partial : 1 = 0; ///< the rays disagreed
    std::uint16_t self : 1 = 0;    ///< a cluster's link to itself: carries nothing until refined
    std::uint16_t exact : 1 = 0;   ///< an exact link between planar ends

    float visible() const { return float(v_bits) * (1.0f / 65535.0f); }
    void set_visible(double v) {
        v_bits = v > 0 ? std::uint16_t(std::clamp(std::lround(v * 65535.0), 1L, 65535L)) : 0;
    }
    float spread() const { return d.x; } ///< of an exact link
    /// An exact link whose form factor its points do not resolve: the oracle splits it.
    bool unresolved() const { return exact && d.x == k_unresolved; }
};
static_assert(sizeof(ClusterLink) == 32);
/// Most rays a cluster link may record (ClusterLink::rays).
constexpr int k_max_link_rays = (1 << 13) - 1;

/// What the refinement oracle weighs against ε: F·B (Hanrahan et al.'s BF), or ΔF·B + F·ΔB:
/// the variation of the form factor over the receiver times the source radiosity (the error
/// of giving the whole receiver one value) plus the form factor times the range of radiosity
/// over the source's leaves (the error of treating the source as uniform).
enum class Oracle { bf, variation };

struct RefineSettings {
    Oracle oracle = Oracle::variation;
    /// W/m² (largest channel): refine links whose F·B (the irradiance they bring) exceeds it.
    double threshold = 0;
    /// W/m²: the same for cluster links, whose point approximation may be off by a factor
    /// where a small bright source lights a large cluster: ε × the mean irradiance (emitted
    /// power over the total area) rather than ε × the brightest exitance.
    double cluster_threshold = 0;
    double min_area = 0; ///< m²
    RowSettings rows;
    double offset = 0;
};

/// What refine() reports after each of its passes (a pass refines every link once).
struct RefinePass {
    const char* kind = ""; ///< "light", "cluster" or "element" links
    int pass = 0;          ///< passes of refine() so far, from 1
    std::size_t element_links = 0, cluster_links = 0, light_links = 0, nodes = 0;
};

class LinkSet {
public:
    /// \p sun (may be null) must outlive the link set.
    LinkSet(Hierarchy& h, std::vector<std::int32_t>& twin, const VisibilityQuery& visibility,
            const std::vector<PointLight>& lights, const Sun* sun, RefineSettings settings);

    /// Links between all pairs of roots that face each other, and from every light to every
    /// root it can see.
    void link_roots();
    /// With clusters: one link of the top cluster to itself, which refinement splits, and the
    /// lights' links to every root they see. \p exitance is the clusters' exitance lobes
    /// (Σ B A cos) and \p peak their brightest root's radiosity, read by the oracle at every
    /// refine().
    /// \p emitted is the clusters' emitted exitance lobes (Σ E A cos): the oracle holds the
    /// direct light a link brings to a tighter bound than the reflected.
    void link_clusters(const ClusterTree& tree, const std::vector<Lobes>& exitance,
                       const std::vector<Lobes>& emitted, const std::vector<float>& peak,
                       const std::vector<float>& departure);
    /// Uses \p tree (as link_clusters) without making links.
    void attach_clusters(const ClusterTree& tree, const std::vector<Lobes>& exitance,
                         const std::vector<Lobes>& emitted, const std::vector<float>& peak,
                         const std::vector<float>& departure);
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

    std::span<const Link> links() const { return links_.span(); }
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
    /// Whether node \p n (an element or a face cluster) emits (until
    /// release_refinement_tables).
    bool emits(NodeRef n) const;
    /// The roots of cluster \p c (until release_refinement_tables).
    std::span<const std::uint32_t> cluster_roots(std::uint32_t c) const {
        return std::span<const std::uint32_t>(dfs_roots_)
            .subspan(root_begin_[c], root_end_[c] - root_begin_[c]);
    }
    /// The exact link from planar end \p q to planar end \p p (one a face cluster) as the
    /// refinement would make it (link_clusters or attach_clusters first): for tests.
    ClusterLink exact_link(NodeRef q, NodeRef p) const { return make_exact_link(q, p); }
    /// The exact links q ← p and p ← q as the refinement makes a pair linked both ways in one
    /// pass: for tests.
    std::pair<ClusterLink, ClusterLink> exact_pair(NodeRef q, NodeRef p) const {
        std::pair<ClusterLink, ClusterLink> out;
        make_exact_pair(q, p, out.first, out.second);
        return out;
    }
    /// Frees the tables refinement and the cluster links' gather read (the cluster tree's
    /// roots, boundaries, bounds and occluder planes), keeping the links: after the last
    /// gather, before the output stage.
    void release_refinement_tables();
    /// Moves the element links (or the cluster links) out, leaving the link set without them.
    MappedArray<Link> take_links() { return std::exchange(links_, {}); }
    MappedArray<ClusterLink> take_cluster_links() { return std::exchange(cluster_links_, {}); }
    const std::vector<LightLink>& light_links() const { return light_links_; }
    /// What the sun's links deliver, Σ irradiance × receiver area (W per channel): the
    /// sun's power in the balance.
    RgbD sun_power() const;
    std::span<const ClusterLink> cluster_links() const { return cluster_links_.span(); }
    /// CSR offsets of cluster_links() with an element receiver, by element node, and with a
    /// cluster receiver, by cluster (cluster links are kept sorted by receiver).
    const std::vector<std::uint32_t>& cluster_offsets_elements() const { return cl_elements_; }
    const std::vector<std::uint32_t>& cluster_offsets_clusters() const { return cl_clusters_; }
    std::size_t link_count() const {
        return links_.size() + light_links_.size() + cluster_links_.size();
    }
    /// CSR offsets of links() by receiver node (links are kept sorted by receiver).
    const std::vector<std::uint32_t>& receiver_offsets() const { return offsets_; }

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
    /// The link from \p source to \p receiver among links_[0, sorted) as receiver_offsets()
    /// indexed them, or null.
    const Link* find_link(std::uint32_t receiver, std::uint32_t source, std::size_t sorted) const;
    LightLink make_light_link(std::uint32_t receiver, LightId light) const;
    LightLink make_sun_link(std::uint32_t receiver) const;
    void subdivide(std::uint32_t node, std::vector<Rgb>& b, std::vector<float>& b_range);
    bool refine_pass(std::vector<Rgb>& b, std::vector<float>& b_range);
    bool refine_light_pass(std::vector<Rgb>& b, std::vector<float>& b_range);
    void sort_and_index();
    /// Sorts the (non-empty) element links by the offsets sort_and_index counted.
    void sort_links();
    void link_lights();
    /// Elements q and p may exchange light: distinct, not twins, p radiates, they face.
    bool linkable(std::uint32_t q, std::uint32_t p) const;
    void index_cluster_links();
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
    /// Rebuilds dfs_exitance_ from the roots' radiosities \p b.
    void weigh_sources(const std::vector<Rgb>& b);
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
    /// it unoccluded (W/m²), its reflected part divided by k_reflected_slack.
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
    struct Plane {
        Vec3 n;
        double d = 0; ///< n · (a point of the plane)
    };
    // Exact links (links/exact_links.cpp).
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
    /// The face clusters' boundaries (boundary_) and which are exact sources.
    void build_boundaries();
    /// Appends the boundary \p edges of a face cluster to \p out, collinear edges in a row
    /// as one.
    void merge_collinear(const std::vector<BoundaryEdge>& edges,
                         std::vector<ContourEdge>& out) const;
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
    /// Area centroid of a node.
    Vec3 node_centroid(NodeRef n) const;
    /// The unit direction from face cluster \p from's centroid toward \p toward's, in
    /// from's plane; zero for an element, or where toward is nearly straight above.
    Vec3 planar_direction(NodeRef from, NodeRef toward) const;
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
    /// The element oracle's estimate for an exact link, with the source's mean radiosity
    /// and its range over the source (clusters: their departure from the linear fit).
    double exact_link_error(const ClusterLink& link, const std::vector<Rgb>& b,
                            const std::vector<float>& b_range) const;
    /// What the oracle weighs an exact link from \p p against (W/m²).
    double exact_bar(NodeRef p) const;

    Hierarchy& h_;
    std::vector<std::int32_t>& twin_;
    const VisibilityQuery& visibility_;
    const std::vector<PointLight>& lights_;
    const Sun* sun_ = nullptr; ///< null without a sun
    RefineSettings settings_;
    MappedArray<Link> links_;
    std::vector<LightLink> light_links_;
    std::vector<std::uint32_t> offsets_;
    const ClusterTree* tree_ = nullptr;
    const std::vector<Lobes>* exitance_ = nullptr;
    const std::vector<Lobes>* emitted_ = nullptr;
    const std::vector<float>* peak_ = nullptr;
    const std::vector<float>* departure_ = nullptr; ///< ClusterValues::departure
    /// Per face cluster c, its boundary boundary_[boundary_begin_[c], boundary_begin_[c + 1]).
    std::vector<ContourEdge> boundary_;
    std::vector<std::uint32_t> boundary_begin_;
    std::vector<std::uint8_t> exact_source_; ///< per cluster (exact_source)
    std::vector<Lobes> area_lobes_;          ///< per cluster: Σ A max(0, ±n_a)
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
    MappedArray<ClusterLink> cluster_links_;
    std::vector<std::uint32_t> cl_elements_, cl_clusters_;
    /// Within one refine(), per link: its oracle already said keep. Radiosities do not change
    /// during refine() and new nodes take their parent's values, so it would say keep again:
    /// each pass weighs only the links made by the one before (same decisions, a fraction of
    /// the work; a refine() takes about as many passes as the hierarchies are deep).
    std::vector<std::uint8_t> kept_, cluster_kept_;
};

} // namespace penumbra::solver
