// Exact links of hierarchical radiosity (see ClusterLink in links/link_store.h): light between two
// planar ends, one of them a face cluster, computed as between two elements. The receiver's
// mean form factor comes from point-to-polygon form factors (Lambert's contour) at quadrature
// points spread over its roots; the source polygon of a face cluster is the boundary of the
// union of its roots (interior edges cancel in the contour sum), so its cost grows with the
// cluster's perimeter rather than its root count. The visible fraction is the kernel-weighted
// share of open rays between area-drawn points of the receiver and exitance-drawn points of
// the source.
//
// Both ends are first-order: a cluster receiver takes the least-squares plane of its points'
// form factors (its slope pushed down to the roots about the cluster's centroid, so it adds
// no power), and a cluster source sends the value of the linear fit of its radiosity
// (planar_gradients) at the part of it the receiver sees most of (seen_offset). With one
// value per end, the wall beside a floor split their link until the floor's gradient was
// resolved, and took more links for a less accurate solve (docs/calibration.md#exact-links).
//
// Without exact links, a wall tessellated into 50 triangles and the floor beside it (each a face
// cluster) are too close for a point model (the lobe links' admissibility), so every pair of
// their roots gets a link: a tessellated floor took 66 times the links of the same floor
// of untessellated rectangles (docs/calibration.md#exact-links).

#include <algorithm>
#include <cmath>
#include <limits>

#include "kernels/form_factor.h"
#include "links/link_set.h"

