#include "iteration/cluster_transport.h"

#include <algorithm>

#include "core/parallel.h"

namespace penumbra::solver {

namespace {

struct SourceTerm {
    Rgb emitted, total; ///< Σ E A cos and Σ B A cos toward the receiver, times g · v
};

// What the exact links from each face cluster read of it in one gather, worked out once per
// cluster rather than per link (a third of the cluster gather's time went to it): its mean
// radiosity and emission, and whether it emits.
struct FaceMeans {
    std::vector<Rgb> total, emitted;
    std::vector<std::uint8_t> emits;
};

FaceMeans face_means(const ClusterTree& tree, const ClusterTables& tables,
                     const ClusterValues& cv) {
    FaceMeans m;
    m.total.resize(tree.size());
    m.emitted.resize(tree.size());
    m.emits.resize(tree.size());
    parallel_for_index(tree.size(), 256, [&](std::size_t c) {
        if (!tree.planar[c])
            return;
        const auto i = std::uint32_t(c);
        m.total[c] = tables.face_mean(i, cv.exitance);
        m.emitted[c] = tables.face_mean(i, cv.exitance_emitted);
        m.emits[c] = tables.emits(cluster_ref(i)) ? 1 : 0;
    });
    return m;
}

// \p increment and \p exact_emitted: as gather_cluster_links.
SourceTerm source_term(const Hierarchy& h, const ClusterTables& tables, const ClusterValues& cv,
                       const FaceMeans& means, const std::vector<Rgb>& b, const ClusterLink& link,
                       bool increment, bool exact_emitted) {
    const float scale = link.g * link.visible();
    if (link.exact) { // F · v times the radiosity the source sends it
        SourceTerm s;
        if (!is_cluster(link.source)) {
            const std::uint32_t p = link.source;
            if (!increment && !h.emission[p].is_black())
                s.emitted = h.emission[p] * scale;
            s.total = b[p] * scale;
        } else {
            const std::uint32_t c = cluster_index(link.source);
            // Most sources emit nothing: their emitted part is not worked out.
            if (means.emits[c])
                s.emitted =
                    tables.exact_source_radiosity(link, means.emitted[c], cv.gradient_emitted) *
                    scale;
            s.total = tables.exact_source_radiosity(link, means.total[c], cv.gradient) * scale;
        }
        if (!exact_emitted) {
            s.total = s.total - s.emitted;
            s.emitted = Rgb{};
        }
        return s;
    }
    const Vec3 toward_receiver = -Vec3(link.d);
    if (is_cluster(link.source)) {
        const std::uint32_t c = cluster_index(link.source);
        return {lobe_projection(cv.exitance_emitted[c], toward_receiver) * scale,
                lobe_projection(cv.exitance[c], toward_receiver) * scale};
    }
    const std::uint32_t p = link.source;
    const float f = scale * float(h.area[p] * std::max(0.0, dot(h.normal[p], toward_receiver)));
    return {increment ? Rgb{} : h.emission[p] * f, b[p] * f};
}

} // namespace

void init_cluster_values(const ClusterTree& tree, const Hierarchy& h, const std::vector<Rgb>& b,
                         ClusterValues& cv) {
    pull_lobes(tree, h, h.emission, cv.exitance_emitted);
    planar_gradients(tree, h, h.emission, cv.gradient_emitted);
    pull_clusters(tree, h, b, cv);
    weigh_departures(tree, h, b, cv);
    cv.gathered_direct.assign(tree.size(), Lobes{});
    cv.gathered_indirect.assign(tree.size(), Lobes{});
    cv.root_direct.assign(h.root_count, Rgb{});
    cv.root_indirect.assign(h.root_count, Rgb{});
}

void gather_cluster_links(const Hierarchy& h, const ClusterTables& tables, const LinkStore& links,
                          const std::vector<Rgb>& b, ClusterValues& cv,
                          std::vector<Rgb>& gathered_direct, std::vector<Rgb>& gathered_indirect,
                          bool increment, bool exact_emitted) {
    const ClusterTree& tree = tables.tree();
    const auto& all = links.cluster_links();
    const auto& by_element = links.cluster_offsets_elements();
    const auto& by_cluster = links.cluster_offsets_clusters();
    const FaceMeans means = face_means(tree, tables, cv);
    parallel_for_index(h.size(), 256, [&](std::size_t q) {
        Rgb direct, indirect;
        for (std::uint32_t k = by_element[q]; k < by_element[q + 1]; ++k) {
            const ClusterLink& l = all[k];
            if (l.self)
                continue;
            const SourceTerm s = source_term(h, tables, cv, means, b, l, increment, exact_emitted);
            // An exact link's F holds the cosines.
            const float cosine = l.exact ? 1.0f : float(std::max(0.0, dot(h.normal[q], Vec3(l.d))));
            direct += s.emitted * cosine;
            indirect += (s.total - s.emitted) * cosine;
        }
        gathered_direct[q] += direct;
        gathered_indirect[q] += indirect;
    });
    cv.slope_direct.resize(tree.size());
    cv.slope_indirect.resize(tree.size());
    parallel_for_index(tree.size(), 64, [&](std::size_t c) {
        Lobes direct{}, indirect{};
        Slope slope_direct{}, slope_indirect{};
        // The frame exact links' slopes are given in (ClusterTables::exact_slope), once per
        // receiver rather than per link.
        const Frame frame = tree.planar[c] ? Frame::from_normal(tree.normal[c]) : Frame{};
        for (std::uint32_t k = by_cluster[c]; k < by_cluster[c + 1]; ++k) {
            const ClusterLink& l = all[k];
            if (l.self)
                continue;
            const SourceTerm s = source_term(h, tables, cv, means, b, l, increment, exact_emitted);
            // An exact link's irradiance is the plane's: deposited along its normal, every
            // root of the face cluster reads it back whole, plus its slope across the plane.
            const Vec3 along = l.exact ? tree.normal[c] : Vec3(l.d);
            lobe_deposit(direct, along, s.emitted);
            lobe_deposit(indirect, along, s.total - s.emitted);
            if (l.exact && (l.d.z != 0 || l.slope_t != 0) && l.g > 0) {
                const Vec3 t = ClusterTables::exact_slope(l, frame) * double(1.0f / l.g);
                for (std::size_t a = 0; a < 3; ++a) {
                    slope_direct[a] += s.emitted * float(t[a]);
                    slope_indirect[a] += (s.total - s.emitted) * float(t[a]);
                }
            }
        }
        cv.gathered_direct[c] = direct;
        cv.gathered_indirect[c] = indirect;
        cv.slope_direct[c] = slope_direct;
        cv.slope_indirect[c] = slope_indirect;
    });
}

// The slopes of a face cluster and of its face-cluster ancestors make one linear function
// over its plane: pushed down as its value at each cluster's centroid (level) and its
// gradient, read by each root at its centroid. The centroids are area-weighted, so a slope
// adds no power.
void push_clusters(const ClusterTree& tree, const Hierarchy& h, ClusterValues& cv) {
    std::vector<Lobes> down_direct(tree.size()), down_indirect(tree.size());
    const bool sloped = cv.slope_direct.size() == tree.size();
    std::vector<Slope> gradient_direct, gradient_indirect;
    std::vector<Rgb> level_direct, level_indirect;
    if (sloped) {
        gradient_direct = cv.slope_direct;
        gradient_indirect = cv.slope_indirect;
        level_direct.assign(tree.size(), Rgb{});
        level_indirect.assign(tree.size(), Rgb{});
    }
    for_each_cluster_by_level(tree, false, [&](std::uint32_t c) {
        down_direct[c] = cv.gathered_direct[c];
        down_indirect[c] = cv.gathered_indirect[c];
        if (tree.parent[c] >= 0) {
            const auto parent = std::size_t(tree.parent[c]);
            for (std::size_t l = 0; l < 6; ++l) {
                down_direct[c][l] += down_direct[parent][l];
                down_indirect[c][l] += down_indirect[parent][l];
            }
            if (sloped && tree.planar[parent]) {
                const Vec3 offset = tree.centroid[c] - tree.centroid[parent];
                level_direct[c] =
                    level_direct[parent] + slope_along(gradient_direct[parent], offset);
                level_indirect[c] =
                    level_indirect[parent] + slope_along(gradient_indirect[parent], offset);
                for (std::size_t a = 0; a < 3; ++a) {
                    gradient_direct[c][a] += gradient_direct[parent][a];
                    gradient_indirect[c][a] += gradient_indirect[parent][a];
                }
            }
        }
        for (std::uint32_t k = tree.child_begin[c]; k < tree.child_begin[c + 1]; ++k) {
            const NodeRef r = tree.children[k];
            if (is_cluster(r))
                continue;
            cv.root_direct[r] = lobe_projection(down_direct[c], h.normal[r]);
            cv.root_indirect[r] = lobe_projection(down_indirect[c], h.normal[r]);
            if (sloped && tree.planar[c]) {
                const Vec3 offset = h.centroid(r) - tree.centroid[c];
                cv.root_direct[r] += level_direct[c] + slope_along(gradient_direct[c], offset);
                cv.root_indirect[r] +=
                    level_indirect[c] + slope_along(gradient_indirect[c], offset);
            }
        }
    });
}

void pull_clusters(const ClusterTree& tree, const Hierarchy& h, const std::vector<Rgb>& b,
                   ClusterValues& cv) {
    pull_lobes(tree, h, b, cv.exitance);
    planar_gradients(tree, h, b, cv.gradient);
    cv.peak.assign(tree.size(), 0.0f);
    for_each_cluster_by_level(tree, true, [&](std::uint32_t c) {
        for (std::uint32_t k = tree.child_begin[c]; k < tree.child_begin[c + 1]; ++k) {
            const NodeRef child = tree.children[k];
            cv.peak[c] = std::max(cv.peak[c], is_cluster(child) ? cv.peak[cluster_index(child)]
                                                                : b[child].max_component());
        }
    });
}

void weigh_departures(const ClusterTree& tree, const Hierarchy& h, const std::vector<Rgb>& b,
                      ClusterValues& cv) {
    planar_gradients(tree, h, b, cv.gradient, &cv.departure);
}

} // namespace penumbra::solver
