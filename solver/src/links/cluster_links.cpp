// Cluster links of hierarchical radiosity (see hierarchy/cluster_tree.h): creation, visibility and
// refinement. Refinement starts from the top cluster's link to itself; a cluster's self-link
// is split into links between all pairs of its children (and their own self-links) once the
// cluster carries light; other cluster links are split while the oracle's estimate of their
// error exceeds the threshold, at the cluster end of a cluster–element link, else at the
// larger end. Pairs of elements become ordinary links.
//
// Oracle (its estimates and constants: oracle/oracle.h): a pair whose bounding radii sum to
// half their distance or more is always split (the point model fails there, whatever the
// rays say); otherwise the irradiance the link brings to a surface facing the source (by the
// larger of the centres' point kernel and the link's own calibrated one), times the relative
// error of the point approximation (2 × the bounding radii over the distance) where it is visible,
// plus the uncertainty of its visibility: all of it for partly occluded links, 1/n for links all n
// of whose rays were blocked (n blocked rays cannot tell 0 from about 1/n). The irradiance counts
// what the source emits in full and what it reflects divided by k_reflected_slack. Such a
// link is first given more rays (up to 64), which is far cheaper than splitting it: the parts
// of a wall-separated pair are occluded again, and splitting the receiver does not lower the
// irradiance in question.
//
// Before that, a link whose first rays were all blocked is offered to the planes they hit
// (visibility/occluders.h): a plane with the link's ends on its two sides whose surfaces cover the
// shaft's cross-section proves it dark, and the link is dropped. On the office floors most
// blocked links cross a partition (docs/calibration.md#occlusion-certificates).

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <tuple>

#include <tbb/parallel_sort.h>

#include "core/parallel.h"
#include "kernels/form_factor.h"
#include "links/link_set.h"

