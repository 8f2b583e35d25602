#pragma once
// Light transport through cluster links (see hierarchy/cluster_tree.h): gathering over the links,
// the push of clusters' irradiance lobes down to the roots, and the pull of exitance lobes up.

#include <vector>

#include "hierarchy/cluster_tree.h"
#include "hierarchy/hierarchy.h"
#include "links/cluster_tables.h"
#include "links/link_store.h"

namespace penumbra::solver {

struct ClusterValues {
    std::vector<Lobes> exitance_emitted; ///< Σ E A cos lobes per cluster (fixed)
    std::vector<Lobes> exitance;         ///< Σ B A cos lobes per cluster
    std::vector<Slope> gradient_emitted; ///< of the emission over each face cluster (fixed)
    std::vector<Slope> gradient;         ///< of the radiosity over each face cluster
    std::vector<float> peak;             ///< largest radiosity of a root (largest channel)
    /// Of a face cluster: twice the largest departure of its roots' radiosity from its linear
    /// fit (largest channel; 0 for volume clusters): what a source sending the fit's value
    /// may be off by (weigh_departures).
    std::vector<float> departure;
    std::vector<Lobes> gathered_direct; ///< irradiance lobes gathered by each cluster
    std::vector<Lobes> gathered_indirect;
    /// Per face cluster, the gradient (W/m² per metre, by world axis) that its exact links
    /// add to the irradiance across its plane, about its centroid (set by the gather).
    std::vector<Slope> slope_direct, slope_indirect;
    std::vector<Rgb> root_direct; ///< irradiance pushed down to each root
    std::vector<Rgb> root_indirect;
};

/// Exitance lobes of the emission (fixed) and of the radiosity \p b; sized for \p tree.
void init_cluster_values(const ClusterTree& tree, const Hierarchy& h, const std::vector<Rgb>& b,
                         ClusterValues& cv);

/// \brief Gathers every cluster link: adds to the element receivers' \p gathered_direct /
///        \p gathered_indirect and sets the clusters' gathered lobes. Parallel by receiver.
///        With \p increment, \p b (and cv.exitance) is radiosity to be sent on top of what
///        was (shooting's unshot): all of it counts as indirect, and cv.exitance_emitted is
///        not read for element sources (the caller zeroes it for clusters). Without
///        \p exact_emitted, exact links leave what their source emits out (the vertices
///        gather it themselves, leaf_direct in hierarchical.cpp).
void gather_cluster_links(const Hierarchy& h, const ClusterTables& tables, const LinkStore& links,
                          const std::vector<Rgb>& b, ClusterValues& cv,
                          std::vector<Rgb>& gathered_direct, std::vector<Rgb>& gathered_indirect,
                          bool increment = false, bool exact_emitted = true);

/// Pushes the clusters' gathered lobes down to the roots (cv.root_direct / root_indirect).
void push_clusters(const ClusterTree& tree, const Hierarchy& h, ClusterValues& cv);

/// Pulls the roots' radiosity \p b up into the clusters' exitance lobes.
void pull_clusters(const ClusterTree& tree, const Hierarchy& h, const std::vector<Rgb>& b,
                   ClusterValues& cv);

/// Sets cv.departure (and cv.gradient, as pull_clusters does) from the roots' radiosities
/// \p b: what the refinement oracle reads of a face-cluster source, so computed before each
/// refinement rather than after every sweep (a walk over every face cluster's roots).
void weigh_departures(const ClusterTree& tree, const Hierarchy& h, const std::vector<Rgb>& b,
                      ClusterValues& cv);

} // namespace penumbra::solver
