// Where the links are kept: sorted by receiver, then source, and indexed by receiver.

#include "links/link_store.h"

#include <algorithm>
#include <bit>
#include <variant>

#include <tbb/parallel_sort.h>

#include "core/parallel.h"

namespace penumbra::solver {

const Link* LinkStore::find_link(std::uint32_t receiver, std::uint32_t source,
                                 std::size_t sorted) const {
    if (std::size_t(receiver) + 1 >= offsets_.size())
        return nullptr; // a node made since the links were indexed
    const auto begin = links_.begin() + offsets_[receiver];
    const auto end = links_.begin() + offsets_[receiver + 1];
    if (std::size_t(offsets_[receiver + 1]) > sorted)
        return nullptr;
    const auto it = std::lower_bound(begin, end, source,
                                     [](const Link& l, std::uint32_t s) { return l.source < s; });
    return it != end && it->source == source ? &*it : nullptr;
}

RgbD LinkStore::distant_power(const Hierarchy& h) const {
    RgbD sum;
    for (const LightLink& l : light_links_)
        if (at_infinity(l.light.source()))
            sum += RgbD(l.irradiance) * h.area[l.receiver];
    return sum;
}

namespace {

// Permutes \p v in place so that bucket(v[i]) does not decrease, bucket b taking
// [start[b], start[b + 1]) (American flag sort: one swap puts a link in its bucket for good).
template <typename Bucket>
void flag_permute(std::span<Link> v, std::span<const std::uint32_t> start, Bucket bucket) {
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for (std::size_t b = 0; b + 1 < start.size(); ++b)
        while (next[b] < start[b + 1]) {
            const std::size_t k = bucket(v[next[b]]);
            if (k == b)
                ++next[b];
            else
                std::swap(v[next[b]], v[next[k]++]);
        }
}

} // namespace

// By receiver, then source, in place (no second copy of what is most of a big solve's
// memory): an American flag sort on the receiver's high bits (at most 1024 buckets, whose
// write positions stay in cache), then on the rest within each such bucket in parallel, then
// each receiver's few links by source (a receiver links to a source once).
void LinkStore::sort_and_index(std::size_t nodes, const ClusterTree* tree) {
    offsets_.assign(nodes + 1, 0);
    for (const Link& l : links_)
        ++offsets_[l.receiver + 1];
    for (std::size_t n = 0; n < nodes; ++n)
        offsets_[n + 1] += offsets_[n];
    if (!links_.empty())
        sort_links(nodes);
    if (tree)
        index_cluster_links(nodes, tree->size());
}

void LinkStore::sort_links(std::size_t nodes) {
    const int shift = std::max(0, int(std::bit_width(nodes)) - 10);
    const std::size_t tops = ((nodes - 1) >> shift) + 1;
    std::vector<std::uint32_t> top_start(tops + 1);
    for (std::size_t t = 0; t <= tops; ++t)
        top_start[t] = offsets_[std::min(nodes, t << shift)];
    flag_permute(links_.span(), top_start, [shift](const Link& l) { return l.receiver >> shift; });
    parallel_for_index(tops, 1, [&](std::size_t t) {
        const std::size_t first = t << shift, last = std::min(nodes, (t + 1) << shift);
        std::vector<std::uint32_t> start(offsets_.begin() + std::ptrdiff_t(first),
                                         offsets_.begin() + std::ptrdiff_t(last) + 1);
        const std::uint32_t base = start.front();
        for (std::uint32_t& x : start)
            x -= base;
        flag_permute(links_.span().subspan(base, start.back()), start,
                     [first](const Link& l) { return l.receiver - first; });
    });
    parallel_for_index(nodes, 256, [&](std::size_t q) {
        std::sort(links_.begin() + offsets_[q], links_.begin() + offsets_[q + 1],
                  [](const Link& a, const Link& b) { return a.source < b.source; });
    });
}

void LinkStore::index_cluster_links(std::size_t nodes, std::size_t clusters) {
    // In place (a stable sort would copy them): a receiver links to a source once, so the
    // order is total and the result the same on any thread count.
    tbb::parallel_sort(cluster_links_.begin(), cluster_links_.end(),
                       [](const ClusterLink& a, const ClusterLink& b) {
                           return a.receiver != b.receiver ? a.receiver < b.receiver
                                                           : a.source < b.source;
                       });
    cl_elements_.assign(nodes + 1, 0);
    cl_clusters_.assign(clusters + 1, 0);
    for (const ClusterLink& l : cluster_links_) {
        if (is_cluster(l.receiver))
            ++cl_clusters_[cluster_index(l.receiver) + 1];
        else
            ++cl_elements_[l.receiver + 1];
    }
    for (std::size_t n = 0; n < nodes; ++n)
        cl_elements_[n + 1] += cl_elements_[n];
    cl_clusters_[0] = cl_elements_.back();
    for (std::size_t c = 0; c < clusters; ++c)
        cl_clusters_[c + 1] += cl_clusters_[c];
}

} // namespace penumbra::solver
