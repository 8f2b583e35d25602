// Progressive shooting on the hierarchy (Southwell iteration; Cohen et al. 1988 on Hanrahan et
// al.'s links): the root tree with the most unshot power sends it through every element link
// it is the source of. Receivers keep what arrives at the node it arrives at (lazily, in
// O(1) a link) and spread it over their leaves only when their own tree shoots or the solve
// ends, so a shot costs its links, not the hierarchy.
//
// One Jacobi sweep first gives the direct light exactly (and, after a refinement, the change
// the new links make); its change of radiosity is the first unshot radiosity, all of it
// reflected light. Cluster links (point-to-point transfer through lobes) are shot in rounds:
// what the roots shot since the last round goes through them at once, as one gather of the
// increments. A last sweep leaves the radiosities as consistent as a gathering solve's.
//
// Serial: a shot touches few links, and one order of shots makes the result independent of
// the thread count.

#include <algorithm>
#include <cmath>

#include "iteration/transport.h"

namespace penumbra::solver {

namespace {

// Largest value over a fixed set of slots, updated one slot at a time (a segment tree); ties
// go to the lowest index.
class MaxTree {
public:
    explicit MaxTree(std::size_t n) {
        size_ = 1;
        while (size_ < n)
            size_ *= 2;
        value_.assign(2 * size_, -1.0);
        index_.assign(2 * size_, 0);
        for (std::size_t i = 0; i < size_; ++i)
            index_[size_ + i] = std::uint32_t(i);
        for (std::size_t p = size_ - 1; p >= 1; --p)
            combine(p);
    }
    void set(std::size_t i, double x) {
        std::size_t p = size_ + i;
        value_[p] = x;
        for (p /= 2; p >= 1; p /= 2)
            combine(p);
    }
    std::uint32_t top() const { return index_[1]; }
    double top_value() const { return value_[1]; }

private:
    void combine(std::size_t p) {
        const std::size_t l = 2 * p, r = l + 1;
        const std::size_t pick = value_[l] >= value_[r] ? l : r;
        value_[p] = value_[pick];
        index_[p] = index_[pick];
    }
    std::size_t size_ = 1;
    std::vector<double> value_;
    std::vector<std::uint32_t> index_;
};

double magnitude(const Rgb& c) {
    return std::abs(c.r) + std::abs(c.g) + std::abs(c.b);
}

class Shooter {
public:
    Shooter(const Hierarchy& h, const LinkStore& links, NodeValues& v, Clusters& clusters)
        : h_(h), links_(links), v_(v), clusters_(clusters),
          by_source_(index_by_source(h, links.links())), trees_(tree_nodes(h)),
          root_of_(h.root_of_nodes()), unshot_(h.size()), pending_link_(h.size()),
          pending_emitted_(h.size()), pending_even_(h.size()), power_(h.root_count, 0.0),
          top_(h.root_count) {
        if (clusters_.enabled)
            shot_.assign(h.size(), Rgb{});
    }

    /// The leaves' unshot radiosity: what they gained since \p before (a gathering sweep).
    void set_unshot(const std::vector<Rgb>& before) {
        for (std::size_t r = 0; r < h_.root_count; ++r) {
            double p = 0;
            for (std::uint32_t i = trees_.start[r]; i < trees_.start[r + 1]; ++i) {
                const std::uint32_t n = trees_.nodes[i];
                if (!h_.is_leaf(n))
                    continue;
                unshot_[n] = v_.b[n] - before[n];
                p += h_.area[n] * magnitude(unshot_[n]);
            }
            set_power(r, p);
        }
    }

    double unshot_power() const { return total_; }
    bool can_shoot() const { return top_.top_value() > 0; }

    void shoot_next() { shoot(top_.top()); }

    /// Sends what the roots shot since the last round through the cluster links; recomputes
    /// the total unshot power (no drift).
    void cluster_round() {
        if (clusters_.enabled && any_shot_) {
            const ClusterTree& tree = clusters_.tree;
            ClusterValues cv;
            pull_lobes(tree, h_, shot_, cv.exitance);
            planar_gradients(tree, h_, shot_, cv.gradient);
            cv.exitance_emitted.assign(tree.size(), Lobes{});
            cv.gathered_direct.assign(tree.size(), Lobes{});
            cv.gathered_indirect.assign(tree.size(), Lobes{});
            cv.root_direct.assign(h_.root_count, Rgb{});
            cv.root_indirect.assign(h_.root_count, Rgb{});
            std::vector<Rgb> direct(h_.size()), indirect(h_.size());
            gather_cluster_links(h_, *clusters_.tables, links_, shot_, cv, direct, indirect, true);
            push_clusters(tree, h_, cv);
            for (std::size_t q = 0; q < h_.size(); ++q)
                if (magnitude(indirect[q]) > 0)
                    receive(std::uint32_t(q), indirect[q], pending_even_);
            for (std::size_t r = 0; r < h_.root_count; ++r)
                if (magnitude(cv.root_indirect[r]) > 0)
                    receive(std::uint32_t(r), cv.root_indirect[r], pending_even_);
            shot_.assign(h_.size(), Rgb{});
            any_shot_ = false;
        }
        total_ = 0;
        for (double p : power_)
            total_ += p;
    }

