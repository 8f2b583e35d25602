// Gathering, push-pull and the sweeps of hierarchical radiosity (see iteration/transport.h).

#include "iteration/transport.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "output/vertex_values.h"

namespace penumbra::solver {

Rgb reflected_exitance(const Hierarchy& h, const std::vector<Rgb>& b, std::uint32_t n) {
    const Rgb m = b[n] - h.emission[n];
    return {std::max(0.0f, m.r), std::max(0.0f, m.g), std::max(0.0f, m.b)};
}

namespace {

/// Gauss–Seidel sweeps take the roots in blocks of this many, in order: the links of a block
/// gather (in parallel) the radiosities that earlier blocks of the same sweep have already
/// updated. The blocks depend on the root count alone, so results do not depend on threads.
constexpr std::size_t k_gauss_seidel_block = 32;

void size_values(const Hierarchy& h, NodeValues& v) {
    const std::size_t n = h.size();
    for (std::vector<Rgb>* a : {&v.gathered_direct, &v.gathered_indirect, &v.h_direct,
                                &v.h_indirect, &v.link_direct, &v.link_indirect})
        a->resize(n);
    v.b_lo.resize(n);
    v.b_hi.resize(n);
    v.b_range.resize(n);
}

// The roots' specular light: the fixed part and what the roots' reflected exitance of the
// last sweep passes on through the transfers (a lag of one sweep, as transmitted light).
void transfer_specular(const Hierarchy& h, NodeValues& v) {
    std::vector<RgbD> power(h.root_count);
    for (const SpecularLight::Transfer& t : v.specular_transfers) { // serial: a fixed order
        power[t.to] += RgbD(reflected_exitance(h, v.b, t.from) * t.area_m2);
    }
    for (std::size_t r = 0; r < h.root_count; ++r) {
        const RgbD e = power[r] * (1.0 / h.area[r]);
        v.specular[r] = v.specular_fixed[r] + Rgb{float(e.r), float(e.g), float(e.b)};
    }
}

// Light links and cluster links to element receivers (into extra_*), the roots' specular
// light, and the clusters' irradiance pushed down to the roots, from the current radiosities.
void gather_extra(const Hierarchy& h, const LinkStore& links, NodeValues& v, Clusters& clusters) {
    v.extra_direct.assign(h.size(), Rgb{});
    v.extra_indirect.assign(h.size(), Rgb{});
    for (const LightLink& l : links.light_links()) // few; serial keeps the order fixed
        v.extra_direct[l.receiver] += l.irradiance;
    if (!v.specular_transfers.empty())
        transfer_specular(h, v);
    for (std::size_t r = 0; r < v.specular.size(); ++r)
        v.extra_indirect[r] += v.specular[r];
    if (clusters.enabled) {
        gather_cluster_links(h, *clusters.tables, links, v.b, clusters.values, v.extra_direct,
                             v.extra_indirect);
        push_clusters(clusters.tree, h, clusters.values);
    }
}

// Element links of node q: what its sources send, split into emission and the rest.
void gather_node(const Hierarchy& h, const LinkStore& links, NodeValues& v,
                 const std::vector<Rgb>& b_source, std::uint32_t q) {
    const auto& offsets = links.receiver_offsets();
    const auto& all = links.links();
    RgbD direct, indirect;
    for (std::uint32_t k = offsets[q]; k < offsets[q + 1]; ++k) {
        const Link& l = all[k];
        direct += RgbD(h.emission[l.source]) * l.ff;
        indirect += RgbD(b_source[l.source] - h.emission[l.source]) * l.ff;
    }
    v.link_direct[q] = Rgb(float(direct.r), float(direct.g), float(direct.b));
    v.link_indirect[q] = Rgb(float(indirect.r), float(indirect.g), float(indirect.b));
    v.gathered_direct[q] = v.link_direct[q] + v.extra_direct[q];
    v.gathered_indirect[q] = v.link_indirect[q] + v.extra_indirect[q];
}

// What each leaf passes on from its other side: τ times its twin's irradiance of the last
// sweep. Taken before the trees are swept in parallel (a twin lies in another tree, maybe of
// the same block), so no tree reads a value another thread writes; the lag of one sweep is
// one more step of the same fixed-point iteration.
void take_transmitted(const Hierarchy& h, NodeValues& v) {
    if (!h.any_transmittance()) {
        v.transmitted.clear();
        return;
    }
    v.transmitted.assign(h.size(), Rgb{});
    parallel_for_index(h.size(), 1024, [&](std::size_t n) {
        const std::int32_t t = h.twin[n];
        if (t >= 0 && h.is_leaf(std::uint32_t(n)) && !h.transmittance[n].is_black())
            v.transmitted[n] = h.transmittance[n] * (v.h_direct[t] + v.h_indirect[t]);
    });
}

const std::vector<Rgb>& sent_radiosity(const Hierarchy& h, const NodeValues& v) {
    return v.b_emit.size() == h.size() ? v.b_emit : v.b;
}

// Leaf x's radiosity \p b as it is sent: by x itself and, by its emit weights, as its share
// of what each ancestor sends (whose b_emit the caller has zeroed).
void add_emit_shares(const Hierarchy& h, NodeValues& v, std::uint32_t x, const Rgb& b) {
    v.b_emit[x] = b;
    for (std::int32_t a = h.parent[x]; a >= 0; a = h.parent[a])
        v.b_emit[a] +=
            b * float(h.area[x] / h.area[a] * v.weights.emit[v.weights.at(x, h.level[a])]);
}

// A |ΔB| summed over the channels.
double leaf_change(const Rgb& d, double area) {
    return (double(std::abs(d.r)) + std::abs(d.g) + std::abs(d.b)) * area;
}

// Push irradiance down and pull radiosity up in one tree; returns the node's new radiosity
// and adds Σ A |ΔB| over the leaves to \p change.
Rgb push_pull(const Hierarchy& h, NodeValues& v, std::uint32_t node, const Rgb& down_direct,
              const Rgb& down_indirect, double& change) {
    Rgb hd = down_direct + v.gathered_direct[node];
    Rgb hi = down_indirect + v.gathered_indirect[node];
    const bool weighted = !v.weights.empty();
    Rgb b;
    if (h.is_leaf(node)) {
        // The ancestors' element links by this leaf's receive weights rather than evenly: the
        // direct light by the emitters' weight, the reflected light by its own per channel.
        for (std::int32_t a = weighted ? h.parent[node] : -1; a >= 0; a = h.parent[a]) {
            const std::size_t i = v.weights.at(node, h.level[a]);
            hd += v.link_direct[a] * (v.weights.receive[i] - 1.0f);
            hi += v.link_indirect[a] * (v.weights.receive_reflected[i] - Rgb(1.0f));
        }
        b = h.emission[node] + h.reflectance[node] * (hd + hi);
        if (!v.transmitted.empty())
            b += v.transmitted[node];
        if (weighted)
            add_emit_shares(h, v, node, b);
        v.h_direct[node] = hd;
        v.h_indirect[node] = hi;
        v.b_lo[node] = v.b_hi[node] = b.max_component();
        change += leaf_change(b - v.b[node], h.area[node]);
    } else {
        Rgb sum_b, sum_hd, sum_hi;
        if (weighted)
            v.b_emit[node] = Rgb{}; // the leaves below add their shares
        v.b_lo[node] = 1e30f;
        v.b_hi[node] = 0;
        for (int c = 0; c < 4; ++c) {
            const auto child = std::uint32_t(h.first_child[node] + c);
            sum_b += push_pull(h, v, child, hd, hi, change);
            sum_hd += v.h_direct[child];
            sum_hi += v.h_indirect[child];
            v.b_lo[node] = std::min(v.b_lo[node], v.b_lo[child]);
            v.b_hi[node] = std::max(v.b_hi[node], v.b_hi[child]);
        }
        b = sum_b * 0.25f; // children have equal areas
        v.h_direct[node] = sum_hd * 0.25f;
        v.h_indirect[node] = sum_hi * 0.25f;
    }
    v.b[node] = b;
    v.b_range[node] = v.b_hi[node] - v.b_lo[node];
    return b;
}

double push_pull_root(const Hierarchy& h, NodeValues& v, const Clusters& clusters, std::size_t r) {
    double change = 0;
    const bool c = clusters.enabled;
    push_pull(h, v, std::uint32_t(r), c ? clusters.values.root_direct[r] : Rgb{},
              c ? clusters.values.root_indirect[r] : Rgb{}, change);
    return change;
}

// Radiosity of \p node pulled from its leaves (irradiances, ranges and b_emit too).
Rgb pull(const Hierarchy& h, NodeValues& v, std::uint32_t node) {
    if (h.is_leaf(node)) {
        if (!v.weights.empty())
            add_emit_shares(h, v, node, v.b[node]);
        v.b_lo[node] = v.b_hi[node] = v.b[node].max_component();
    } else {
        if (!v.weights.empty())
            v.b_emit[node] = Rgb{};
        Rgb sum, sum_hd, sum_hi;
        v.b_lo[node] = 1e30f;
        v.b_hi[node] = 0;
        for (int c = 0; c < 4; ++c) {
            const auto child = std::uint32_t(h.first_child[node] + c);
            sum += pull(h, v, child);
            sum_hd += v.h_direct[child];
            sum_hi += v.h_indirect[child];
            v.b_lo[node] = std::min(v.b_lo[node], v.b_lo[child]);
            v.b_hi[node] = std::max(v.b_hi[node], v.b_hi[child]);
        }
        v.b[node] = sum * 0.25f; // children have equal areas
        v.h_direct[node] = sum_hd * 0.25f;
        v.h_indirect[node] = sum_hi * 0.25f;
    }
    v.b_range[node] = v.b_hi[node] - v.b_lo[node];
    return v.b[node];
}

double total_of(const std::vector<double>& change) {
    double total = 0;
    for (double c : change) // in root order: the same sum for every thread count
        total += c;
    return total;
}

double relative_change(double change, double emitted) {
    return change / std::max(emitted * 3.0, 1e-300); // change is summed over 3 channels
}

} // namespace

double relative_leaf_change(const Hierarchy& h, const std::vector<Rgb>& before,
                            const std::vector<Rgb>& after, double emitted) {
    double change = 0;
    for (std::size_t n = 0; n < h.size(); ++n)
        if (h.is_leaf(std::uint32_t(n)))
            change += leaf_change(after[n] - before[n], h.area[n]);
    return relative_change(change, emitted);
}

TreeNodes tree_nodes(const Hierarchy& h) {
    TreeNodes t;
    t.start.reserve(h.root_count + 1);
    t.nodes.reserve(h.size());
    std::vector<std::uint32_t> stack;
    for (std::size_t r = 0; r < h.root_count; ++r) {
        t.start.push_back(std::uint32_t(t.nodes.size()));
        stack.assign(1, std::uint32_t(r));
        while (!stack.empty()) {
            const std::uint32_t n = stack.back();
            stack.pop_back();
            t.nodes.push_back(n);
            if (!h.is_leaf(n))
                for (int c = 3; c >= 0; --c)
                    stack.push_back(std::uint32_t(h.first_child[n] + c));
        }
    }
    t.start.push_back(std::uint32_t(t.nodes.size()));
    return t;
}

namespace {

// One Gauss–Seidel sweep by blocks of roots: each block gathers, then pushes and pulls its
// trees, before the next block gathers. Cluster links are gathered once, at the start.
double sweep_gauss_seidel(const Hierarchy& h, const LinkStore& links, NodeValues& v,
                          Clusters& clusters, const TreeNodes& trees, double emitted) {
    size_values(h, v);
    take_transmitted(h, v);
    gather_extra(h, links, v, clusters);
    const std::vector<Rgb>& b_source = sent_radiosity(h, v);
    std::vector<double> change(h.root_count, 0.0);
    for (std::size_t first = 0; first < h.root_count; first += k_gauss_seidel_block) {
        const std::size_t last = std::min(h.root_count, first + k_gauss_seidel_block);
        const std::uint32_t begin = trees.start[first], end = trees.start[last];
        parallel_for_index(end - begin, 64, [&](std::size_t i) {
            gather_node(h, links, v, b_source, trees.nodes[begin + i]);
        });
        parallel_for_index(last - first, 1, [&](std::size_t i) {
            change[first + i] = push_pull_root(h, v, clusters, first + i);
        });
    }
    if (clusters.enabled)
        pull_clusters(clusters.tree, h, v.b, clusters.values);
    return relative_change(total_of(change), emitted);
}

} // namespace

void record_pass(const Hierarchy& h, const NodeValues& v, SweepLog& log, double relative,
                 bool history) {
    ++log.total;
    if (log.stats && history)
        log.stats->residual_history.push_back(relative);
    const SolveObserver* o = log.observer;
    if (o && o->on_pass && o->every_shots > 0 && log.total % o->every_shots == 0)
        o->on_pass(root_snapshot(log.mesh, h, v), log.total, relative, false);
}

void pull_emit(const Hierarchy& h, NodeValues& v) {
    v.b_emit.assign(h.size(), Rgb{});
    parallel_for_index(h.root_count, 16, [&](std::size_t r) {
        std::vector<std::uint32_t> stack{std::uint32_t(r)};
        while (!stack.empty()) {
            const std::uint32_t n = stack.back();
            stack.pop_back();
            if (h.is_leaf(n)) {
                add_emit_shares(h, v, n, v.b[n]);
                continue;
            }
            for (int c = 3; c >= 0; --c)
                stack.push_back(std::uint32_t(h.first_child[n] + c));
        }
    });
}

void pull_all(const Hierarchy& h, NodeValues& v) {
    size_values(h, v);
    if (!v.weights.empty())
        v.b_emit.resize(h.size());
    parallel_for_index(h.root_count, 16, [&](std::size_t r) { pull(h, v, std::uint32_t(r)); });
}

double sweep_jacobi(const Hierarchy& h, const LinkStore& links, NodeValues& v, Clusters& clusters,
                    double emitted) {
    size_values(h, v);
    take_transmitted(h, v);
    gather_extra(h, links, v, clusters);
    const std::vector<Rgb>& b_source = sent_radiosity(h, v);
    parallel_for_index(h.size(), 256, [&](std::size_t q) {
        gather_node(h, links, v, b_source, std::uint32_t(q));
    });
    std::vector<double> change(h.root_count, 0.0);
    parallel_for_index(h.root_count, 16,
                       [&](std::size_t r) { change[r] = push_pull_root(h, v, clusters, r); });
    if (clusters.enabled)
        pull_clusters(clusters.tree, h, v.b, clusters.values);
    return relative_change(total_of(change), emitted);
}

Solution root_snapshot(const RadiosityMesh& mesh, const Hierarchy& h, const NodeValues& v) {
    ElementResult er;
    for (std::size_t r = 0; r < h.root_count; ++r) {
        er.radiosity.push_back(v.b[r]);
        er.h_direct.push_back(r < v.h_direct.size() ? v.h_direct[r] : Rgb{});
        er.h_indirect.push_back(r < v.h_indirect.size() ? v.h_indirect[r] : Rgb{});
    }
    return snapshot_solution(mesh, er);
}

Solved solve_links(const Hierarchy& h, const LinkStore& links, NodeValues& v, Clusters& clusters,
                   const SolverSettings& settings, Iteration iteration, double emitted,
                   SweepLog& log) {
    Solved s;
    if (iteration == Iteration::shooting) {
        s = shoot_links(h, links, v, clusters, settings, emitted, log);
        if (v.specular_transfers.empty())
            return s;
        // Shots carry nothing through the specular transfers: sweep until they settle too.
        iteration = Iteration::jacobi;
        s.relative = 1;
    }
    const TreeNodes trees = iteration == Iteration::gauss_seidel ? tree_nodes(h) : TreeNodes{};
    for (int sweeps = 0; sweeps < settings.max_sweeps && s.relative > settings.residual; ++sweeps) {
        s.relative = iteration == Iteration::gauss_seidel
                         ? sweep_gauss_seidel(h, links, v, clusters, trees, emitted)
                         : sweep_jacobi(h, links, v, clusters, emitted);
        ++s.sweeps;
        record_pass(h, v, log, s.relative, true);
    }
    s.limit_hit = s.relative > settings.residual;
    return s;
}

void release_sweep_values(NodeValues& v) {
    for (std::vector<Rgb>* a :
         {&v.gathered_direct, &v.gathered_indirect, &v.link_direct, &v.link_indirect,
          &v.extra_direct, &v.extra_indirect, &v.b_emit, &v.transmitted})
        *a = {};
    v.b_lo = {};
    v.b_hi = {};
    v.b_range = {};
}

} // namespace penumbra::solver
