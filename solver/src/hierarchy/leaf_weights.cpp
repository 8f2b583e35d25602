// Leaf weights of hierarchical links (see hierarchy/leaf_weights.h). Each leaf evaluates the links
// of its ancestors after each refinement, and only where the leaf or the ancestor's links are new
// (or, once, when the first solve has given the reflected light): some twenty point form factors
// per link on the Cornell box, no rays.

#include "hierarchy/leaf_weights.h"

#include <algorithm>
#include <bit>

#include "core/parallel.h"
#include "core/rng.h"
#include "kernels/form_factor.h"

namespace penumbra::solver {

namespace {

// One link as one word for the hash (far end, form factor's bits, occlusion): one mix per link.
std::uint64_t link_word(std::uint32_t far_end, float ff, bool partial) {
    return (std::uint64_t(far_end) << 32 | std::bit_cast<std::uint32_t>(ff)) ^
           (std::uint64_t(partial) << 63) ^ 0x632be59bd9b4e019ULL;
}

// The emission of a receiving link's far end, which its direct weight is weighed by (a re-solve
// may change it).
std::uint64_t emission_word(const Rgb& e) {
    return (std::uint64_t(std::bit_cast<std::uint32_t>(e.r)) << 32 |
            std::bit_cast<std::uint32_t>(e.g)) ^
           (std::uint64_t(std::bit_cast<std::uint32_t>(e.b)) << 16);
}

// A hash of each node's links as receiver (far end, form factor, occlusion, the far end's
// emission) and as source (far end, form factor, occlusion).
std::vector<std::uint64_t> link_signatures(const Hierarchy& h, const LinkStore& links,
                                           const LinksBySource& by_source) {
    const std::span<const Link> all = links.links();
    const std::vector<std::uint32_t>& by_receiver = links.receiver_offsets();
    std::vector<std::uint64_t> sig(h.size(), 0);
    parallel_for_index(h.size(), 256, [&](std::size_t a) {
        std::uint64_t s = mix64(a);
        for (std::uint32_t k = by_receiver[a]; k < by_receiver[a + 1]; ++k) {
            s = mix64(s ^ link_word(all[k].source, all[k].ff, all[k].partial()));
            if (!h.emission[all[k].source].is_black())
                s = mix64(s ^ emission_word(h.emission[all[k].source]));
        }
        s = mix64(s ^ 0x9e3779b97f4a7c15ULL); // receiving and sending links differ
        for (std::uint32_t i = by_source.start[a]; i < by_source.start[a + 1]; ++i) {
            const Link& l = all[by_source.order[i]];
            s = mix64(s ^ link_word(l.receiver, l.ff, l.partial()));
        }
        sig[a] = s;
    });
    return sig;
}

// What the weights need of every node as a link's far end.
struct Ends {
    /// Beyond five sizes the differential form A cos θ cos θ' / (π r²) is within about 1 % of
    /// the contour integral (a disc: R² / d² against R² / (R² + d²)), and the weights use only
    /// how F varies between the leaves of one node.
    static constexpr double k_far_sizes = 5.0;

    std::vector<Vec3> centroid;
    std::vector<double> far2; ///< squared distance beyond which the differential form is used