    /// Spreads everything received over the leaves.
    void flush_all() {
        for (std::size_t r = 0; r < h_.root_count; ++r)
            flush(r);
    }

private:
    void set_power(std::size_t r, double p) {
        total_ += p - power_[r];
        power_[r] = p;
        top_.set(r, p);
    }

    // Irradiance \p e arrives at node \p q: it becomes ρ e of unshot radiosity when spread,
    // and τ e on the other side (counted here until then).
    void receive(std::uint32_t q, const Rgb& e, std::vector<Rgb>& pending) {
        pending[q] += e;
        const std::uint32_t r = root_of_[q];
        set_power(r, power_[r] +
                         h_.area[q] * magnitude((h_.reflectance[q] + h_.transmittance[q]) * e));
    }

    // Leaf x's twin passes on τ ΔH: its radiosity and its tree's unshot power grow.
    void transmit(std::uint32_t x, const Rgb& dh) {
        const std::int32_t t = h_.twin[x];
        if (t < 0 || h_.transmittance[x].is_black())
            return;
        const Rgb db = h_.transmittance[x] * dh;
        v_.b[std::uint32_t(t)] += db;
        unshot_[std::uint32_t(t)] += db;
        const std::uint32_t r = root_of_[std::uint32_t(t)];
        set_power(r, power_[r] + h_.area[std::uint32_t(t)] * magnitude(db));
    }

    // What tree r received, spread to its leaves (the links' part by the leaves' receive
    // weights) and reflected: their radiosity and unshot radiosity grow by ρ ΔH, their
    // twins' by τ ΔH.
    void flush(std::size_t r) {
        const bool weighted = !v_.weights.empty();
        const std::uint32_t begin = trees_.start[r], end = trees_.start[r + 1];
        for (std::uint32_t i = begin; i < end; ++i) {
            const std::uint32_t x = trees_.nodes[i];
            if (!h_.is_leaf(x))
                continue;
            Rgb dh = pending_even_[x] + pending_link_[x] + pending_emitted_[x];
            for (std::int32_t a = h_.parent[x]; a >= 0; a = h_.parent[a]) {
                dh += pending_even_[a];
                if (!weighted) {
                    dh += pending_link_[a] + pending_emitted_[a];
                    continue;
                }
                const std::size_t k = v_.weights.at(x, h_.level[a]);
                dh += pending_link_[a] * v_.weights.receive_reflected[k] +
                      pending_emitted_[a] * v_.weights.receive[k];
            }
            if (magnitude(dh) == 0)
                continue;
            const Rgb db = h_.reflectance[x] * dh;
            v_.b[x] += db;
            v_.h_indirect[x] += dh;
            unshot_[x] += db;
            transmit(x, dh);
        }
        for (std::uint32_t i = begin; i < end; ++i) {
            pending_even_[trees_.nodes[i]] = Rgb{};
            pending_link_[trees_.nodes[i]] = Rgb{};
            pending_emitted_[trees_.nodes[i]] = Rgb{};
        }
    }

    // Tree r's unshot radiosity through every element link its nodes are the source of (a
    // node sends its leaves' unshot radiosity by their emit weights, as gathering does).
    void shoot(std::size_t r) {
        flush(r);
        const std::uint32_t begin = trees_.start[r], end = trees_.start[r + 1];
        const bool weighted = !v_.weights.empty();
        for (std::uint32_t i = begin; i < end; ++i)
            if (!h_.is_leaf(trees_.nodes[i]))
                unshot_[trees_.nodes[i]] = Rgb{};
        for (std::uint32_t i = begin; i < end; ++i) {
            const std::uint32_t x = trees_.nodes[i];
            if (!h_.is_leaf(x))
                continue;
            for (std::int32_t a = h_.parent[x]; a >= 0; a = h_.parent[a]) {
                const double share = h_.area[x] / h_.area[a];
                const double w = weighted ? v_.weights.emit[v_.weights.at(x, h_.level[a])] : 1.0;
                unshot_[a] += unshot_[x] * float(share * w);
            }
        }
        set_power(r, 0.0);
        const std::span<const Link> all = links_.links();
        for (std::uint32_t i = begin; i < end; ++i) {
            const std::uint32_t n = trees_.nodes[i];
            const Rgb u = unshot_[n];
            if (magnitude(u) == 0)
                continue;
            const bool emits = !h_.emission[n].is_black();
            for (std::uint32_t k = by_source_.start[n]; k < by_source_.start[n + 1]; ++k) {
                const Link& l = all[by_source_.order[k]];
                receive(l.receiver, u * l.ff, emits ? pending_emitted_ : pending_link_);
            }
        }
        if (clusters_.enabled) {
            // The cluster links take each node's area mean, as gathering's pull does.
            for (std::uint32_t i = begin; i < end; ++i) {
                const std::uint32_t x = trees_.nodes[i];
                if (!h_.is_leaf(x))
                    continue;
                shot_[x] += unshot_[x];
                for (std::int32_t a = h_.parent[x]; a >= 0; a = h_.parent[a])
                    shot_[a] += unshot_[x] * float(h_.area[x] / h_.area[a]);
            }
            any_shot_ = true;
        }
        for (std::uint32_t i = begin; i < end; ++i)
            unshot_[trees_.nodes[i]] = Rgb{};
    }