namespace penumbra::solver {

namespace {

/// The point of triangle \p t at barycentrics (1 − b1 − b2, b1, b2).
Vec3 at_barycentrics(const std::array<Vec3, 3>& t, const std::array<double, 2>& b) {
    return t[0] * (1.0 - b[0] - b[1]) + t[1] * b[0] + t[2] * b[1];
}

/// Quadrature points on a receiver cluster: up to this many (4 for a receiver small against
/// the distance).
constexpr int k_exact_points = 128;
/// A source cluster straddling a quadrature point's tangent plane is clipped there
/// (clipped_contour, or triangle by triangle where its crossings do not pair up) if it has
/// at most this many roots; a larger one is split by the oracle at once (the links it splits
/// into are better for the shooting iteration: HierarchicalIterations' Cornell box).
constexpr std::uint32_t k_clip_roots = 64;
/// An exact link with a receiver cluster closer to its source than this times its radius
/// takes the finest points.
constexpr double k_near_gap = 0.5;

} // namespace

double LinkSet::box_gap(NodeRef a, NodeRef b) const {
    Vec3 lo[2], hi[2];
    const NodeRef ends[2] = {a, b};
    for (int i = 0; i < 2; ++i) {
        lo[i] = Vec3(1e300, 1e300, 1e300);
        hi[i] = Vec3(-1e300, -1e300, -1e300);
        for_each_corner(ends[i], [&](const Vec3& v) {
            lo[i] = min(lo[i], v);
            hi[i] = max(hi[i], v);
        });
    }
    Vec3 gap;
    for (std::size_t k = 0; k < 3; ++k)
        gap[k] = std::max({0.0, lo[1][k] - hi[0][k], lo[0][k] - hi[1][k]});
    return length(gap);
}

bool LinkSet::planar_end(NodeRef n) const {
    return !is_cluster(n) || tree_->planar[cluster_index(n)] != 0;
}

bool LinkSet::exact_source(NodeRef n) const {
    return !is_cluster(n) || tables_->exact_source_[cluster_index(n)] != 0;
}

LinkSet::Plane LinkSet::node_plane(NodeRef n) const {
    if (!is_cluster(n))
        return {h_.normal[n], dot(h_.normal[n], h_.triangle[n][0])};
    const std::uint32_t c = cluster_index(n);
    const Vec3& normal = tree_->normal[c];
    return {normal, dot(normal, h_.triangle[tables_->dfs_roots_[tables_->root_begin_[c]]][0])};
}

template <typename Fn> void LinkSet::for_each_corner(NodeRef n, Fn&& fn) const {
    if (!is_cluster(n)) {
        for (const Vec3& v : h_.triangle[n])
            fn(v);
        return;
    }
    const Vec3& lo = tree_->lo[cluster_index(n)];
    const Vec3& hi = tree_->hi[cluster_index(n)];
    for (int k = 0; k < 8; ++k)
        fn(Vec3(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z));
}

bool LinkSet::sees_whole(const Vec3& x, const Vec3& n, NodeRef p) const {
    bool in_front = true;
    for_each_corner(p, [&](const Vec3& v) { in_front = in_front && dot(v - x, n) >= 0; });
    return in_front;
}

template <typename Fn> void LinkSet::for_each_contour_edge(NodeRef p, Fn&& fn) const {
    if (!is_cluster(p)) {
        const auto& t = h_.triangle[p];
        fn(t[0], t[1]);
        fn(t[1], t[2]);
        fn(t[2], t[0]);
        return;
    }
    const std::uint32_t c = cluster_index(p);
    for (std::uint32_t k = tables_->boundary_begin_[c]; k < tables_->boundary_begin_[c + 1]; ++k) {
        const ContourEdge& e = tables_->boundary_[k];
        fn(h_.triangle[e.from_root][e.from], h_.triangle[e.to_root][e.to]);
    }
}

double LinkSet::cut_form_factor(const Vec3& x, const Vec3& n, NodeRef p, const Plane& plane,
                                bool& unresolved) const {
    if (!is_cluster(p))
        return form_factor_point_triangle(x, n, h_.triangle[p]);
    const std::uint32_t c = cluster_index(p);
    if (tables_->root_end_[c] - tables_->root_begin_[c] > k_clip_roots) {
        unresolved = true;
        return 0.0;
    }
    bool clipped = false;
    const double f = clipped_contour(x, n, c, plane.n, clipped);
    return clipped ? f : root_form_factors(x, n, tables_->root_begin_[c], tables_->root_end_[c]);
}

// The part of a face cluster in front of x's tangent plane has for its boundary the parts of
// the cluster's boundary in front (clipped where they cross) and the intervals of the line
// where the two planes meet that lie inside the cluster, each run from where the boundary
// leaves the half-space to where it comes back: along cross(n, normal) for a boundary wound
// counter-clockwise about the cluster's normal. Sorted along it, the crossings pair up into
// those intervals (a vertex on the line is crossed out of and back into at the same point,
// taken in the order that keeps the pairs). Root by root, the clipped clusters of the office
// floors took a twentieth of the solve.
double LinkSet::clipped_contour(const Vec3& x, const Vec3& n, std::uint32_t c, const Vec3& normal,
                                bool& ok) const {
    struct Crossing {
        double t = 0;
        Vec3 at;
        bool exit = false;
    };
    thread_local std::vector<Crossing> crossings;
    crossings.clear();
    const Vec3 along = cross(n, normal);
    // Planes (nearly) parallel: x lies in the cluster's plane, which straddles its tangent
    // plane by rounding alone, and the line they meet on is undefined.
    if (!(dot(along, along) > 1e-12))
        return ok = false, 0.0;
    double sum = 0;
    for (std::uint32_t k = tables_->boundary_begin_[c]; k < tables_->boundary_begin_[c + 1]; ++k) {
        const ContourEdge& e = tables_->boundary_[k];
        const Vec3& a = h_.triangle[e.from_root][e.from];
        const Vec3& b = h_.triangle[e.to_root][e.to];
        const double ha = dot(a - x, n), hb = dot(b - x, n);
        const bool in_a = ha > 0, in_b = hb > 0; // a point on the plane counts as behind it
        if (in_a && in_b) {
            sum += contour_term(x, n, a, b);
            continue;
        }
        if (in_a == in_b)
            continue;
        // Where the edge crosses: the vertex itself where it lies on the plane.
        const Vec3 at = ha == 0 ? a : hb == 0 ? b : a + (b - a) * (ha / (ha - hb));
        crossings.push_back({dot(at, along), at, in_a});
        sum += in_a ? contour_term(x, n, a, at) : contour_term(x, n, at, b);
    }
    std::sort(crossings.begin(), crossings.end(),
              [](const Crossing& u, const Crossing& v) { return u.t < v.t; });
    const Crossing* open = nullptr;
    for (std::size_t i = 0; i < crossings.size();) {
        std::size_t j = i; // crossings [i, j) at one point of the line
        while (j < crossings.size() && crossings[j].t == crossings[i].t)
            ++j;
        std::size_t exits = 0, entries = 0, first_exit = j, first_entry = j;
        for (std::size_t k = i; k < j; ++k) {
            if (crossings[k].exit)
                first_exit = exits++ == 0 ? k : first_exit;
            else
                first_entry = entries++ == 0 ? k : first_entry;
        }
        // Inside an interval an entry closes it, outside one an exit opens it.
        while (exits + entries > 0) {
            if (open == nullptr) {
                if (exits == 0)
                    return ok = false, 0.0;
                open = &crossings[first_exit];
                --exits;
            } else {
                if (entries == 0)
                    return ok = false, 0.0;
                sum += contour_term(x, n, open->at, crossings[first_entry].at);
                open = nullptr;
                --entries;
            }
        }
        i = j;
    }
    if (open != nullptr)
        return ok = false, 0.0;
    ok = true;
    return std::abs(sum) / (2.0 * k_pi);
}

double LinkSet::root_form_factors(const Vec3& x, const Vec3& n, std::uint32_t begin,
                                  std::uint32_t end) const {
    double sum = 0;
    for (std::uint32_t k = begin; k < end; ++k)
        sum += form_factor_point_triangle(x, n, h_.triangle[tables_->dfs_roots_[k]]);
    return sum;
}

void LinkSet::receiver_points(NodeRef q, int count, std::vector<WeightedPoint>& out) const {
    out.clear();
    if (!is_cluster(q)) {
        std::array<std::array<double, 2>, k_max_quadrature_points> bary;
        std::size_t m = 0;
        quadrature_barycentrics(count <= 4 ? 1 : (count <= 16 ? 2 : 3), bary.data(), &m);
        const auto& t = h_.triangle[q];
        for (std::size_t k = 0; k < m; ++k)
            out.push_back({at_barycentrics(t, bary[k]), 1.0 / double(m)});
        return;
    }
    const std::uint32_t c = cluster_index(q), begin = tables_->root_begin_[c],
                        end = tables_->root_end_[c];
    const double lo = tables_->dfs_area_[begin], range = tables_->dfs_area_[end] - lo;
    if (end - begin <= std::uint32_t(count)) { // every root's rule (of 1 or 4 points), by area
        const bool four = 4 * (end - begin) <= std::uint32_t(count);
        std::array<std::array<double, 2>, k_max_quadrature_points> bary;
        std::size_t m = 0;
        quadrature_barycentrics(four ? 1 : 0, bary.data(), &m);
        for (std::uint32_t k = begin; k < end; ++k) {
            const auto& t = h_.triangle[tables_->dfs_roots_[k]];
            for (std::size_t i = 0; i < m; ++i)
                out.push_back({at_barycentrics(t, bary[i]),
                               h_.area[tables_->dfs_roots_[k]] / range / double(m)});
        }
        return;
    }
    // Strata of equal area over the running sum (depth-first order is spatially coherent),
    // each at its centroid: exact for a linear integrand, as the element rules are.
    std::uint32_t k = begin;
    for (int s = 0; s < count; ++s) {
        const double u0 = lo + double(s) / double(count) * range;
        const double u1 = lo + double(s + 1) / double(count) * range;
        Vec3 sum;
        double weight = 0;
        while (k < end && tables_->dfs_area_[k + 1] <= u0)
            ++k;
        for (std::uint32_t j = k; j < end && tables_->dfs_area_[j] < u1; ++j) {
            const double overlap =
                std::min(tables_->dfs_area_[j + 1], u1) - std::max(tables_->dfs_area_[j], u0);
            if (overlap <= 0)
                continue;
            sum += h_.centroid(tables_->dfs_roots_[j]) * overlap;
            weight += overlap;
        }
        if (weight > 0)
            out.push_back({sum / weight, 1.0 / double(count)});
    }
}

Vec3 LinkSet::sample_point(NodeRef n, Pcg32& rng, const std::vector<double>& running) const {
    if (!is_cluster(n))
        return sample_triangle(h_.triangle[n], rng.next_double(), rng.next_double());
    const std::size_t k = draw_root(cluster_index(n), rng.next_double(), running);
    return sample_triangle(h_.triangle[tables_->dfs_roots_[k]], rng.next_double(),
                           rng.next_double());
}

// The least-squares plane through the point form factors \p values at \p points over the
// receiver's plane (in its frame, exact_slope), scaled toward the mean where it would fall
// below 0 over the receiver's bounds; the spread becomes twice the largest departure from
// it. A wall lights the floor beside it by a steep gradient across the floor: the spread of
// a constant split such links where a plane fits (docs/calibration.md#exact-links).
void LinkSet::fit_slope(ClusterLink& link, const std::vector<WeightedPoint>& points,
                        const std::vector<double>& values, double f) const {
    const std::uint32_t c = cluster_index(link.receiver);
    const Vec3& m = tree_->centroid[c];
    const Frame frame = Frame::from_normal(tree_->normal[c]);
    // Weighted covariances of the points' offsets (u, w) in the frame and of F with them.
    double mu = 0, mw = 0;
    for (const WeightedPoint& x : points) {
        mu += x.w * dot(x.x - m, frame.s);
        mw += x.w * dot(x.x - m, frame.t);
    }
    double cuu = 0, cww = 0, cuw = 0, fu = 0, fw = 0; // covariances (weights sum to 1)
    for (std::size_t i = 0; i < points.size(); ++i) {
        const double u = dot(points[i].x - m, frame.s) - mu;
        const double w = dot(points[i].x - m, frame.t) - mw;
        const double wt = points[i].w, df = values[i] - f;
        cuu += wt * u * u;
        cww += wt * w * w;
        cuw += wt * u * w;
        fu += wt * df * u;
        fw += wt * df * w;
    }
    Vec3 gradient = fit_gradient(frame, cuu, cww, cuw, fu, fw);
    if (dot(gradient, gradient) == 0)
        return;
    double lowest = 0;
    for_each_corner(link.receiver,
                    [&](const Vec3& v) { lowest = std::min(lowest, dot(v - m, gradient)); });
    if (f + lowest < 0)
        gradient *= f / -lowest;
    double departure = 0;
    for (std::size_t i = 0; i < points.size(); ++i)
        departure = std::max(departure, std::abs(values[i] - (f + dot(points[i].x - m, gradient))));
    link.d.z = float(dot(gradient, frame.s));
    link.slope_t = float(dot(gradient, frame.t));
    link.d.x = float(2.0 * departure);
}

// By symmetry of the kernel, the part of source p that receiver q sees most of (the
// F-weighted centroid of p over q) is the centroid of p's points weighted by their own point
// form factors toward q: a quadrature over p, as over q for F.
double LinkSet::seen_offset(NodeRef p, NodeRef q, const ExactEnd& end) const {
    const Vec3 toward = tables_->planar_direction(p, q);
    if (dot(toward, toward) == 0)
        return 0.0;
    const Vec3 m = tables_->node_centroid(p);
    double sum = 0, moment = 0;
    for (std::size_t k = 0; k < end.points.size(); ++k) {
        const WeightedPoint& y = end.points[k];
        sum += y.w * end.values[k];
        moment += y.w * end.values[k] * dot(y.x - m, toward);
    }
    return sum > 0 ? moment / sum : 0.0;
}

bool LinkSet::exact_ends_open(NodeRef q, NodeRef p, const Plane& pq, const Plane& pp) const {
    const double eps = 1e-9 * h_.diagonal;
    bool q_sees = false, p_sees = false; // some of each end in front of the other's plane
    for_each_corner(p, [&](const Vec3& v) { q_sees = q_sees || dot(pq.n, v) - pq.d > eps; });
    for_each_corner(q, [&](const Vec3& v) { p_sees = p_sees || dot(pp.n, v) - pp.d > eps; });
    return q_sees && p_sees && !centres_occluded(q, p);
}

int LinkSet::exact_point_count(NodeRef q, NodeRef p, const Plane& pp) const {
    // A receiver that straddles the source's plane, or whose gap to the source is small
    // against its size, takes the finest points (4 per root): fewer do not resolve the cut,
    // or the steep part of F by a common edge (a wall and the floor it stands on got a
    // twentieth of their form factor from cluster centroids). Such receivers are no longer
    // split at once (docs/calibration.md#k_exact_points).
    const double eps = 1e-9 * h_.diagonal;
    bool fine = false;
    for_each_corner(q, [&](const Vec3& v) { fine = fine || dot(pp.n, v) - pp.d < -eps; });
    fine = fine || (is_cluster(q) && box_gap(q, p) < k_near_gap * node_radius(q));
    if (fine)
        return k_exact_points;
    // Otherwise by the receiver's diameter over the distance; 64 points rather than 128
    // between 0.4 and 1, where most of the points were (docs/calibration.md#k_exact_points).
    const double r = length(node_centre(p) - node_centre(q));
    const double ratio = 2.0 * node_radius(q) / std::max(r, 1e-300);
    return ratio < 0.1 ? 4 : ratio < 0.4 ? 16 : ratio < 1.0 ? 64 : k_exact_points;
}

void LinkSet::exact_end(NodeRef q, NodeRef p, const Plane& pq, const Plane& pp, int count,
                        ExactEnd& end) const {
    receiver_points(q, count, end.points);
    end.values.assign(end.points.size(), 0.0);
    end.unresolved = false;
    // Points that see all of p take the contour sum of its boundary, edge by edge over the
    // points at once (add_contour_terms); the rest are cut by their tangent planes.
    thread_local ContourPoints whole;
    whole.clear();
    const double eps = 1e-9 * h_.diagonal;
    for (std::size_t k = 0; k < end.points.size(); ++k) {
        const Vec3& x = end.points[k].x;
        if (dot(pp.n, x) - pp.d <= eps)
            continue; // behind the source's plane: it radiates the other way
        if (sees_whole(x, pq.n, p))
            whole.push_back(x, k);
        else
            end.values[k] = cut_form_factor(x, pq.n, p, pp, end.unresolved);
    }
    if (!whole.empty()) {
        for_each_contour_edge(
            p, [&](const Vec3& a, const Vec3& b) { add_contour_terms(a, b, pq.n, whole); });
        whole.write_form_factors(end.values.data());
    }
    end.f = 0;
    end.lo = std::numeric_limits<double>::infinity();
    end.hi = 0;
    for (std::size_t k = 0; k < end.points.size(); ++k) {
        const double fx = end.values[k];
        end.f += end.points[k].w * fx;
        end.lo = std::min(end.lo, fx);
        end.hi = std::max(end.hi, fx);
    }
}

bool LinkSet::set_exact_form_factor(ClusterLink& link, const ExactEnd& receiver,
                                    const ExactEnd* source) const {
    if (!(receiver.f > 0) && !receiver.unresolved)
        return false;
    link.g = float(receiver.f);
    if (receiver.unresolved) {
        link.d.x = k_unresolved;
        return true;
    }
    link.d.x = float(receiver.hi - receiver.lo);
    if (source)
        link.d.y = float(seen_offset(link.source, link.receiver, *source));
    if (is_cluster(link.receiver))
        fit_slope(link, receiver.points, receiver.values, receiver.f);
    return true;
}

ClusterLink LinkSet::make_exact_link(NodeRef q, NodeRef p) const {
    ClusterLink link = exact_placeholder(q, p);
    const Plane pq = node_plane(q), pp = node_plane(p);
    if (!exact_ends_open(q, p, pq, pp))
        return link;
    // The unoccluded form factor and its spread over the receiver's points.
    thread_local ExactEnd receiver, source;
    const int count = exact_point_count(q, p, pp);
    exact_end(q, p, pq, pp, count, receiver);
    const Vec3 toward = tables_->planar_direction(p, q); // zero: the source sends its mean
    const bool offset = is_cluster(p) && !receiver.unresolved && dot(toward, toward) > 0;
    if (offset) // a quarter as many points over the source suffice for where it is seen
        exact_end(p, q, pp, pq, std::max(4, count / 4), source);
    if (set_exact_form_factor(link, receiver, offset ? &source : nullptr))
        exact_visibility(link, pq, pp);
    return link;
}

// A pair linked both ways shares what one link computes over each end: the receiver's points
// give its form factor, and its source's points (where that is a cluster) where the receiver
// sees most of it, which is the other link's form factor. 60 % of a refinement's new exact
// links come with their reverse.
void LinkSet::make_exact_pair(NodeRef q, NodeRef p, ClusterLink& qp, ClusterLink& pq_link) const {
    qp = exact_placeholder(q, p);
    pq_link = exact_placeholder(p, q);
    const Plane pq = node_plane(q), pp = node_plane(p);
    if (!exact_ends_open(q, p, pq, pp))
        return;
    thread_local ExactEnd at_q, at_p;
    int count_q = exact_point_count(q, p, pp), count_p = exact_point_count(p, q, pq);
    // Each end's points serve the other link's offset, which asks for a quarter of that
    // link's count.
    if (is_cluster(q))
        count_q = std::max(count_q, std::max(4, count_p / 4));
    if (is_cluster(p))
        count_p = std::max(count_p, std::max(4, count_q / 4));
    exact_end(q, p, pq, pp, count_q, at_q);
    exact_end(p, q, pp, pq, count_p, at_p);
    if (set_exact_form_factor(qp, at_q, is_cluster(p) ? &at_p : nullptr))
        exact_visibility(qp, pq, pp);
    if (set_exact_form_factor(pq_link, at_p, is_cluster(q) ? &at_q : nullptr))
        exact_visibility(pq_link, pp, pq);
}

ClusterLink LinkSet::exact_placeholder(NodeRef q, NodeRef p) {
    ClusterLink link;
    link.receiver = q;
    link.source = p;
    link.exact = 1;
    return link;
}

// The visible fraction of the light sent: kernel-weighted rays from area-drawn points of the
// receiver to points of the source drawn by exitance (area × radiosity, as for lobe links).
// Drawn by area, the dark part of a ceiling above a lamp (which sends into the lamp's back)
// counted at the ceiling's mean radiosity, and the lamp room lost 0.26 % of its power.
void LinkSet::exact_visibility(ClusterLink& link, const Plane& pq, const Plane& pp) const {
    const NodeRef q = link.receiver, p = link.source;
    Pcg32 rng = Pcg32::for_stream(RngPurpose::exact_visibility, q, p, 0, settings_.rows.seed);
    const int rays = std::clamp(settings_.rows.visibility_rays, 4, k_max_link_rays);
    thread_local std::vector<Segment> segments;
    thread_local std::vector<double> kernel;
    thread_local std::vector<std::int32_t> hits;
    thread_local std::vector<std::uint8_t> blocked;
    segments.clear();
    kernel.clear();
    for (int k = 0; k < 2 * rays && int(segments.size()) < rays; ++k) {
        const Vec3 xq = sample_point(q, rng, tables_->dfs_area_),
                   xp = sample_point(p, rng, tables_->dfs_exitance_);
        const Vec3 w = xp - xq;
        const double d2 = dot(w, w);
        const double cq = dot(pq.n, w), cp = -dot(pp.n, w);
        if (!(d2 > 0) || cq <= 0 || cp <= 0)
            continue; // no transfer between these two points
        const Vec3 from = xq + pq.n * settings_.offset, to = xp + pp.n * settings_.offset;
        segments.push_back({Vec3f(from), Vec3f(to - from), 0.0f, 1.0f});
        kernel.push_back(cq * cp / (d2 * d2));
    }
    if (segments.empty()) { // the transfer is where no ray was drawn: unknown
        link.set_visible(1.0);
        link.partial = 1;
        return;
    }
    // Occlusion rays, which stop at any hit; a link all of whose rays are blocked traces them
    // again to their first hits, the planes that may prove it dark (a sixth of the office
    // floors' exact links; docs/calibration.md#occlusion-certificates).
    blocked.resize(segments.size());
    visibility_.occluded(segments, blocked);
    double all = 0, open = 0;
    int open_rays = 0;
    for (std::size_t k = 0; k < segments.size(); ++k) {
        all += kernel[k];
        if (!blocked[k]) {
            open += kernel[k];
            ++open_rays;
        }
    }
    link.rays = std::uint16_t(segments.size());
    if (open_rays == 0) {
        if (certified_blocked(q, p, segments, hits, false)) {
            link.g = 0.0f; // carries nothing: the refinement drops it
            link.set_visible(0.0);
            return;
        }
    }
    link.set_visible(all > 0 ? open / all : 0.0);
    link.partial = open_rays > 0 && open_rays < int(segments.size());
}

double LinkSet::exact_link_error(const ClusterLink& link, const std::vector<Rgb>& b,
                                 const std::vector<float>& b_range) const {
    if (link.unresolved())
        return std::numeric_limits<double>::infinity();
    const NodeRef p = link.source;
    double mean = 0, range = 0;
    if (is_cluster(p)) {
        const std::uint32_t c = cluster_index(p);
        mean = double(lobe_projection((*tables_->exitance_)[c], tree_->normal[c]).max_component()) /
               tree_->area[c];
        range = double((*tables_->departure_)[c]);
    } else {
        mean = double(b[p].max_component());
        range = double(b_range[p]);
    }
    return oracle::exact_link_error(settings_, link, mean, range, splittable(link.receiver, true));
}

} // namespace penumbra::solver