    explicit Ends(const Hierarchy& h) : centroid(h.size()), far2(h.size()) {
        parallel_for_index(h.size(), 1024, [&](std::size_t n) {
            centroid[n] = h.centroid(std::uint32_t(n));
            const double reach = k_far_sizes * h.size_of(std::uint32_t(n));
            far2[n] = reach * reach;
        });
    }
};

// F from the centroid of leaf x to node s; 0 if the centroid is behind s.
double centroid_form_factor(const Hierarchy& h, const Ends& ends, std::uint32_t x,
                            std::uint32_t s) {
    const Vec3& c = ends.centroid[x];
    const Vec3 d = ends.centroid[s] - c;
    const double r2 = dot(d, d);
    if (r2 > ends.far2[s]) {
        const double cos_x = dot(d, h.normal[x]), cos_s = -dot(d, h.normal[s]);
        return cos_x > 0 && cos_s > 0 ? h.area[s] * cos_x * cos_s / (k_pi * r2 * r2) : 0.0;
    }
    if (dot(c - h.triangle[s][0], h.normal[s]) <= 0)
        return 0;
    return form_factor_point_triangle(c, h.normal[x], h.triangle[s]);
}

struct RawWeight {
    float receive = 1, emit = 1;
    Rgb reflected{1.0f};
};

// The far ends' light as a receive weight weighs it: emission (a channel sum: one weight for
// the direct light) and reflected radiosity (per channel), and their form factors alone, the
// reflected weight's fallback where no reflected light is known.
struct Seen {
    double f = 0, emitted = 0;
    RgbD reflected;
    void add(double ff, const Rgb& e, const Rgb& r) {
        f += ff;
        emitted += ff * e.sum();
        reflected += RgbD(std::max(r.r, 0.0f), std::max(r.g, 0.0f), std::max(r.b, 0.0f)) * ff;
    }
};

float ratio(double seen, double linked, double fallback) {
    return float(linked > 0 ? seen / linked : fallback);
}

// Leaf x's unscaled weights for its ancestor a (1 where a has no links of that kind). A partly
// occluded link keeps its even spread: its visibility from x is not known without rays.
RawWeight raw_weight(const Hierarchy& h, const LinkStore& links, const LinksBySource& by_source,
                     const Ends& ends, const std::vector<Rgb>& b, bool solved, std::uint32_t x,
                     std::uint32_t a) {
    const std::span<const Link> all = links.links();
    const std::vector<std::uint32_t>& by_receiver = links.receiver_offsets();
    RawWeight w;
    Seen seen, linked;
    for (std::uint32_t k = by_receiver[a]; k < by_receiver[a + 1]; ++k) {
        const Link& l = all[k];
        const Rgb& e = h.emission[l.source];
        const Rgb r = solved ? b[l.source] - e : Rgb{};
        seen.add(l.partial() ? double(l.ff) : centroid_form_factor(h, ends, x, l.source), e, r);
        linked.add(l.ff, e, r);
    }
    const double even = linked.f > 0 ? seen.f / linked.f : 1.0;
    w.receive = ratio(seen.emitted, linked.emitted, 1.0);
    w.reflected = Rgb(ratio(seen.reflected.r, linked.reflected.r, even),
                      ratio(seen.reflected.g, linked.reflected.g, even),
                      ratio(seen.reflected.b, linked.reflected.b, even));
    double sent = 0, share = 0;
    for (std::uint32_t i = by_source.start[a]; i < by_source.start[a + 1]; ++i) {
        const Link& l = all[by_source.order[i]];
        const double even_share = h.area[l.receiver] * l.ff / h.area[a]; // F(a → r)
        sent += l.partial() ? even_share : centroid_form_factor(h, ends, x, l.receiver);
        share += even_share;
    }
    if (share > 0)
        w.emit = float(sent / share);
    return w;
}

float scaled(double raw, double mean) {
    return mean > 0 ? float(raw / mean) : 1.0f;
}

// Divides the weights of each inner node's leaves by their area mean over its leaves; where
// no leaf sees any far end (a grazing pair), the weights are 1: the links' even spread.
void scale_to_unit_means(const Hierarchy& h, LeafWeights& w) {
    struct Means {
        double receive = 1, emit = 1;
        RgbD reflected{1, 1, 1};
    };
    std::vector<Means> mean(h.size());
    parallel_for_index(h.size(), 16, [&](std::size_t n) {
        const auto a = std::uint32_t(n);
        if (h.is_leaf(a))
            return;
        double r = 0, e = 0;
        RgbD reflected;
        std::vector<std::uint32_t> stack{a};
        while (!stack.empty()) {
            const std::uint32_t m = stack.back();
            stack.pop_back();
            if (!h.is_leaf(m)) {
                for (int c = 3; c >= 0; --c)
                    stack.push_back(std::uint32_t(h.first_child[m] + c));
                continue;
            }
            const std::size_t i = w.at(m, h.level[a]);
            r += h.area[m] * w.raw_receive[i];
            e += h.area[m] * w.raw_emit[i];
            reflected += RgbD(w.raw_reflected[i]) * h.area[m];
        }
        mean[a] = {r / h.area[a], e / h.area[a], reflected * (1.0 / h.area[a])};
    });
    w.receive.resize(w.raw_receive.size());
    w.emit.resize(w.raw_emit.size());
    w.receive_reflected.resize(w.raw_reflected.size());
    parallel_for_index(h.size(), 64, [&](std::size_t n) {
        const auto x = std::uint32_t(n);
        if (!h.is_leaf(x))
            return;
        for (std::int32_t a = h.parent[x]; a >= 0; a = h.parent[a]) {
            const std::size_t i = w.at(x, h.level[a]);
            const Means& m = mean[std::size_t(a)];
            w.receive[i] = scaled(w.raw_receive[i], m.receive);
            w.emit[i] = scaled(w.raw_emit[i], m.emit);
            const Rgb& raw = w.raw_reflected[i];
            w.receive_reflected[i] = Rgb(scaled(raw.r, m.reflected.r), scaled(raw.g, m.reflected.g),
                                         scaled(raw.b, m.reflected.b));
        }
    });
}

} // namespace

LinksBySource index_by_source(const Hierarchy& h, std::span<const Link> links,
                              bool inner_sources_only) {
    LinksBySource s;
    s.start.assign(h.size() + 1, 0);
    auto indexed = [&](const Link& l) { return !inner_sources_only || !h.is_leaf(l.source); };
    for (const Link& l : links)
        if (indexed(l))
            ++s.start[l.source + 1];
    for (std::size_t n = 0; n < h.size(); ++n)
        s.start[n + 1] += s.start[n];
    std::vector<std::uint32_t> next(s.start.begin(), s.start.end() - 1);
    s.order.resize(s.start.back());
    for (std::size_t k = 0; k < links.size(); ++k)
        if (indexed(links[k]))
            s.order[next[links[k].source]++] = std::uint32_t(k);
    return s;
}

LeafWeights leaf_weights(const Hierarchy& h, const LinkStore& links, const std::vector<Rgb>& b,
                         bool solved, const LeafWeights& previous) {
    // Weights are per leaf and ancestor: only inner nodes' links are read (a big scene's
    // leaves send most links, and an index of all of them is 4 bytes a link).
    const LinksBySource by_source = index_by_source(h, links.links(), true);
    LeafWeights w;
    w.signature = link_signatures(h, links, by_source);
    w.offset.assign(h.size() + 1, 0);
    for (std::size_t n = 0; n < h.size(); ++n)
        w.offset[n + 1] = w.offset[n] + (h.is_leaf(std::uint32_t(n)) ? h.level[n] : 0);
    w.raw_receive.assign(w.offset.back(), 1.0f);
    w.raw_emit.assign(w.offset.back(), 1.0f);
    w.raw_reflected.assign(w.offset.back(), Rgb(1.0f));
    w.reflected_solved = solved;
    // Reflected weights of a solve are kept only for the same materials' next solves.
    const bool keep_reflected = solved && previous.reflected_solved;
    // A leaf is known if it was one last cycle (nodes keep their ids, a leaf its entry count,
    // ancestors have lower ids).
    const std::size_t old_nodes = previous.empty() ? 0 : previous.offset.size() - 1;
    auto known = [&](std::size_t x) {
        return x < old_nodes &&
               previous.offset[x + 1] - previous.offset[x] == w.offset[x + 1] - w.offset[x];
    };
    const Ends ends(h);
    parallel_for_index(h.size(), 16, [&](std::size_t n) {
        const auto x = std::uint32_t(n);
        if (!h.is_leaf(x))
            return;
        for (std::int32_t a = h.parent[x]; a >= 0; a = h.parent[a]) {
            const std::size_t i = w.at(x, h.level[a]);
            if (keep_reflected && known(x) &&
                previous.signature[std::size_t(a)] == w.signature[std::size_t(a)]) {
                const std::size_t j = previous.at(x, h.level[a]);
                w.raw_receive[i] = previous.raw_receive[j];
                w.raw_emit[i] = previous.raw_emit[j];
                w.raw_reflected[i] = previous.raw_reflected[j];
                continue;
            }
            const RawWeight r =
                raw_weight(h, links, by_source, ends, b, solved, x, std::uint32_t(a));
            w.raw_receive[i] = r.receive;
            w.raw_emit[i] = r.emit;
            w.raw_reflected[i] = r.reflected;
        }
    });
    scale_to_unit_means(h, w);
    return w;
}

} // namespace penumbra::solver