    const Hierarchy& h_;
    const LinkStore& links_;
    NodeValues& v_;
    Clusters& clusters_;
    LinksBySource by_source_;
    TreeNodes trees_;
    std::vector<std::uint32_t> root_of_;
    std::vector<Rgb> unshot_;       ///< leaves: unshot radiosity; inner nodes: scratch
    std::vector<Rgb> pending_link_; ///< irradiance arrived through element links, not spread
    /// The same from emitting sources, spread by the direct light's weights (what an emitter
    /// sends after its first shot, its reflected light, is counted with it).
    std::vector<Rgb> pending_emitted_;
    std::vector<Rgb> pending_even_; ///< irradiance arrived through cluster links
    std::vector<Rgb> shot_;         ///< radiosity shot since the last cluster round (area means)
    bool any_shot_ = false;
    std::vector<double> power_; ///< per root: Σ A |unshot| (pending counted as ρ ΔH)
    double total_ = 0;
    MaxTree top_;
};

} // namespace

Solved shoot_links(const Hierarchy& h, const LinkStore& links, NodeValues& v, Clusters& clusters,
                   const SolverSettings& settings, double emitted, SweepLog& log) {
    std::vector<Rgb> before = v.b;
    before.resize(h.size());
    const double first = sweep_jacobi(h, links, v, clusters, emitted);
    record_pass(h, v, log, first, true);
    Shooter shooter(h, links, v, clusters);
    shooter.set_unshot(before);
    shooter.cluster_round();
    // Unshot power is summed over the three channels, as the sweeps' change is.
    const double target = settings.residual * std::max(emitted * 3.0, 1e-300);
    const std::int64_t max_shots =
        settings.max_shots > 0 ? settings.max_shots : 10000 * std::int64_t(h.root_count) + 100;
    const std::int64_t round = std::max<std::int64_t>(64, std::int64_t(h.root_count) / 4);
    const std::int64_t history_every = std::max<std::int64_t>(1, std::int64_t(h.root_count));
    Solved s;
    std::int64_t shots = 0;
    const SolveObserver* o = log.observer;
    while (shots < max_shots) {
        if (shooter.unshot_power() <= target || !shooter.can_shoot()) {
            shooter.cluster_round(); // what is still in flight through cluster links
            if (shooter.unshot_power() <= target || !shooter.can_shoot())
                break;
        }
        shooter.shoot_next();
        ++shots;
        if (shots % round == 0)
            shooter.cluster_round();
        const double relative = shooter.unshot_power() / std::max(emitted * 3.0, 1e-300);
        if (log.stats && shots % history_every == 0)
            log.stats->residual_history.push_back(relative);
        ++log.total;
        if (o && o->on_pass && o->every_shots > 0 && log.total % o->every_shots == 0) {
            pull_all(h, v); // a preview: light still pending in unshot trees is not in it
            o->on_pass(root_snapshot(log.mesh, h, v), log.total, relative, false);
        }
    }
    const bool stopped = shots >= max_shots && shooter.unshot_power() > target;
    shooter.cluster_round(); // what the last shots sent through cluster links
    shooter.flush_all();
    pull_all(h, v);
    if (clusters.enabled) // the cluster links' sources as the shots left them
        pull_clusters(clusters.tree, h, v.b, clusters.values);
    // A last sweep: the split into direct and indirect light and the inner nodes as a
    // gathering solve leaves them, and one more step toward the solution.
    s.relative = sweep_jacobi(h, links, v, clusters, emitted);
    record_pass(h, v, log, s.relative, true);
    s.limit_hit = stopped || s.relative > settings.residual;
    s.sweeps = int(std::min<std::int64_t>(shots, 1 << 30));
    return s;
}

} // namespace penumbra::solver
