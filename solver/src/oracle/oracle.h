#pragma once
// The refinement oracle of hierarchical radiosity, in one place: for each kind of link
// (element, light, cluster and exact links), the estimate of the error its transfer makes
// and whether it is refined, with the constants they were calibrated with. The link code
// (links/) gathers what the estimates read (form factors, spreads, visibility, the sources'
// radiosities and the clusters' lobes) and asks these.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "hierarchy/cluster_tree.h"
#include "links/link_store.h"

namespace penumbra::solver {

/// What the refinement oracle weighs against ε: F·B (Hanrahan et al.'s BF), or ΔF·B + F·ΔB:
/// the variation of the form factor over the receiver times the source radiosity (the error
/// of giving the whole receiver one value) plus the form factor times the range of radiosity
/// over the source's leaves (the error of treating the source as uniform).
using Oracle = RefinementOracle;

struct OracleSettings {
    Oracle oracle = Oracle::variation;
    /// W/m² (largest channel): refine links whose F·B (the irradiance they bring) exceeds it.
    double threshold = 0;
    /// W/m²: the same for cluster links, whose point approximation may be off by a factor
    /// where a small bright source lights a large cluster: ε × the mean irradiance (emitted
    /// power over the total area) rather than ε × the brightest exitance.
    double cluster_threshold = 0;
    double min_area = 0; ///< m²
};

namespace oracle {

// Element links.

/// \brief The error estimate of element link \p link (Hanrahan et al.'s BF oracle: the
///        irradiance it brings; or the variation oracle), doubled when partly occluded (its
///        visibility estimate is the least certain part). \p b_source: the source's
///        radiosity, \p b_range: its range over the source's leaves (largest channel);
///        \p receiver_area: m².
inline double element_link_error(const OracleSettings& s, const Link& link, double b_source,
                                 double b_range, double receiver_area) {
    // A receiver at the minimum area takes the mean of F over it whatever the source's
    // parts: splitting the source would not lower the error of its one value.
    const double spread = receiver_area > s.min_area ? double(link.spread()) : 0.0;
    return (s.oracle == Oracle::bf ? double(link.ff) * b_source
                                   : spread * b_source + double(link.ff) * b_range) *
           (link.partial() ? 2.0 : 1.0);
}

/// \brief Whether element link \p link is refined (element_link_error above the threshold,
///        one of its ends above the minimum area).
inline bool refine_element_link(const OracleSettings& s, const Link& link, double b_source,
                                double b_range, double receiver_area, double source_area) {
    if (element_link_error(s, link, b_source, b_range, receiver_area) <= s.threshold)
        return false;
    return std::max(receiver_area, source_area) > s.min_area;
}

// Light links.

/// \brief Whether light link \p l to a receiver of \p receiver_area m² is refined: partly
///        occluded (or across a spot's hard edge), or bringing more than the threshold
///        (BF) or varying by more over its receiver (variation), above the minimum area.
inline bool refine_light_link(const OracleSettings& s, const LightLink& l, double receiver_area) {
    const double e =
        s.oracle == Oracle::bf ? double(l.irradiance.max_component()) : double(l.spread);
    return (l.partial || e > s.threshold) && receiver_area > s.min_area;
}

// Cluster links (links/cluster_links.cpp).

/// A cluster link is kept only while the bounding spheres' radii sum to less than this times
/// the distance between the centres (a multipole method's admissibility): closer pairs' four
/// rays, between points that face the other centre, see little of what the parts exchange
/// (docs/calibration.md#k_admissible).
inline constexpr double k_admissible = 0.5;
/// The reflected light a cluster link brings is weighed against this many times the threshold
/// of its direct light (what its source emits): reflected light is smooth, and direct light
/// is what the vertices' far part shows (docs/calibration.md#k_reflected_slack).
inline constexpr double k_reflected_slack = 5.0;
/// Rays a link all of whose rays were blocked may get before the oracle splits it instead:
/// more rays cost time and change little (docs/calibration.md#k_max_cluster_rays).
inline constexpr int k_max_cluster_rays = 64;
/// Such a link gets rays until its uncertainty is this many times below the threshold: a link
/// taken as occluded loses what light it carries, always in the same direction.
inline constexpr double k_resample_margin = 16.0;

/// Links to a receiver that is specular only (Hierarchy::specular_only: a mirror, a metal, a
/// dielectric) are held to this many times the thresholds: the renderer traces what it shows,
/// and nothing reads the solution's light on it but its reported irradiance
/// (docs/calibration.md#k_specular_only_slack).
inline constexpr double k_specular_only_slack = 10.0;

/// \brief The settings a link to a receiver is refined by: \p s, with its thresholds times
///        k_specular_only_slack when the receiver is \p specular_only.
inline OracleSettings receiver_settings(OracleSettings s, bool specular_only) {
    if (specular_only) {
        s.threshold *= k_specular_only_slack;
        s.cluster_threshold *= k_specular_only_slack;
    }
    return s;
}

/// \brief Whether a pair of ends whose centres are \p r apart and whose bounding radii sum
///        to \p radii may exchange light through one cluster link (k_admissible).
inline bool admissible(double r, double radii) {
    return radii < k_admissible * r;
}

/// \brief What the oracle weighs of the intensity a cluster link's source sends: \p direct
///        (what it emits) in full, the rest of \p all divided by k_reflected_slack.
inline double weighed_intensity(double all, double direct) {
    return direct + std::max(0.0, all - direct) / k_reflected_slack;
}

/// \brief The part of the open irradiance a link's visibility may be off by: all of it
///        where the rays disagree; where all n were blocked, 1/n (n blocked rays cannot tell
///        0 from about 1/n).
inline double visibility_uncertainty(const ClusterLink& link) {
    if (link.partial)
        return 1.0;
    if (link.visible() > 0 || link.rays == 0)
        return 0.0;
    return 1.0 / double(link.rays);
}

/// \brief The error estimate of an admissible lobe link (not a self-link, not exact) whose
///        centres are \p r apart and whose radii sum to \p radii: the \p irradiance it would
///        bring unoccluded (weighed_intensity) times the relative error of the point
///        approximation (2 × the radii over the distance) where it is visible, plus the
///        uncertainty of its visibility.
inline double lobe_link_error(const ClusterLink& link, double r, double radii, double irradiance) {
    const double size_factor = 2.0 * radii / r;
    return irradiance * (double(link.visible()) * size_factor + visibility_uncertainty(link));
}

/// \brief The error estimate of a cluster's link to itself: its parts could bring each
///        other up to its brightest radiosity \p peak.
inline double self_link_error(float peak) {
    return double(peak);
}

/// \brief Whether a lobe link of error \p error is refined.
inline bool refine_lobe_link(const OracleSettings& s, double error) {
    return error > s.cluster_threshold;
}

/// \brief The rays an all-blocked lobe link that has \p rays and would bring \p open
///        (W/m², unoccluded) is given for its uncertainty to fall k_resample_margin below
///        the cluster threshold (at most k_max_cluster_rays), or 0 if it is there already.
inline double resample_rays(const OracleSettings& s, double open, std::uint16_t rays) {
    const double threshold = s.cluster_threshold;
    if (open / double(rays) <= threshold / k_resample_margin)
        return 0;
    return std::min(double(k_max_cluster_rays), std::ceil(k_resample_margin * open / threshold));
}

// Exact links (links/exact_links.cpp).

/// The same for exact links (all their light is reflected), whose receivers take the plane
/// of their form factor (links/exact_links.cpp; docs/calibration.md#k_exact_slack).
inline constexpr double k_exact_slack = 7.5;
/// A partly occluded exact link to a cluster receiver counts this many times F · B v (1 − v)
/// as error (exact_link_error; 4 times the mean error of its visibility over a sharp shadow):
/// without it a ceiling shadowed by a lamp just below it takes light its clusters' mean
/// visibility gives it (docs/calibration.md#k_shadow_weight).
inline constexpr double k_shadow_weight = 8.0;

/// \brief The element oracle's estimate for a resolved exact link, with the source's
///        \p mean radiosity and its \p range over the source (clusters: their departure from
///        the linear fit); \p receiver_splittable: refinement may split the receiver.
inline double exact_link_error(const OracleSettings& s, const ClusterLink& link, double mean,
                               double range, bool receiver_splittable) {
    const double f = double(link.g), visible = double(link.visible());
    // A receiver that cannot be split takes the mean of F over it whatever its source's
    // parts: splitting the source would not lower the error of its one value.
    const double spread = receiver_splittable ? double(link.spread()) : 0.0;
    const double estimate =
        s.oracle == Oracle::bf ? f * visible * mean : spread * mean + f * visible * range;
    // All rays blocked: n of them cannot tell 0 from about 1/n.
    const double uncertain =
        link.visible() > 0 || link.rays == 0 ? 0.0 : f * mean / double(link.rays);
    // A partly occluded link gives its cluster receiver its mean visibility v everywhere,
    // across the shadow: where that is sharp, v is off by 2 v (1 − v) on average. As with
    // the spread, only splitting the receiver resolves that (docs/calibration.md#k_shadow_weight).
    const double shadow = link.partial && is_cluster(link.receiver) && receiver_splittable
                              ? k_shadow_weight * f * visible * (1.0 - visible) * mean
                              : 0.0;
    return estimate * (link.partial ? 2.0 : 1.0) + uncertain + shadow;
}

/// \brief What the oracle weighs an exact link against (W/m²). One from a source that does
///        not emit carries reflected light only: it is weighed as a lobe link's reflected
///        light is (against the element threshold, ε × the brightest exitance, a lamp's, the
///        lamp room's sensor behind the box read 3.1 % high). One from an emitter is weighed
///        as a lobe link's direct light.
inline double exact_link_bar(const OracleSettings& s, bool source_emits) {
    return source_emits ? s.cluster_threshold : k_exact_slack * s.cluster_threshold;
}

/// \brief Whether an exact link of error \p error from a source that \p source_emits is
///        refined.
inline bool refine_exact_link(const OracleSettings& s, double error, bool source_emits) {
    return error > exact_link_bar(s, source_emits);
}

} // namespace oracle
} // namespace penumbra::solver