namespace penumbra::solver {

namespace {

constexpr int k_cluster_rays = 4;
constexpr int k_facing_tries = 8;
/// Largest factor the true cosines may scale a cluster link's kernel by (cast_cluster_rays).
constexpr double k_max_calibration = 4.0;
/// An all-blocked link's rays traced to their first hits before the rest (certified_blocked).
constexpr std::size_t k_first_certifying_rays = 4;

enum ClusterDecision : std::uint8_t { keep = 0, split_receiver, split_source, split_self };

} // namespace

template <typename Fn> void LinkSet::for_each_child(NodeRef n, Fn&& fn) const {
    if (is_cluster(n)) {
        const std::uint32_t c = cluster_index(n);
        for (std::uint32_t k = tree_->child_begin[c]; k < tree_->child_begin[c + 1]; ++k)
            fn(tree_->children[k]);
        return;
    }
    for (int c = 0; c < 4; ++c)
        fn(NodeRef(h_.first_child[n] + c));
}

Vec3 LinkSet::node_centre(NodeRef n) const {
    return is_cluster(n) ? tree_->centre(cluster_index(n)) : h_.centroid(n);
}

double LinkSet::node_area(NodeRef n) const {
    return is_cluster(n) ? tree_->area[cluster_index(n)] : h_.area[n];
}

double LinkSet::node_radius(NodeRef n) const {
    if (is_cluster(n))
        return tree_->radius(cluster_index(n));
    const Vec3 c = h_.centroid(n);
    double r = 0;
    for (const Vec3& v : h_.triangle[n])
        r = std::max(r, length(v - c));
    return r;
}

bool LinkSet::splittable(NodeRef n, bool exact) const {
    if (is_cluster(n))
        return !exact || tree_->area[cluster_index(n)] > settings_.min_area;
    return !h_.is_leaf(n) || h_.area[n] > settings_.min_area;
}

Vec3 LinkSet::sample_facing_point(NodeRef n, const Vec3& toward, Pcg32& rng, Vec3& normal,
                                  const std::vector<double>& running) const {
    if (!is_cluster(n)) {
        normal = h_.normal[n];
        return sample_triangle(h_.triangle[n], rng.next_double(), rng.next_double());
    }
    // A root below the cluster, chosen by its weight in \p running (a running sum over the
    // roots in depth-first order), until one faces \p toward (a property of its plane, so no
    // point is drawn for the others).
    const std::uint32_t c = cluster_index(n);
    for (int attempt = 0; attempt < k_facing_tries; ++attempt) {
        const std::size_t k = draw_root(c, rng.next_double(), running);
        if (dot(toward, tables_->dfs_plane_[k].n) <= tables_->dfs_plane_[k].d) {
            // A face cluster's roots share its plane (to its grouping's tolerance): none of
            // the others would face it either, but for an end within that tolerance of the
            // plane (a grazing transfer). The stream skips their draws, as if they had been
            // made.
            if (tree_->planar[c]) {
                rng.advance(k_facing_tries - 1 - attempt);
                break;
            }
            continue;
        }
        const std::uint32_t e = tables_->dfs_roots_[k];
        normal = h_.normal[e];
        return sample_triangle(h_.triangle[e], rng.next_double(), rng.next_double());
    }
    normal = Vec3{};
    return Vec3{};
}

std::size_t LinkSet::draw_root(std::uint32_t c, double u,
                               const std::vector<double>& running) const {
    const std::uint32_t begin = tables_->root_begin_[c], end = tables_->root_end_[c];
    const double x = running[begin] + u * (running[end] - running[begin]);
    // The first root whose running sum passes x: in [lo, hi) of running. Roots' weights vary
    // smoothly in depth-first order, so the search gallops out from where x would be were
    // they equal: a binary search over a large cluster's range missed the cache at most
    // steps (draw_root and its caller took a tenth of the proxy's solve;
    // docs/calibration.md#speed).
    const std::size_t n = end - begin;
    if (n <= 1)
        return begin;
    std::size_t lo = begin + 1, hi = std::size_t(end) + 1;
    const std::size_t guess = lo + std::min(n - 1, std::size_t(u * double(n)));
    if (running[guess] > x) {
        hi = guess;
        for (std::size_t step = 1; guess - lo >= step; step *= 2) {
            if (!(running[guess - step] > x)) {
                lo = guess - step + 1;
                break;
            }
            hi = guess - step;
        }
    } else {
        lo = guess + 1;
        for (std::size_t step = 1; guess + step < hi; step *= 2) {
            if (running[guess + step] > x) {
                hi = guess + step;
                break;
            }
            lo = guess + step + 1;
        }
    }
    const auto it = std::upper_bound(running.begin() + std::ptrdiff_t(lo),
                                     running.begin() + std::ptrdiff_t(hi), x);
    return std::size_t(
        std::clamp<std::ptrdiff_t>(it - running.begin() - 1, begin, std::ptrdiff_t(end) - 1));
}

bool LinkSet::faces_box(std::uint32_t c, NodeRef other) const {
    Vec3 lo, hi;
    if (is_cluster(other)) {
        lo = tree_->lo[cluster_index(other)];
        hi = tree_->hi[cluster_index(other)];
    } else {
        lo = hi = h_.triangle[other][0];
        for (const Vec3& v : h_.triangle[other]) {
            lo = min(lo, v);
            hi = max(hi, v);
        }
    }
    // A lobe +a can see the other node if some of it lies beyond the cluster's low side.
    const double eps = 1e-9 * h_.diagonal;
    for (std::size_t a = 0; a < 3; ++a) {
        if (tables_->area_lobes_[c][2 * a].max_component() > 0 && hi[a] > tree_->lo[c][a] + eps)
            return true;
        if (tables_->area_lobes_[c][2 * a + 1].max_component() > 0 && lo[a] < tree_->hi[c][a] - eps)
            return true;
    }
    return false;
}

ClusterLink LinkSet::make_cluster_link(NodeRef q, NodeRef p) const {
    ClusterLink link;
    link.receiver = q;
    link.source = p;
    if (q == p) {
        link.self = 1;
        return link;
    }
    if (planar_end(q) && planar_end(p) && exact_source(p))
        return make_exact_link(q, p);
    const Vec3 cq = node_centre(q), cp = node_centre(p);
    const double rq = node_radius(q), rp = node_radius(p);
    const Vec3 delta = cp - cq;
    const double r = length(delta);
    const Vec3 d = r > 0 ? delta / r : Vec3(0, 0, 1);
    const double eps = 1e-9 * h_.diagonal;
    // An element sees nothing of a node wholly behind its plane, nor lights it.
    if (!is_cluster(q) && dot(cp - h_.triangle[q][0], h_.normal[q]) + rp <= eps)
        return link;
    if (!is_cluster(p) && dot(cq - h_.triangle[p][0], h_.normal[p]) + rq <= eps)
        return link;
    if (is_cluster(q) && !faces_box(cluster_index(q), p))
        return link;
    if (is_cluster(p) && !faces_box(cluster_index(p), q))
        return link;
    link.d = Vec3f(d);
    // A pair too close for a point is split by the oracle at once: its rays would be wasted.
    // Only the segment between its centres is traced, both ways, for a plane that may prove
    // it dark (which spares the links its parts would make: most pairs across a partition
    // are close ones). Otherwise no ray can be cast only where no surface of an end faces the
    // other.
    const bool near = !oracle::admissible(r, rq + rp);
    if (near && centres_occluded(q, p))
        return link; // carries nothing: the refinement drops it
    if (near || !cast_cluster_rays(link, k_cluster_rays)) {
        const double closest = 0.25 * (rq + rp), reach = std::max(r, closest);
        link.g = float(1.0 / (k_pi * reach * reach));
        link.set_visible(1.0);
    }
    return link;
}

// The distance term 1/(π d²) is averaged over the rays' end points (the point kernel at the
// centres alone underestimates it: the mean of 1/d² exceeds 1/r²), bounded where the nodes
// nearly touch: such links carry light only while the oracle finds it negligible. g · v is
// the mean over the rays of V / (π d²); g alone the mean over the open rays (over all while
// none is open, which is what the link's g holds then).
//
// The lobe model gives each end the cosine of the centres' direction, where the light of a
// pair of near planar clusters (a floor and a wall by their common edge) travels at other
// angles: g is scaled by the open rays' mean true kernel cos_q cos_p / (π d²) over their mean
// 1/(π d²) times their mean product of the model's cosines (at most k_max_calibration, where
// the centres' direction grazes an end). With planar clusters this cuts the power error of a
// closed room several times (docs/calibration.md#calibrated-lobe-kernels).
bool LinkSet::cast_cluster_rays(ClusterLink& link, int count) const {
    const NodeRef q = link.receiver, p = link.source;
    const Vec3 cq = node_centre(q), cp = node_centre(p);
    const double closest = 0.25 * (node_radius(q) + node_radius(p));
    Pcg32 rng =
        Pcg32::for_stream(RngPurpose::cluster_visibility, q, p, link.rays, settings_.rows.seed);
    const double rc = length(cp - cq);
    const Vec3 dc = rc > 0 ? (cp - cq) / rc : Vec3(0, 0, 1);
    // Per ray: the point kernel 1/(π d²), the true one (cos_q cos_p / (π d²)) and the cosines'
    // product the lobe model gives the two ends along the centres' direction. Called for
    // every new cluster link: no allocation per call (nothing below starts parallel work).
    thread_local std::vector<Segment> segments;
    thread_local std::vector<double> kernel, true_kernel, model_cosines;
    thread_local std::vector<std::uint8_t> blocked;
    thread_local std::vector<std::int32_t> hits;
    segments.clear();
    kernel.clear();
    true_kernel.clear();
    model_cosines.clear();
    hits.clear();
    for (int k = 0; k < count; ++k) {
        Vec3 nq, np;
        const Vec3 xq = sample_facing_point(q, cp, rng, nq, tables_->dfs_area_);
        const Vec3 xp = sample_facing_point(p, cq, rng, np, tables_->dfs_exitance_);
        if (nq == Vec3{} || np == Vec3{})
            continue; // no surface of a cluster faces the other end
        const Vec3 from = xq + nq * settings_.offset, to = xp + np * settings_.offset;
        segments.push_back({Vec3f(from), Vec3f(to - from), 0.0f, 1.0f});
        const double dd = std::max(dot(xp - xq, xp - xq), closest * closest);
        kernel.push_back(1.0 / (k_pi * dd));
        const double length_qp = length(xp - xq);
        const Vec3 w = length_qp > 0 ? (xp - xq) / length_qp : dc;
        true_kernel.push_back(std::max(0.0, dot(nq, w)) * std::max(0.0, -dot(np, w)) / (k_pi * dd));
        model_cosines.push_back(std::max(0.0, dot(nq, dc)) * std::max(0.0, -dot(np, dc)));
    }
    if (segments.empty())
        return link.rays > 0;
    // A link's first rays name what they hit: the planes that may block it all.
    blocked.assign(segments.size(), 0);
    if (link.rays == 0) {
        hits.resize(segments.size());
        visibility_.first_hit(segments, hits);
        for (std::size_t k = 0; k < segments.size(); ++k)
            blocked[k] = hits[k] != -1;
    } else {
        visibility_.occluded(segments, blocked);
    }
    const double before = double(link.rays);
    double open = std::round(double(link.visible()) * before); // a count of rays
    double g_open = open > 0 ? double(link.g) * open : 0.0;
    double g_all = open > 0 ? 0.0 : double(link.g) * before; // only read while none is open
    const bool first_open = open == 0; // the kernel is calibrated over the first open rays
    double true_open = 0, cosines_open = 0;
    for (std::size_t k = 0; k < segments.size(); ++k) {
        g_all += kernel[k];
        if (!blocked[k]) {
            open += 1;
            g_open += kernel[k];
            true_open += true_kernel[k];
            cosines_open += model_cosines[k];
        }
    }
    if (first_open && g_open > 0 && cosines_open > 0)
        g_open *= std::min(k_max_calibration, open * true_open / (g_open * cosines_open));
    const double total = before + double(segments.size());
    if (open == 0 && !hits.empty()) {
        if (certified_blocked(link.receiver, link.source, segments, hits, true)) {
            link.rays = std::uint16_t(total);
            link.g = 0.0f; // carries nothing: the refinement drops it
            link.set_visible(0.0);
            return true;
        }
    }
    link.rays = std::uint16_t(total);
    link.set_visible(open / total);
    link.g = float(open > 0 ? g_open / open : g_all / total);
    link.partial = open > 0 && open < total;
    return true;
}

bool LinkSet::shaft_end(NodeRef n, NodeRef other, std::uint32_t plane, double side,
                        std::vector<Vec3>& points) const {
    const double tol = tables_->occluders_.tolerance();
    const Vec3& normal = tables_->occluders_.normal(plane);
    auto beyond = [&](const Vec3& x) { return side * tables_->occluders_.distance(plane, x); };
    if (!is_cluster(n)) {
        const bool faces_other = side * dot(h_.normal[n], normal) < -k_lobe_component;
        // Of an element, only the part in front of an element at the other end exchanges
        // light with it (a ceiling panel and the side of a desk top below it: the part of the
        // panel behind the side's plane would see past the desk's edge).
        std::array<Vec3, 4> clipped;
        std::size_t count = 0;
        if (is_cluster(other)) {
            for (const Vec3& v : h_.triangle[n])
                clipped[count++] = v;
        } else {
            count = clip_to_half_space(h_.triangle[other][0], h_.normal[other],
                                       h_.triangle[n].data(), 3, clipped.data());
        }
        if (count < 3)
            return false; // nothing of it faces the other end
        for (std::size_t k = 0; k < count; ++k) {
            const double d = beyond(clipped[k]);
            if (d < -tol || (faces_other && d <= tol))
                return false;
            points.push_back(clipped[k]);
        }
        return true;
    }
    const std::uint32_t c = cluster_index(n);
    // A box flat along an axis (a face cluster's in an axis plane) has half the corners:
    // the shaft's hull is made of the crossings of every pair of the two ends' points.
    auto corners = [](const Vec3& lo, const Vec3& hi, auto&& fn) {
        const int flat = (lo.x == hi.x ? 1 : 0) | (lo.y == hi.y ? 2 : 0) | (lo.z == hi.z ? 4 : 0);
        for (int k = 0; k < 8; ++k)
            if ((k & flat) == 0)
                fn(Vec3(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z));
    };
    bool on_side = true;
    corners(tree_->lo[c], tree_->hi[c], [&](const Vec3& x) {
        on_side = on_side && beyond(x) >= -tol;
        points.push_back(x);
    });
    if (!on_side)
        return false;
    // A surface facing the other side has a normal component of sign −sign(side · n_a) along
    // some axis a: all of that lobe's bounds must lie strictly on this side.
    for (std::size_t a = 0; a < 3; ++a) {
        if (std::abs(normal[a]) <= k_lobe_component)
            continue;
        const auto& box =
            tables_->lobe_bounds_[c][std::size_t(lobe_index(int(a), -side * normal[a]))];
        if (box[0] > box[3])
            continue; // no such surface
        corners(Vec3(box[0], box[1], box[2]), Vec3(box[3], box[4], box[5]),
                [&](const Vec3& x) { on_side = on_side && beyond(x) > tol; });
    }
    return on_side;
}

bool LinkSet::certified_blocked(NodeRef q, NodeRef p, std::vector<Segment>& segments,
                                std::vector<std::int32_t>& hits, bool traced) const {
    // The rays' first hits name the planes to try, a few rays before the rest: one wall
    // blocks most dark pairs, and the first rays' hits name it. Any plane that blocks proves
    // the pair dark, so the answer does not depend on the order; one that failed fails again
    // (the test depends on q, p and the plane alone), so each is tried once.
    thread_local std::vector<std::uint32_t> tried;
    tried.clear();
    const std::size_t n = segments.size(), few = std::min(n, k_first_certifying_rays);
    auto trace_and_try = [&](std::size_t begin, std::size_t end) {
        if (begin == end)
            return false;
        const std::span<std::int32_t> part(hits.data() + begin, end - begin);
        visibility_.first_hit(std::span<const Segment>(segments).subspan(begin, end - begin), part);
        return certified_occluded(q, p, part, tried);
    };
    hits.resize(n);
    if (traced ? certified_occluded(q, p, hits, tried)
               : trace_and_try(0, few) || trace_and_try(few, n))
        return true;
    // The first hits from the source's end: a wall behind its furniture.
    for (Segment& s : segments)
        s = {s.origin + s.direction, s.direction * -1.0f, s.tnear, s.tfar};
    return trace_and_try(0, few) || trace_and_try(few, n);
}

bool LinkSet::centres_occluded(NodeRef q, NodeRef p) const {
    if (!tables_ || tables_->occluders_.size() == 0)
        return false;
    const Vec3 cq = node_centre(q), cp = node_centre(p);
    // Off the ends themselves: an element's centre lies on its own plane.
    constexpr float lo = 1e-4f, hi = 1.0f - 1e-4f;
    // From q's end, then from p's where what q's end hits first does not block: a segment
    // open one way is open the other.
    const Segment both[2] = {{Vec3f(cq), Vec3f(cp - cq), lo, hi},
                             {Vec3f(cp), Vec3f(cq - cp), lo, hi}};
    thread_local std::vector<std::uint32_t> tried;
    tried.clear();
    for (const Segment& s : both) {
        std::int32_t hit = -1;
        visibility_.first_hit({&s, 1}, {&hit, 1});
        if (hit == -1)
            return false;
        if (certified_occluded(q, p, {&hit, 1}, tried))
            return true;
    }
    return false;
}

bool LinkSet::certified_occluded(NodeRef q, NodeRef p, std::span<const std::int32_t> hits,
                                 std::vector<std::uint32_t>& tried) const {
    if (!tables_ || tables_->occluders_.size() == 0)
        return false;
    // Called for most new pairs: no allocation per call.
    thread_local std::vector<Vec3> a, b;
    const Vec3 cq = node_centre(q), cp = node_centre(p);
    for (const std::int32_t e : hits) {
        if (e < 0 || std::size_t(e) >= h_.root_count)
            continue;
        const std::uint32_t plane = tables_->occluders_.plane_of_root(std::uint32_t(e));
        if (std::find(tried.begin(), tried.end(), plane) != tried.end())
            continue;
        tried.push_back(plane);
        const double dq = tables_->occluders_.distance(plane, cq),
                     dp = tables_->occluders_.distance(plane, cp);
        if (dq * dp >= 0)
            continue; // the centres are not on its two sides
        const double side = dq > 0 ? 1.0 : -1.0;
        a.clear();
        b.clear();
        if (shaft_end(q, p, plane, side, a) && shaft_end(p, q, plane, -side, b) &&
            tables_->occluders_.blocks(plane, a, b))
            return true;
    }
    return false;
}

LinkSet::PairGeometry LinkSet::pair_geometry(const ClusterLink& link) const {
    return {length(node_centre(link.source) - node_centre(link.receiver)),
            node_radius(link.receiver) + node_radius(link.source)};
}

double LinkSet::cluster_link_error(const ClusterLink& link, const std::vector<Rgb>& b) const {
    if (link.self)
        return oracle::self_link_error((*tables_->peak_)[cluster_index(link.receiver)]);
    const PairGeometry g = pair_geometry(link);
    if (!oracle::admissible(g.r, g.radii)) // too close for a point: split, whatever its rays said
        return std::numeric_limits<double>::infinity();
    return oracle::lobe_link_error(link, g.r, g.radii, weighed_irradiance(link, b, g));
}

double LinkSet::weighed_irradiance(const ClusterLink& link, const std::vector<Rgb>& b,
                                   const PairGeometry& g) const {
    // Σ B A cos toward the receiver, relaxed by the angle the pair subtends: over a wide
    // angle the direction between the parts differs from the centres' (a lamp in one half of a
    // cluster pair radiates down onto the floor of the other half, not sideways).
    const double spread = g.r > 0 ? std::min(1.0, g.radii / g.r) : 1.0;
    const double all = intensity_toward(link, *tables_->exitance_, b, spread);
    const double direct = intensity_toward(link, *tables_->emitted_, h_.emission, spread);
    const double weighed = oracle::weighed_intensity(all, direct);
    const double r_floor = 1e-6 * h_.diagonal; // coincident centres: refine, without overflow
    const double point = 1.0 / (k_pi * std::max(g.r * g.r, r_floor * r_floor));
    // A link with open rays brings its own kernel g (calibrated to the true cosines, which may
    // exceed the centres' point kernel): the oracle weighs the larger.
    return weighed * (link.visible() > 0 ? std::max(point, double(link.g)) : point);
}

double LinkSet::intensity_toward(const ClusterLink& link, const std::vector<Lobes>& lobes,
                                 const std::vector<Rgb>& element, double spread) const {
    const NodeRef p = link.source;
    const Vec3 d(link.d);
    if (is_cluster(p)) {
        const Lobes& l = lobes[cluster_index(p)];
        double widest = 0;
        for (const Rgb& lobe : l)
            widest = std::max(widest, double(lobe.max_component()));
        return double(lobe_projection(l, -d).max_component()) + spread * widest;
    }
    const double cosine = std::clamp(dot(h_.normal[p], -d) + spread, 0.0, 1.0);
    return double(element[p].max_component()) * h_.area[p] * cosine;
}

// An all-blocked link above the threshold only for its visibility's uncertainty gets as many
// rays as would bring that uncertainty under the threshold (oracle::resample_rays): one
// link's rays settle what would otherwise be split level after level (splitting its receiver
// does not lower the irradiance it might bring).
bool LinkSet::resample_occluded(const std::vector<Rgb>& b) {
    std::vector<std::uint8_t> changed(cluster_links_.size(), 0);
    parallel_for_index(cluster_links_.size(), 256, [&](std::size_t k) {
        // A link kept by an earlier pass of this refine() got the rays it asked for then (but
        // for draws that found no facing surface, made up at the next refine()), and the
        // radiosities have not changed since: every pass walked every link here (80 M
        // links, about 30 passes a cycle on the 1M floor; docs/calibration.md#speed).
        ClusterLink& l = cluster_links_[k];
        if (cluster_kept_[k] || l.self || l.exact || l.visible() > 0 || l.rays == 0 ||
            l.rays >= oracle::k_max_cluster_rays)
            return;
        const double open = weighed_irradiance(l, b, pair_geometry(l));
        const double wanted = oracle::resample_rays(settings_, open, l.rays);
        if (wanted == 0)
            return;
        const std::uint16_t before = l.rays;
        cast_cluster_rays(l, int(wanted) - int(l.rays));
        changed[k] = l.rays > before; // no end faced the other: nothing to add
        if (changed[k])
            cluster_kept_[k] = 0; // weighed anew
    });
    return std::any_of(changed.begin(), changed.end(), [](std::uint8_t c) { return c != 0; });
}

bool LinkSet::refine_cluster_pass(std::vector<Rgb>& b, std::vector<float>& b_range) {
    const bool resampled = resample_occluded(b);
    std::vector<std::uint8_t> decision(cluster_links_.size(), keep);
    parallel_for_index(cluster_links_.size(), 256, [&](std::size_t k) {
        const ClusterLink& l = cluster_links_[k];
        if (cluster_kept_[k])
            return;
        const OracleSettings s =
            oracle::receiver_settings(settings_, tables_->specular_only(l.receiver));
        const bool over = l.exact ? oracle::refine_exact_link(s, exact_link_error(l, b, b_range),
                                                              tables_->emits(l.source))
                                  : oracle::refine_lobe_link(s, cluster_link_error(l, b));
        if (!over)
            return;
        if (l.self) {
            decision[k] = split_self;
            return;
        }
        // An exact link splits its larger end, as an element link does. A lobe link splits
        // the cluster end of a cluster–element link (element pairs get the exact form factor
        // and the element oracle), else the larger end.
        const NodeRef q = l.receiver, p = l.source;
        const bool sq = splittable(q, l.exact), sp = splittable(p, l.exact);
        const bool receiver_first = l.exact ? node_area(q) >= node_area(p)
                                    : is_cluster(q) != is_cluster(p)
                                        ? is_cluster(q)
                                        : node_radius(q) >= node_radius(p);
        if (sq && (receiver_first || !sp))
            decision[k] = split_receiver;
        else if (sp)
            decision[k] = split_source;
    });
    // Links before the first split stay where they are: a late pass of a big refinement splits
    // a few of the newest links among tens of millions (the 1M floor's cycles took 20-30
    // passes), and moving every kept link was most of such a pass.
    const std::size_t first = std::size_t(
        std::find_if(decision.begin(), decision.end(), [](std::uint8_t d) { return d != keep; }) -
        decision.begin());
    if (first == decision.size()) {
        cluster_kept_.assign(cluster_links_.size(), 1);
        return resampled;
    }
    for (std::size_t k = first; k < cluster_links_.size(); ++k) {
        const ClusterLink& l = cluster_links_[k];
        const NodeRef n = decision[k] == split_receiver ? l.receiver : l.source;
        if ((decision[k] == split_receiver || decision[k] == split_source) && !is_cluster(n))
            subdivide(n, b, b_range);
    }
    // In place: the kept links move to the front, the parts of the split ones follow them.
    // Element pairs are made once the cluster passes are done (make_pair_links): most are
    // linked both ways, and a pair's two links share one computation.
    std::vector<std::pair<NodeRef, NodeRef>> cluster_pairs;
    auto add_pair = [&](NodeRef q, NodeRef p) {
        if (is_cluster(q) || is_cluster(p))
            cluster_pairs.emplace_back(q, p);
        else if (linkable(q, p))
            links_.emplace_back(q, p, 0.0f, 0.0f, false);
    };
    std::size_t kept = first;
    for (std::size_t k = first; k < cluster_links_.size(); ++k) {
        const ClusterLink l = cluster_links_[k];
        switch (decision[k]) {
        case keep:
            cluster_links_[kept++] = l;
            break;
        case split_self:
            for_each_child(l.receiver, [&](NodeRef i) {
                for_each_child(l.receiver, [&](NodeRef j) {
                    if (i != j)
                        add_pair(i, j);
                    else if (is_cluster(i))
                        cluster_pairs.emplace_back(i, i);
                });
            });
            break;
        case split_receiver:
            for_each_child(l.receiver, [&](NodeRef c) { add_pair(c, l.source); });
            break;
        case split_source:
            for_each_child(l.source, [&](NodeRef c) { add_pair(l.receiver, c); });
            break;
        }
    }
    check_growth(links_.size(), kept + cluster_pairs.size(),
                 "a refinement pass of the cluster links");
    cluster_links_.resize(kept + cluster_pairs.size());
    const std::vector<std::uint32_t> reverse = exact_reverses(cluster_pairs);
    parallel_for_index(cluster_pairs.size(), 16, [&](std::size_t i) {
        const auto [q, p] = cluster_pairs[i];
        if (reverse[i] == k_no_reverse)
            cluster_links_[kept + i] = make_cluster_link(q, p);
        else if (reverse[i] > i)
            make_exact_pair(q, p, cluster_links_[kept + i], cluster_links_[kept + reverse[i]]);
    });
    cluster_pairs = {};
    // Drop the new links that carry nothing (the kept ones all carry something).
    const auto carried = std::remove_if(
        cluster_links_.begin() + std::ptrdiff_t(kept), cluster_links_.end(),
        [](const ClusterLink& l) { return !l.self && !(l.g > 0) && !l.unresolved(); });
    cluster_links_.resize(std::size_t(carried - cluster_links_.begin()));
    cluster_kept_.assign(cluster_links_.size(), 0);
    std::fill(cluster_kept_.begin(), cluster_kept_.begin() + std::ptrdiff_t(kept), std::uint8_t(1));
    return true;
}

std::vector<std::uint32_t>
LinkSet::exact_reverses(const std::vector<std::pair<NodeRef, NodeRef>>& pairs) const {
    std::vector<std::uint32_t> order(pairs.size()), reverse(pairs.size(), k_no_reverse);
    std::iota(order.begin(), order.end(), 0u);
    auto key = [&](std::uint32_t i) {
        const auto [q, p] = pairs[i];
        return std::tuple(std::min(q, p), std::max(q, p), q);
    };
    tbb::parallel_sort(order.begin(), order.end(),
                       [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
    for (std::size_t k = 0; k + 1 < order.size(); ++k) {
        const auto [q, p] = pairs[order[k]];
        const auto [q2, p2] = pairs[order[k + 1]];
        if (q != p && q == p2 && p == q2 && planar_end(q) && planar_end(p) && exact_source(q) &&
            exact_source(p)) {
            reverse[order[k]] = order[k + 1];
            reverse[order[k + 1]] = order[k];
            ++k;
        }
    }
    return reverse;
}

void LinkSet::link_clusters() {
    links_.clear();
    cluster_links_.clear();
    cluster_links_.push_back(make_cluster_link(cluster_ref(0), cluster_ref(0)));
    link_lights();
    sort_and_index();
}

} // namespace penumbra::solver
