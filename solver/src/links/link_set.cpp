// Link creation and refinement for hierarchical radiosity. Refinement is deterministic and
// parallel where it can be: decisions and form factors are computed per link in parallel,
// node subdivision happens serially in link order.

#include "links/link_set.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <span>
#include <tuple>
#include <variant>

#include <tbb/parallel_sort.h>

#include "core/parallel.h"
#include "core/rng.h"
#include "kernels/form_factor.h"
#include "sources/point_lights.h"
#include "sources/sky_light.h"
#include "sources/sun_light.h"

namespace penumbra::solver {

namespace {

enum Decision : std::uint8_t { keep = 0, split_receiver = 1, split_source = 2 };

OrientedTriangle oriented(const Hierarchy& h, std::uint32_t n) {
    return {h.triangle[n], h.normal[n]};
}

bool faces(const Hierarchy& h, std::uint32_t a, std::uint32_t b, double eps) {
    return in_front(oriented(h, a), oriented(h, b), eps) &&
           in_front(oriented(h, b), oriented(h, a), eps);
}

// A node that neither emits, reflects nor passes on light stays black.
bool can_radiate(const Hierarchy& h, std::uint32_t n) {
    return !h.emission[n].is_black() || !h.reflectance[n].is_black() ||
           !h.transmittance[n].is_black();
}

// Children of a twin are in mirrored order (the back winding is reversed): 0↔0, 1↔2, 3↔3.
constexpr int k_twin_child[4] = {0, 2, 1, 3};

} // namespace

LinkSet::LinkSet(Hierarchy& h, LinkStore& store, ClusterTables* tables,
                 const VisibilityQuery& visibility, const std::vector<PointLight>& lights,
                 const Sun* sun, const Sky* sky, RefineSettings settings)
    : h_(h), store_(store), links_(store.links_), light_links_(store.light_links_),
      offsets_(store.offsets_), cluster_links_(store.cluster_links_), tables_(tables),
      tree_(tables ? tables->tree_ : nullptr), visibility_(visibility), lights_(lights), sun_(sun),
      sky_(sky), settings_(settings) {}

Link LinkSet::make_link(std::uint32_t q, std::uint32_t p) const {
    if (centres_occluded(q, p)) // a plane between them proves them dark
        return {q, p, 0.0f, 0.0f, false};
    const OrientedTriangle a = oriented(h_, q), b = oriented(h_, p);
    const PairFormFactor pf =
        triangle_form_factor(a, b, quadrature_level_for(a, b, settings_.rows), visibility_,
                             settings_.offset, q, p, settings_.rows);
    return {q, p, float(pf.f), float(pf.f_spread), pf.partial};
}

Link LinkSet::reverse_link(const Link& l) const {
    const std::uint32_t q = l.receiver, p = l.source;
    if (l.ff <= 0)
        return {p, q, 0.0f, 0.0f, false};
    double spread = 0;
    if (std::max(h_.area[q], h_.area[p]) > settings_.min_area) { // the oracle may split it
        const OrientedTriangle a = oriented(h_, p), b = oriented(h_, q);
        spread =
            triangle_form_factor_visible(a, b, quadrature_level_for(a, b, settings_.rows)).f_spread;
    }
    return {p, q, float(double(l.ff) * h_.area[q] / h_.area[p]), float(spread), l.partial()};
}

// Sorted by unordered pair, a pair linked both ways is two neighbours: its link from the
// smaller end is computed (the finer rule the distance asks of the larger end costs more and
// is less accurate beside a small source) and the other follows by reciprocity.
void LinkSet::make_pair_links(std::size_t first, bool indexed) {
    const std::span<Link> pending = links_.span().subspan(first);
    auto key = [](const Link& l) {
        return std::tuple(std::min(l.receiver, l.source), std::max(l.receiver, l.source),
                          l.receiver);
    };
    tbb::parallel_sort(pending.begin(), pending.end(),
                       [&](const Link& x, const Link& y) { return key(x) < key(y); });
    auto reverse_of = [](const Link& x, const Link& y) {
        return x.receiver == y.source && x.source == y.receiver;
    };
    // Which links are made with the one before them, found before any is written (a pair's
    // first link writes its second).
    std::vector<std::uint8_t> second(pending.size(), 0);
    parallel_for_index(pending.size(), 1024, [&](std::size_t k) {
        second[k] = k > 0 && reverse_of(pending[k - 1], pending[k]);
    });
    parallel_for_index(pending.size(), 16, [&](std::size_t k) {
        if (second[k])
            return; // made with the link before it
        const std::uint32_t q = pending[k].receiver, p = pending[k].source;
        if (k + 1 == pending.size() || !second[k + 1]) {
            const Link* old = indexed ? store_.find_link(p, q, first) : nullptr;
            pending[k] = old ? reverse_link(*old) : make_link(q, p);
            return;
        }
        const bool q_first = h_.area[q] < h_.area[p] || (h_.area[q] == h_.area[p] && q < p);
        const Link made = q_first ? make_link(q, p) : make_link(p, q);
        const Link other = reverse_link(made);
        pending[k] = q_first ? made : other;
        pending[k + 1] = q_first ? other : made;
    });
    // Drop the links that carry nothing, in place.
    links_.resize(std::size_t(std::remove_if(links_.begin() + std::ptrdiff_t(first), links_.end(),
                                             [](const Link& l) { return !(l.ff > 0); }) -
                              links_.begin()));
}

LightLink LinkSet::make_light_link(std::uint32_t q, LightId id) const {
    const LightSource source = id.source();
    if (std::holds_alternative<SunSource>(source))
        return make_sun_link(q);
    if (std::holds_alternative<SkySource>(source))
        return make_sky_link(q);
    const std::uint32_t l = std::get<PointSource>(source).index;
    const PointLight& light = lights_[l];
    const Vec3 pos = light.position;
    LightLink link{q, id, Rgb{}, 0, 0};
    if (dot(pos - h_.triangle[q][0], h_.normal[q]) <= 0)
        return link;
    const ProfileRange profile = profile_range(light, h_.triangle[q]);
    if (profile.hi <= 0)
        return link;                 // outside a spot's cut-off
    double e_min = 1e300, e_max = 0; // cos θ / d² at the corners and the centroid
    for (const Vec3& x :
         {h_.triangle[q][0], h_.triangle[q][1], h_.triangle[q][2], h_.centroid(q)}) {
        const Vec3 d = pos - x;
        const double e = std::max(0.0, dot(d, h_.normal[q])) / std::pow(dot(d, d), 1.5);
        e_min = std::min(e_min, e);
        e_max = std::max(e_max, e);
    }
    // The spread of I·profile·cos θ / d² takes the profile's exact range over the receiver, so
    // that the oracle refines where a spot's falloff or cone edge crosses it.
    link.spread =
        float((profile.hi * e_max - profile.lo * e_min) * double(light.intensity.max_component()));
    const double omega = profile_solid_angle_triangle(light, h_.triangle[q]);
    Pcg32 rng = Pcg32::for_stream(RngPurpose::point_light_visibility, l, q, 1, settings_.rows.seed);
    const int rays = std::max(1, settings_.rows.visibility_rays);
    const int open =
        light_rays_open(pos, oriented(h_, q), settings_.offset, rays, visibility_, rng);
    const double v = double(open) / double(rays);
    // A hard cone edge (beam = cut-off) across the receiver is a boundary like a shadow's.
    const bool hard_edge =
        light.spot && light.spot->beam_deg == light.spot->cutoff_deg && profile.varies();
    link.partial = (open > 0 && open < rays) || hard_edge;
    link.irradiance = light.intensity * float(omega * v / h_.area[q]);
    return link;
}

// The sun's link: irradiance · cos θ · V, uniform over a planar receiver but for V, so its
// spread is 0 and the "variation" oracle refines it only where it is partly occluded (a
// penumbra or shadow boundary, down to min_area, as a point light's shadow); "bf" weighs its
// irradiance as a point light's.
LightLink LinkSet::make_sun_link(std::uint32_t q) const {
    const SunIrradiance s = sun_triangle_irradiance(*sun_, oriented(h_, q), settings_.offset,
                                                    h_.diagonal, q, 1, visibility_, settings_.rows);
    return {q, LightId(SunSource{}), s.irradiance, 0, std::uint8_t(s.partial ? 1 : 0)};
}

// The sky's link: its irradiance on the receiver. It is not refined: what the sky's direct
// light looks like on the mesh comes from the vertices' own gathers, and the light it
// reflects is smooth at the mesh's element size, so refining on the sky's variation would
// multiply the leaves for nothing (docs/daylight.md). Panes of glazing let the sky through
// and take none.
LightLink LinkSet::make_sky_link(std::uint32_t q) const {
    if (!h_.opaque[q])
        return {q, LightId(SkySource{}), Rgb{}, 0, 0};
    return {q, LightId(SkySource{}),
            sky_triangle_irradiance(*sky_, oriented(h_, q), settings_.offset, h_.diagonal, q,
                                    visibility_, settings_.rows.seed),
            0, 0};
}

bool LinkSet::linkable(std::uint32_t q, std::uint32_t p) const {
    return p != q && h_.twin[q] != std::int32_t(p) && can_radiate(h_, p) &&
           faces(h_, q, p, 1e-9 * h_.diagonal);
}

void LinkSet::check_growth(std::size_t element_links, std::size_t cluster_links, const char* when,
                           std::string_view advice) const {
    check_system_memory(settings_.max_memory_bytes,
                        {h_.size(), element_links, cluster_links, light_links_.size()}, when,
                        advice);
}

// Every pair of r roots may be linked: when r² links would not fit, they are counted first
// (a second pass of the cheap tests), so that a mesh far too large to link without clusters
// is refused before its links are made.
void LinkSet::check_root_links() const {
    const std::size_t r = h_.root_count;
    if (settings_.max_memory_bytes == 0 ||
        system_bytes({h_.size(), r * r, 0, 0}) <= double(settings_.max_memory_bytes))
        return;
    std::vector<std::size_t> count(r, 0);
    parallel_for_index(r, 4, [&](std::size_t q) {
        for (std::uint32_t p = 0; p < r; ++p)
            count[q] += linkable(std::uint32_t(q), p) ? 1 : 0;
    });
    check_growth(std::accumulate(count.begin(), count.end(), std::size_t(0)), 0,
                 "linking every pair of elements (without clusters)",
                 "use --clustering on (solver.clustering) or a larger --max-edge");
}

void LinkSet::link_roots() {
    const std::size_t r = h_.root_count;
    check_root_links();
    std::vector<std::vector<Link>> per_receiver(r);
    parallel_for_index(r, 4, [&](std::size_t q) {
        for (std::uint32_t p = 0; p < r; ++p)
            if (linkable(std::uint32_t(q), p))
                per_receiver[q].emplace_back(std::uint32_t(q), p, 0.0f, 0.0f, false);
    });
    links_.clear();
    for (auto& v : per_receiver)
        for (const Link& l : v)
            links_.push_back(l);
    make_pair_links(0, false);
    link_lights();
    sort_and_index();
}

void LinkSet::restore(std::span<const Link> links, std::span<const ClusterLink> cluster_links) {
    links_.assign(links);
    cluster_links_.assign(cluster_links);
    link_lights();
    sort_and_index();
}

void LinkSet::link_lights() {
    const std::size_t r = h_.root_count;
    light_links_.clear();
    std::vector<LightId> lights;
    for (std::uint32_t l = 0; l < lights_.size(); ++l)
        lights.emplace_back(PointSource{l});
    if (sun_)
        lights.emplace_back(SunSource{}); // the sun after the point lights
    if (sky_)
        lights.emplace_back(SkySource{});
    for (const LightId light : lights) {
        std::vector<LightLink> made(r);
        parallel_for_index(
            r, 64, [&](std::size_t q) { made[q] = make_light_link(std::uint32_t(q), light); });
        for (const LightLink& link : made)
            if (!link.irradiance.is_black())
                light_links_.push_back(link);
    }
}

void LinkSet::subdivide(std::uint32_t node, std::vector<Rgb>& b, std::vector<float>& b_range) {
    if (!h_.is_leaf(node))
        return;
    // Front and back sides subdivide together so that their leaves stay twins.
    const std::int32_t t = h_.twin[node];
    for (std::uint32_t n : {node, t >= 0 ? std::uint32_t(t) : node}) {
        if (!h_.is_leaf(n))
            continue;
        h_.subdivide(n);
        const Rgb parent_value = b[n];
        const float parent_range = b_range[n];
        for (int c = 0; c < 4; ++c) {
            b.push_back(parent_value);
            b_range.push_back(parent_range);
        }
    }
    if (t >= 0) {
        for (int c = 0; c < 4; ++c) {
            std::uint32_t mine = std::uint32_t(h_.first_child[node] + c);
            std::uint32_t theirs =
                std::uint32_t(h_.first_child[std::uint32_t(t)] + k_twin_child[c]);
            h_.twin[mine] = std::int32_t(theirs);
            h_.twin[theirs] = std::int32_t(mine);
        }
    }
}

bool LinkSet::refine_pass(std::vector<Rgb>& b, std::vector<float>& b_range) {
    kept_.resize(links_.size(), 0); // links cluster refinement added are new
    std::vector<std::uint8_t> decision(links_.size(), keep);
    parallel_for_index(links_.size(), 256, [&](std::size_t k) {
        if (kept_[k])
            return;
        const Link& link = links_[k];
        const double aq = h_.area[link.receiver], ap = h_.area[link.source];
        const OracleSettings s =
            oracle::receiver_settings(settings_, h_.specular_only[link.receiver] != 0);
        if (!oracle::refine_element_link(s, link, double(b[link.source].max_component()),
                                         double(b_range[link.source]), aq, ap))
            return;
        decision[k] = aq >= ap ? split_receiver : split_source;
    });
    if (std::none_of(decision.begin(), decision.end(), [](std::uint8_t d) { return d != keep; })) {
        kept_.assign(links_.size(), 1);
        return false;
    }
    for (std::size_t k = 0; k < links_.size(); ++k)
        if (decision[k] != keep)
            subdivide(decision[k] == split_receiver ? links_[k].receiver : links_[k].source, b,
                      b_range);
    const auto split_count = std::size_t(
        std::count_if(decision.begin(), decision.end(), [](std::uint8_t d) { return d != keep; }));
    check_growth(links_.size() + 3 * split_count, cluster_links_.size(),
                 "a refinement pass of the element links");
    // In place (the biggest refinements of a large scene make tens of millions of links):
    // the kept links move to the front, and the parts of the split links, made after, follow
    // them. A pair split both ways (each link splits its larger end) makes its parts' links
    // both ways. Each casts its own rays: the parts of a pair whose few probes were all open
    // are not all visible (a floor triangle's part under a desk), and taking them as such
    // made the closed 3x3 office floor gain 1.5 % of its power.
    struct Split {
        std::uint32_t receiver, source;
        std::uint8_t decision;
    };
    std::vector<Split> splits;
    std::size_t kept = 0;
    for (std::size_t k = 0; k < links_.size(); ++k) {
        if (decision[k] == keep)
            links_[kept++] = links_[k];
        else
            splits.push_back({links_[k].receiver, links_[k].source, decision[k]});
    }
    links_.resize(kept);
    links_.reserve(kept + 4 * splits.size());
    for (const Split& l : splits)
        for (int c = 0; c < 4; ++c) {
            const std::uint32_t q = l.decision == split_receiver
                                        ? std::uint32_t(h_.first_child[l.receiver] + c)
                                        : l.receiver;
            const std::uint32_t p = l.decision == split_receiver
                                        ? l.source
                                        : std::uint32_t(h_.first_child[l.source] + c);
            if (faces(h_, q, p, 1e-9 * h_.diagonal)) // a part may lie behind the other end
                links_.emplace_back(q, p, 0.0f, 0.0f, false);
        }
    splits = {};
    make_pair_links(kept, false);
    kept_.assign(links_.size(), 0);
    std::fill(kept_.begin(), kept_.begin() + std::ptrdiff_t(kept), std::uint8_t(1));
    return true;
}

bool LinkSet::refine_light_pass(std::vector<Rgb>& b, std::vector<float>& b_range) {
    std::vector<std::uint8_t> split(light_links_.size(), 0);
    parallel_for_index(light_links_.size(), 256, [&](std::size_t k) {
        const LightLink& l = light_links_[k];
        split[k] = oracle::refine_light_link(
            oracle::receiver_settings(settings_, h_.specular_only[l.receiver] != 0), l,
            h_.area[l.receiver]);
    });
    if (std::none_of(split.begin(), split.end(), [](std::uint8_t s) { return s != 0; }))
        return false;
    for (std::size_t k = 0; k < light_links_.size(); ++k)
        if (split[k])
            subdivide(light_links_[k].receiver, b, b_range);
    std::vector<LightLink> next;
    std::vector<std::size_t> fresh;
    for (std::size_t k = 0; k < light_links_.size(); ++k) {
        if (!split[k]) {
            next.push_back(light_links_[k]);
            continue;
        }
        for (int c = 0; c < 4; ++c) {
            fresh.push_back(next.size());
            next.push_back({std::uint32_t(h_.first_child[light_links_[k].receiver] + c),
                            light_links_[k].light, Rgb{}, 0, 0});
        }
    }
    parallel_for_index(fresh.size(), 16, [&](std::size_t f) {
        LightLink& l = next[fresh[f]];
        l = make_light_link(l.receiver, l.light);
    });
    next.erase(std::remove_if(next.begin(), next.end(),
                              [](const LightLink& l) { return l.irradiance.is_black(); }),
               next.end());
    light_links_.swap(next);
    return true;
}

bool LinkSet::refine(std::vector<Rgb>& b, std::vector<float>& b_range,
                     const std::function<void(const RefinePass&)>& on_pass) {
    kept_.assign(links_.size(), 0); // radiosities have changed since the last refine()
    cluster_kept_.assign(cluster_links_.size(), 0);
    bool changed = false;
    int passes = 0;
    auto report = [&](const char* kind) {
        if (on_pass)
            on_pass({kind, ++passes, links_.size(), cluster_links_.size(), light_links_.size(),
                     h_.size()});
    };
    while (refine_light_pass(b, b_range)) {
        changed = true;
        report("light");
    }
    if (tree_)
        tables_->weigh_sources(b);
    const std::size_t first_pending = links_.size();
    while (tree_ && refine_cluster_pass(b, b_range)) {
        changed = true;
        report("cluster");
    }
    make_pair_links(first_pending, true);
    while (refine_pass(b, b_range)) {
        changed = true;
        report("element");
    }
    if (changed) // the links are kept sorted and indexed: only changes need it again
        sort_and_index();
    // Read within one refine() only: a byte per link (170 M of them on the 1M floor).
    kept_ = {};
    cluster_kept_ = {};
    return changed;
}

} // namespace penumbra::solver
