#pragma once
// Links of hierarchical radiosity (Hanrahan, Salzman & Aupperle 1991): energy transfer from a
// source node to a receiver node with a form factor and a visibility class, refined by a
// power oracle.

#include <cstdint>
#include <vector>

#include "core/scene.h"
#include "core/visibility.h"
#include "element_rows.h"
#include "hierarchy.h"

namespace penumbra::solver {

struct Link {
    std::uint32_t receiver = 0, source = 0;
    float ff = 0;             ///< F from receiver to source: H_receiver += ff · B_source
    float spread = 0;         ///< variation of the point form factor over the receiver
    std::uint8_t partial = 0; ///< partly occluded
};

struct LightLink {
    std::uint32_t receiver = 0, light = 0;
    Rgb irradiance;           ///< I Ω V / A of the receiver, W/m²
    float spread = 0;         ///< variation of I cos θ / d² over the receiver (largest channel)
    std::uint8_t partial = 0;
};

/// What the refinement oracle weighs against ε: F·B (Hanrahan et al.'s BF), or ΔF·B + F·ΔB:
/// the variation of the form factor over the receiver times the source radiosity (the error
/// of giving the whole receiver one value) plus the form factor times the range of radiosity
/// over the source's leaves (the error of treating the source as uniform).
enum class Oracle { bf, variation };

struct RefineSettings {
    Oracle oracle = Oracle::variation;
    /// W/m² (largest channel): refine links whose F·B (the irradiance they bring) exceeds it.
    double threshold = 0;
    double min_area = 0;        ///< m²
    RowSettings rows;
    double offset = 0;
};

class LinkSet {
public:
    LinkSet(Hierarchy& h, std::vector<std::int32_t>& twin, const VisibilityQuery& visibility,
            const std::vector<PointLight>& lights, RefineSettings settings);

    /// Links between all pairs of roots that face each other, and from every light to every
    /// root it can see.
    void link_roots();
    /// Sets the refinement threshold (W/m²).
    void set_threshold(double threshold) { settings_.threshold = threshold; }
    /// Refines every link whose oracle says so, given node radiosities \p b and their ranges
    /// over each node's leaves \p b_range (largest channel), until none does. New nodes get
    /// their parent's values. Returns true if anything changed.
    bool refine(std::vector<Rgb>& b, std::vector<float>& b_range);

    const std::vector<Link>& links() const { return links_; }
    const std::vector<LightLink>& light_links() const { return light_links_; }
    /// CSR offsets of links() by receiver node (links are kept sorted by receiver).
    const std::vector<std::uint32_t>& receiver_offsets() const { return offsets_; }

private:
    Link make_link(std::uint32_t receiver, std::uint32_t source) const;
    LightLink make_light_link(std::uint32_t receiver, std::uint32_t light) const;
    void subdivide(std::uint32_t node, std::vector<Rgb>& b, std::vector<float>& b_range);
    bool refine_pass(std::vector<Rgb>& b, std::vector<float>& b_range);
    bool refine_light_pass(std::vector<Rgb>& b, std::vector<float>& b_range);
    void sort_and_index();

    Hierarchy& h_;
    std::vector<std::int32_t>& twin_;
    const VisibilityQuery& visibility_;
    const std::vector<PointLight>& lights_;
    RefineSettings settings_;
    std::vector<Link> links_;
    std::vector<LightLink> light_links_;
    std::vector<std::uint32_t> offsets_;
};

} // namespace penumbra::solver
