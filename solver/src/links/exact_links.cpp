// Exact links of hierarchical radiosity (see ClusterLink in links/link_set.h): light between two
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
/// A receiver whose direction from a cluster source's centroid is within this sine of the
/// source's normal gives no offset (planar_direction, seen_offset).
constexpr double k_min_slope_sine = 0.05;
/// A partly occluded exact link to a cluster receiver counts this many times F · B v (1 − v)
/// as error (exact_link_error; 4 times the mean error of its visibility over a sharp shadow):
/// without it a ceiling shadowed by a lamp just below it takes light its clusters' mean
/// visibility gives it (docs/calibration.md#k_shadow_weight).
constexpr double k_shadow_weight = 8.0;

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
    return !is_cluster(n) || exact_source_[cluster_index(n)] != 0;
}

bool LinkSet::emits(NodeRef n) const {
    if (!is_cluster(n))
        return !h_.emission[n].is_black();
    const std::uint32_t c = cluster_index(n);
    for (const Rgb& lobe : (*emitted_)[c])
        if (!lobe.is_black())
            return true;
    return false;
}

LinkSet::Plane LinkSet::node_plane(NodeRef n) const {
    if (!is_cluster(n))
        return {h_.normal[n], dot(h_.normal[n], h_.triangle[n][0])};
    const std::uint32_t c = cluster_index(n);
    const Vec3& normal = tree_->normal[c];
    return {normal, dot(normal, h_.triangle[dfs_roots_[root_begin_[c]]][0])};
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

// Directed boundary edges of every face cluster, children before parents: a cluster's
// boundary is its children's (a root's: its three edges, wound counter-clockwise about the
// plane's normal) less the edges that appear both ways. Vertices shared by roots are the
// same doubles (the mesh's), so an interior edge's two directions compare equal.
void LinkSet::build_boundaries() {
    const ClusterTree& tree = *tree_;
    std::vector<std::vector<BoundaryEdge>> edges(tree.size());
    auto root_edges = [&](std::uint32_t r, const Vec3& normal, std::vector<BoundaryEdge>& out) {
        const auto& t = h_.triangle[r];
        const bool ccw = dot(cross(t[1] - t[0], t[2] - t[0]), normal) >= 0;
        for (std::uint8_t k = 0; k < 3; ++k) {
            const auto next = std::uint8_t((k + 1) % 3);
            out.push_back(ccw ? BoundaryEdge{r, k, next} : BoundaryEdge{r, next, k});
        }
    };
    auto point = [&](std::uint32_t r, std::uint8_t corner) -> const Vec3& {
        return h_.triangle[r][corner];
    };
    auto key = [&](const Vec3& a, const Vec3& b) {
        return std::array<double, 6>{a.x, a.y, a.z, b.x, b.y, b.z};
    };
    for (std::size_t c = tree.size(); c-- > 0;) {
        if (!tree.planar[c])
            continue;
        std::vector<BoundaryEdge> all;
        for (std::uint32_t k = tree.child_begin[c]; k < tree.child_begin[c + 1]; ++k) {
            const NodeRef child = tree.children[k];
            if (is_cluster(child)) {
                std::vector<BoundaryEdge>& part = edges[cluster_index(child)];
                all.insert(all.end(), part.begin(), part.end());
            } else {
                root_edges(child, tree.normal[c], all);
            }
        }
        // Cancel an edge against its reverse.
        std::vector<std::pair<std::array<double, 6>, std::uint32_t>> keyed(all.size());
        for (std::size_t i = 0; i < all.size(); ++i)
            keyed[i] = {key(point(all[i].root, all[i].from), point(all[i].root, all[i].to)),
                        std::uint32_t(i)};
        std::sort(keyed.begin(), keyed.end());
        std::vector<BoundaryEdge>& out = edges[c];
        for (std::size_t i = 0; i < all.size(); ++i) {
            const BoundaryEdge& e = all[i];
            const Vec3 &a = point(e.root, e.from), &b = point(e.root, e.to);
            const auto reverse = key(b, a);
            const auto it = std::lower_bound(
                keyed.begin(), keyed.end(), reverse,
                [](const auto& x, const std::array<double, 6>& k) { return x.first < k; });
            if (it == keyed.end() || it->first != reverse)
                out.push_back(e);
        }
    }
    boundary_begin_.assign(tree.size() + 1, 0);
    boundary_.clear();
    for (std::size_t c = 0; c < tree.size(); ++c) {
        merge_collinear(edges[c], boundary_);
        boundary_begin_[c + 1] = std::uint32_t(boundary_.size());
    }
    boundary_.shrink_to_fit();
    // An emitting face cluster is an exact source when its emission is uniform (a lamp's
    // panel, not a lamp and the ceiling around it): the vertices of its receivers gather it
    // exactly, root by root.
    exact_source_.assign(tree.size(), 0);
    for (std::size_t c = 0; c < tree.size(); ++c) {
        if (!tree.planar[c])
            continue;
        const Rgb& first = h_.emission[dfs_roots_[root_begin_[c]]];
        bool uniform = true;
        for (std::uint32_t k = root_begin_[c]; k < root_end_[c] && uniform; ++k)
            uniform = h_.emission[dfs_roots_[k]] == first;
        exact_source_[c] = uniform;
    }
}

// A tessellated wall's boundary is its outline cut at every tessellation vertex: a 5 x 5
// wall of 50 triangles has 20 boundary edges and 4 straight runs. A vertex joins two edges
// into a run where it starts one edge and ends one other, the two in line.
void LinkSet::merge_collinear(const std::vector<BoundaryEdge>& edges,
                              std::vector<ContourEdge>& out) const {
    const std::size_t n = edges.size();
    auto start = [&](std::size_t i) -> const Vec3& {
        return h_.triangle[edges[i].root][edges[i].from];
    };
    auto end = [&](std::size_t i) -> const Vec3& {
        return h_.triangle[edges[i].root][edges[i].to];
    };
    auto key = [](const Vec3& v) { return std::array<double, 3>{v.x, v.y, v.z}; };
    // Edges by their start and by their end point.
    std::vector<std::pair<std::array<double, 3>, std::uint32_t>> starts(n), ends(n);
    for (std::size_t i = 0; i < n; ++i) {
        starts[i] = {key(start(i)), std::uint32_t(i)};
        ends[i] = {key(end(i)), std::uint32_t(i)};
    }
    std::sort(starts.begin(), starts.end());
    std::sort(ends.begin(), ends.end());
    auto range = [](const auto& sorted, const std::array<double, 3>& k) {
        return std::equal_range(sorted.begin(), sorted.end(), std::pair(k, std::uint32_t(0)),
                                [](const auto& x, const auto& y) { return x.first < y.first; });
    };
    constexpr std::uint32_t none = ~std::uint32_t(0);
    std::vector<std::uint32_t> next(n, none);
    std::vector<std::uint8_t> continues(n, 0); // the run of the edge before goes on into it
    for (std::size_t i = 0; i < n; ++i) {
        const auto k = key(end(i));
        const auto [s0, s1] = range(starts, k);
        const auto [e0, e1] = range(ends, k);
        if (s1 - s0 != 1 || e1 - e0 != 1)
            continue; // not a simple vertex of the outline
        const std::uint32_t j = s0->second;
        const Vec3 a = end(i) - start(i), b = end(j) - start(j);
        // In line to a relative 1e-9: the sliver between the run and its edges is ~1e-9 of
        // their length squared.
        if (dot(a, b) > 0 && length(cross(a, b)) <= 1e-9 * length(a) * length(b)) {
            next[i] = j;
            continues[j] = 1;
        }
    }
    std::vector<std::uint8_t> done(n, 0);
    auto emit = [&](std::size_t first, std::size_t last) {
        out.push_back({edges[first].root, edges[last].root, edges[first].from, edges[last].to});
    };
    for (std::size_t i = 0; i < n; ++i) {
        if (continues[i] || done[i])
            continue;
        std::size_t last = i;
        done[i] = 1;
        while (next[last] != none && !done[next[last]]) {
            last = next[last];
            done[last] = 1;
        }
        emit(i, last);
    }
    for (std::size_t i = 0; i < n; ++i) // edges of a run with no start (none in a plane)
        if (!done[i])
            emit(i, i);
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
    for (std::uint32_t k = boundary_begin_[c]; k < boundary_begin_[c + 1]; ++k) {
        const ContourEdge& e = boundary_[k];
        fn(h_.triangle[e.from_root][e.from], h_.triangle[e.to_root][e.to]);
    }
}

double LinkSet::cut_form_factor(const Vec3& x, const Vec3& n, NodeRef p, const Plane& plane,
                                bool& unresolved) const {
    if (!is_cluster(p))
        return form_factor_point_triangle(x, n, h_.triangle[p]);
    const std::uint32_t c = cluster_index(p);
    if (root_end_[c] - root_begin_[c] > k_clip_roots) {
        unresolved = true;
        return 0.0;
    }
    bool clipped = false;
    const double f = clipped_contour(x, n, c, plane.n, clipped);
    return clipped ? f : root_form_factors(x, n, root_begin_[c], root_end_[c]);
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
    for (std::uint32_t k = boundary_begin_[c]; k < boundary_begin_[c + 1]; ++k) {
        const ContourEdge& e = boundary_[k];
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
        sum += form_factor_point_triangle(x, n, h_.triangle[dfs_roots_[k]]);
    return sum;
}

Rgb LinkSet::face_mean(std::uint32_t c, const std::vector<Lobes>& lobes) const {
    return lobe_projection(lobes[c], tree_->normal[c]) * float(1.0 / tree_->area[c]);
}

Rgb LinkSet::exact_source_radiosity(const ClusterLink& link, const Rgb& mean,
                                    const std::vector<Slope>& gradient) const {
    if (gradient.empty() || link.d.y == 0)
        return mean;
    const Rgb seen = mean + slope_along(gradient[cluster_index(link.source)],
                                        exact_source_direction(link) * double(link.d.y));
    return Rgb(std::max(seen.r, 0.0f), std::max(seen.g, 0.0f), std::max(seen.b, 0.0f));
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
    const std::uint32_t c = cluster_index(q), begin = root_begin_[c], end = root_end_[c];
    const double lo = dfs_area_[begin], range = dfs_area_[end] - lo;
    if (end - begin <= std::uint32_t(count)) { // every root's rule (of 1 or 4 points), by area
        const bool four = 4 * (end - begin) <= std::uint32_t(count);
        std::array<std::array<double, 2>, k_max_quadrature_points> bary;
        std::size_t m = 0;
        quadrature_barycentrics(four ? 1 : 0, bary.data(), &m);
        for (std::uint32_t k = begin; k < end; ++k) {
            const auto& t = h_.triangle[dfs_roots_[k]];
            for (std::size_t i = 0; i < m; ++i)
                out.push_back(
                    {at_barycentrics(t, bary[i]), h_.area[dfs_roots_[k]] / range / double(m)});
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
        while (k < end && dfs_area_[k + 1] <= u0)
            ++k;
        for (std::uint32_t j = k; j < end && dfs_area_[j] < u1; ++j) {
            const double overlap = std::min(dfs_area_[j + 1], u1) - std::max(dfs_area_[j], u0);
            if (overlap <= 0)
                continue;
            sum += h_.centroid(dfs_roots_[j]) * overlap;
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
    return sample_triangle(h_.triangle[dfs_roots_[k]], rng.next_double(), rng.next_double());
}

Vec3 LinkSet::node_centroid(NodeRef n) const {
    return is_cluster(n) ? tree_->centroid[cluster_index(n)] : h_.centroid(n);
}

Vec3 LinkSet::exact_source_direction(const ClusterLink& link) const {
    return planar_direction(link.source, link.receiver);
}

Vec3 LinkSet::planar_direction(NodeRef from, NodeRef toward) const {
    if (!is_cluster(from))
        return {};
    const std::uint32_t c = cluster_index(from);
    const Vec3 delta = node_centroid(toward) - tree_->centroid[c];
    const Vec3& n = tree_->normal[c];
    const Vec3 along = delta - n * dot(n, delta);
    const double len = length(along);
    // An end (nearly) straight above: what it sees of `from` is centred, not off along a
    // direction.
    if (!(len > k_min_slope_sine * length(delta)))
        return {};
    return along / len;
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

Vec3 LinkSet::exact_slope(const ClusterLink& link) const {
    if (!is_cluster(link.receiver))
        return {};
    return exact_slope(link, Frame::from_normal(tree_->normal[cluster_index(link.receiver)]));
}

// By symmetry of the kernel, the part of source p that receiver q sees most of (the
// F-weighted centroid of p over q) is the centroid of p's points weighted by their own point
// form factors toward q: a quadrature over p, as over q for F.
double LinkSet::seen_offset(NodeRef p, NodeRef q, const ExactEnd& end) const {
    const Vec3 toward = planar_direction(p, q);
    if (dot(toward, toward) == 0)
        return 0.0;
    const Vec3 m = node_centroid(p);
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
    const Vec3 toward = planar_direction(p, q); // zero: the source sends its mean
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
        const Vec3 xq = sample_point(q, rng, dfs_area_), xp = sample_point(p, rng, dfs_exitance_);
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
        mean = double(lobe_projection((*exitance_)[c], tree_->normal[c]).max_component()) /
               tree_->area[c];
        range = double((*departure_)[c]);
    } else {
        mean = double(b[p].max_component());
        range = double(b_range[p]);
    }
    const double f = double(link.g), visible = double(link.visible());
    // A receiver that cannot be split takes the mean of F over it whatever its source's
    // parts: splitting the source would not lower the error of its one value.
    const double spread = splittable(link.receiver, true) ? double(link.spread()) : 0.0;
    const double estimate =
        settings_.oracle == Oracle::bf ? f * visible * mean : spread * mean + f * visible * range;
    // All rays blocked: n of them cannot tell 0 from about 1/n.
    const double uncertain =
        link.visible() > 0 || link.rays == 0 ? 0.0 : f * mean / double(link.rays);
    // A partly occluded link gives its cluster receiver its mean visibility v everywhere,
    // across the shadow: where that is sharp, v is off by 2 v (1 − v) on average. As with
    // the spread, only splitting the receiver resolves that (docs/calibration.md#k_shadow_weight).
    const double shadow =
        link.partial && is_cluster(link.receiver) && splittable(link.receiver, true)
            ? k_shadow_weight * f * visible * (1.0 - visible) * mean
            : 0.0;
    return estimate * (link.partial ? 2.0 : 1.0) + uncertain + shadow;
}

} // namespace penumbra::solver
