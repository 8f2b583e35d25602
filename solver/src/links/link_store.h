#pragma once
// The links of hierarchical radiosity (Hanrahan, Salzman & Aupperle 1991) and where they are
// kept: energy transfer from a source node to a receiver node with a form factor and a
// visibility class, indexed by receiver for the gathers. LinkSet (links/link_set.h) makes
// and refines them.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "core/light.h"
#include "core/mesh.h"
#include "hierarchy/cluster_tree.h"
#include "hierarchy/hierarchy.h"
#include "links/mapped_array.h"

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
    /// source) the offset along ClusterTables::exact_source_direction of the F-weighted centroid
    /// of the source (where the receiver sees most of it) from its area centroid: the source
    /// sends the radiosity of its linear fit there (ClusterTables::exact_source_radiosity),
    /// z (of a cluster receiver) the slope of F per metre along the s axis of its plane's
    /// Frame (ClusterTables::exact_slope).
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

/// \brief The element, light and cluster links of a hierarchy, sorted and indexed by
///        receiver (LinkSet makes and refines them).
class LinkStore {
public:
    std::span<const Link> links() const { return links_.span(); }
    /// CSR offsets of links() by receiver node (links are kept sorted by receiver).
    const std::vector<std::uint32_t>& receiver_offsets() const { return offsets_; }
    const std::vector<LightLink>& light_links() const { return light_links_; }
    /// Replaces the light links (other source terms on the same nodes).
    void set_light_links(std::vector<LightLink> links) { light_links_ = std::move(links); }
    std::span<const ClusterLink> cluster_links() const { return cluster_links_.span(); }
    /// CSR offsets of cluster_links() with an element receiver, by element node, and with a
    /// cluster receiver, by cluster (cluster links are kept sorted by receiver).
    const std::vector<std::uint32_t>& cluster_offsets_elements() const { return cl_elements_; }
    const std::vector<std::uint32_t>& cluster_offsets_clusters() const { return cl_clusters_; }
    std::size_t link_count() const {
        return links_.size() + light_links_.size() + cluster_links_.size();
    }
    /// What the links of the sources at infinity (the sun, the sky) deliver, Σ irradiance ×
    /// receiver area (W per channel): their power in the balance.
    RgbD distant_power(const Hierarchy& h) const;
    /// Moves the element links (or the cluster links) out, leaving the store without them.
    MappedArray<Link> take_links() { return std::exchange(links_, {}); }
    MappedArray<ClusterLink> take_cluster_links() { return std::exchange(cluster_links_, {}); }

private:
    friend class LinkSet; // makes and refines the links in place

    /// Sorts the links by receiver, then source, and indexes them for \p nodes nodes (and
    /// the cluster links for the clusters of \p tree, if any).
    void sort_and_index(std::size_t nodes, const ClusterTree* tree);
    /// Sorts the (non-empty) element links by the offsets sort_and_index counted.
    void sort_links(std::size_t nodes);
    void index_cluster_links(std::size_t nodes, std::size_t clusters);
    /// The link from \p source to \p receiver among links_[0, sorted) as receiver_offsets()
    /// indexed them, or null.
    const Link* find_link(std::uint32_t receiver, std::uint32_t source, std::size_t sorted) const;

    MappedArray<Link> links_;
    std::vector<LightLink> light_links_;
    std::vector<std::uint32_t> offsets_;
    MappedArray<ClusterLink> cluster_links_;
    std::vector<std::uint32_t> cl_elements_, cl_clusters_;
};

} // namespace penumbra::solver
