// Constrained Delaunay triangulation and Delaunay refinement of one planar surface (CGAL 5.5
// Mesh_2: Ruppert/Shewchuk refinement with Shewchuk's clusters for small input angles).
// Two triangulations per surface: the region triangulation (outline + contact lines only)
// labels the regions between contact lines; the final one adds the discontinuity segments and
// is refined. Every final face lies in one region, found by locating its centroid.
// Deviation from plain Mesh_2 criteria: faces with an edge shorter than min_edge are not
// refined for their angles, so that nearly touching constraints cannot trigger a cascade.

#include "surface_cdt.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include <fmt/format.h>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/exceptions.h>

#include "constraint_cleanup.h"
#include "core/error.h"
#include "size_field.h"

namespace penumbra::mesher {

namespace {

struct FaceInfo {
    std::int32_t region = -1;
    std::int32_t index = -1;  ///< dense index among the final faces in a region
    bool inside = false;      ///< inside the outline (before refinement)
    bool reached = false;     ///< visited by the inside/outside flood
    std::uint8_t outline = 0; ///< bit i: edge i is a piece of the outline
};

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, K>;
using Fb0 = CGAL::Constrained_Delaunay_triangulation_face_base_2<K>;
using Fb1 = CGAL::Triangulation_face_base_with_info_2<FaceInfo, K, Fb0>;
using Fb = CGAL::Delaunay_mesh_face_base_2<K, Fb1>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;
using Point = Cdt::Point;
using Face_handle = Cdt::Face_handle;
using Vertex_handle = Cdt::Vertex_handle;
using BaseCriteria = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;

Vec2 centroid(const Face_handle& f) {
    const Point& a = f->vertex(0)->point();
    const Point& b = f->vertex(1)->point();
    const Point& c = f->vertex(2)->point();
    return {(a.x() + b.x() + c.x()) / 3.0, (a.y() + b.y() + c.y()) / 3.0};
}

// Whether CGAL's refinement can insert \p fh's circumcentre: false for a face so flat that
// the circumcentre (CGAL's formula, in doubles) has a zero denominator or is no finite double.
bool has_finite_circumcentre(const Face_handle& fh) {
    const Point &p = fh->vertex(0)->point(), &q = fh->vertex(1)->point(),
                &r = fh->vertex(2)->point();
    const double qx = q.x() - p.x(), qy = q.y() - p.y(), rx = r.x() - p.x(), ry = r.y() - p.y();
    const double den = 2 * (qx * ry - rx * qy);
    if (den == 0)
        return false;
    const double q2 = qx * qx + qy * qy, r2 = rx * rx + ry * ry;
    return std::isfinite((ry * q2 - qy * r2) / den) && std::isfinite((rx * q2 - qx * r2) / den);
}

/// Size and angle criteria with a size field (finer along discontinuities) that leave faces
/// with an edge below min_edge alone as far as their angles go.
class Criteria : public BaseCriteria {
public:
    Criteria(double max_edge, double min_edge, const SizeField* field)
        : CGAL::Delaunay_mesh_criteria_2<Cdt>(0.125), BaseCriteria(0.125, max_edge),
          min_edge_(min_edge), field_(field) {}

    class Is_bad : public BaseCriteria::Is_bad {
    public:
        Is_bad(const BaseCriteria::Is_bad& base, double min_edge, const SizeField* field)
            : BaseCriteria::Is_bad(base), min_sq_(min_edge * min_edge), field_(field) {}
        using BaseCriteria::Is_bad::operator();
        CGAL::Mesh_2::Face_badness operator()(const Face_handle& fh, Quality& q) const {
            // A face so flat that its circumcentre is not a finite double cannot be refined:
            // CGAL would insert a NaN point (a sliver polygon's needle faces).
            if (!has_finite_circumcentre(fh))
                return CGAL::Mesh_2::NOT_BAD;
            const CGAL::Mesh_2::Face_badness badness = BaseCriteria::Is_bad::operator()(fh, q);
            if (badness == CGAL::Mesh_2::IMPERATIVELY_BAD)
                return badness;
            double longest = 0, shortest = std::numeric_limits<double>::infinity();
            for (int i = 0; i < 3; ++i) {
                const double l2 = CGAL::squared_distance(fh->vertex(i)->point(),
                                                         fh->vertex((i + 1) % 3)->point());
                longest = std::max(longest, l2);
                shortest = std::min(shortest, l2);
            }
            if (field_) {
                const double b = field_->bound(centroid(fh));
                if (longest > b * b) {
                    q.second = longest / (b * b);
                    return CGAL::Mesh_2::IMPERATIVELY_BAD;
                }
            }
            if (badness == CGAL::Mesh_2::BAD && shortest < min_sq_)
                return CGAL::Mesh_2::NOT_BAD;
            return badness;
        }

    private:
        double min_sq_;
        const SizeField* field_;
    };
    Is_bad is_bad_object() const {
        return Is_bad(BaseCriteria::is_bad_object(), min_edge_, field_);
    }

private:
    double min_edge_;
    const SizeField* field_;
};

Point to_point(const Vec2& p) {
    return Point(p.x, p.y);
}
Vec2 to_vec(const Point& p) {
    return {p.x(), p.y()};
}

double face_area(const Face_handle& f) {
    return std::abs(
        CGAL::area(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point()));
}

// Inserts the noded outline edges and segments (they meet only at shared endpoints), marks
// the outline's edges and the faces inside it: the parity of outline edges crossed from the
// infinite face (a point-in-polygon test with the original outline would misjudge faces
// within round-off of a bent outline edge).
void insert_constraints(Cdt& cdt, const std::vector<Vec2>& outline,
                        const std::vector<Segment2>& segments, double merge) {
    std::vector<std::pair<Vertex_handle, Vertex_handle>> outline_edges;
    Vertex_handle hint;
    for (const NodedSegment& n : node_segments(outline, segments, merge)) {
        const Vertex_handle a = cdt.insert(to_point(n.segment.a),
                                           hint == Vertex_handle() ? Face_handle() : hint->face());
        const Vertex_handle b = cdt.insert(to_point(n.segment.b), a->face());
        if (a == b)
            continue;
        cdt.insert_constraint(a, b);
        if (n.outline)
            outline_edges.emplace_back(a, b);
        hint = b;
    }
    for (Face_handle f : cdt.all_face_handles())
        f->info() = FaceInfo{};
    for (const auto& [a, b] : outline_edges) {
        Face_handle f;
        int i = 0;
        if (cdt.is_edge(a, b, f, i)) {
            f->info().outline |= std::uint8_t(1u << i);
            const Face_handle g = f->neighbor(i);
            g->info().outline |= std::uint8_t(1u << g->index(f));
        }
    }
    std::vector<Face_handle> stack{cdt.infinite_face()};
    cdt.infinite_face()->info().reached = true;
    while (!stack.empty()) {
        const Face_handle f = stack.back();
        stack.pop_back();
        for (int i = 0; i < 3; ++i) {
            const Face_handle g = f->neighbor(i);
            if (g->info().reached)
                continue;
            g->info().reached = true;
            g->info().inside = f->info().inside != bool(f->info().outline & (1u << i));
            stack.push_back(g);
        }
    }
}

// A face whose three vertices are (nearly) collinear and whose middle vertex belongs to no
// other face of the domain is a crease of a constraint polyline (a point moved onto a line
// lands within round-off of it), not an element.
bool crease(const Cdt& cdt, const Face_handle& f) {
    double longest = 0;
    int apex = 0;
    for (int i = 0; i < 3; ++i) {
        const double l2 =
            CGAL::squared_distance(f->vertex(Cdt::ccw(i))->point(), f->vertex(Cdt::cw(i))->point());
        if (l2 > longest) {
            longest = l2;
            apex = i;
        }
    }
    if (!(2 * face_area(f) < 1e-9 * longest))
        return false;
    auto fc = cdt.incident_faces(f->vertex(apex)), done = fc;
    do {
        if (Face_handle(fc) != f && !cdt.is_infinite(fc) && fc->info().region >= 0)
            return false;
    } while (++fc != done);
    return true;
}

/// The final faces inside the outline, with their regions (also in FaceInfo).
struct FinalFaces {
    std::vector<Face_handle> faces;
    std::vector<std::int32_t> region;
};

} // namespace

struct SurfaceTriangulator::Impl {
    std::vector<Vec2> outline;
    std::vector<Segment2> cuts;
    double merge = 0;
    Cdt regions_cdt;
    std::vector<RegionInfo> regions;

    void label_regions();
    std::int32_t region_at(const Vec2& p, Face_handle& hint) const;
    template <typename FullyHidden>
    void classify_refined(Cdt& cdt, const FullyHidden& fully_hidden, Face_handle& hint) const;
    FinalFaces final_faces(Cdt& cdt) const;
    bool on_cut(const Vec2& p, double snap) const;
};

// Regions: faces inside the outline (even-odd), connected across unconstrained edges.
void SurfaceTriangulator::Impl::label_regions() {
    for (Face_handle f : regions_cdt.finite_face_handles())
        f->info().region = f->info().inside ? -2 : -1;
    std::vector<Face_handle> stack;
    for (Face_handle seed : regions_cdt.finite_face_handles()) {
        if (seed->info().region != -2)
            continue;
        const auto id = std::int32_t(regions.size());
        RegionInfo info;
        double best = -1;
        seed->info().region = id;
        stack.push_back(seed);
        while (!stack.empty()) {
            Face_handle f = stack.back();
            stack.pop_back();
            const double a = face_area(f);
            double perimeter = 0;
            for (int i = 0; i < 3; ++i)
                perimeter += std::sqrt(
                    CGAL::squared_distance(f->vertex(i)->point(), f->vertex((i + 1) % 3)->point()));
            info.area += a;
            if (2 * a / perimeter > best) {
                best = 2 * a / perimeter;
                info.sample = centroid(f);
                info.inradius = best;
            }
            for (int i = 0; i < 3; ++i) {
                Face_handle n = f->neighbor(i);
                if (f->is_constrained(i) || regions_cdt.is_infinite(n) || n->info().region != -2)
                    continue;
                n->info().region = id;
                stack.push_back(n);
            }
        }
        regions.push_back(info);
    }
}

std::int32_t SurfaceTriangulator::Impl::region_at(const Vec2& p, Face_handle& hint) const {
    Face_handle f = regions_cdt.locate(to_point(p), hint);
    if (f == Face_handle() || regions_cdt.is_infinite(f))
        return -1;
    hint = f;
    return f->info().region;
}

// Whether p lies on a constrained edge of the region triangulation (outline or cut).
bool SurfaceTriangulator::Impl::on_cut(const Vec2& p, double snap) const {
    Cdt::Locate_type lt;
    int li = 0;
    Face_handle f = regions_cdt.locate(to_point(p), lt, li);
    if (f == Face_handle())
        return false;
    if (lt == Cdt::EDGE)
        return f->is_constrained(li);
    std::array<Face_handle, 4> faces{f, f->neighbor(0), f->neighbor(1), f->neighbor(2)};
    for (const Face_handle& g : faces) {
        for (int i = 0; i < 3; ++i) {
            if (!g->is_constrained(i))
                continue;
            const Vec2 a = to_vec(g->vertex(Cdt::ccw(i))->point());
            const Vec2 b = to_vec(g->vertex(Cdt::cw(i))->point());
            if (distance_to_segment(p, a, b) <= snap)
                return true;
        }
    }
    return false;
}

// The region of every face after refinement. Faces in the domain are located in the region
// triangulation (a flat face that locates nowhere takes a neighbour's region); faces out of
// it belong to a fully hidden region if they lie in one (new faces from splitting the
// region's boundary have no label yet), else to none.
template <typename FullyHidden>
void SurfaceTriangulator::Impl::classify_refined(Cdt& cdt, const FullyHidden& fully_hidden,
                                                 Face_handle& hint) const {
    for (Face_handle f : cdt.all_face_handles()) {
        f->info().index = -1;
        if (cdt.is_infinite(f)) {
            f->info().region = -1;
            continue;
        }
        std::int32_t r = f->info().region;
        if (f->is_in_domain() || r < 0)
            r = region_at(centroid(f), hint);
        if (!f->is_in_domain() && r >= 0 && !fully_hidden(r))
            r = -1;
        f->info().region = r;
    }
    for (Face_handle f : cdt.finite_face_handles())
        for (int i = 0; i < 3 && f->is_in_domain() && f->info().region < 0; ++i)
            if (f->neighbor(i)->is_in_domain())
                f->info().region = f->neighbor(i)->info().region;
}

SurfaceTriangulator::SurfaceTriangulator(const std::vector<Vec2>& outline,
                                         const std::vector<Segment2>& cuts, double merge)
    : impl_(std::make_unique<Impl>()) {
    impl_->outline = outline;
    impl_->cuts = cuts;
    impl_->merge = merge;
    try {
        insert_constraints(impl_->regions_cdt, outline, cuts, merge);
        impl_->label_regions();
    } catch (const CGAL::Failure_exception& e) {
        throw ExternalError(fmt::format("CGAL: {}", e.what()));
    }
}

SurfaceTriangulator::~SurfaceTriangulator() = default;

std::vector<RegionInfo>& SurfaceTriangulator::regions() {
    return impl_->regions;
}

const std::vector<RegionInfo>& SurfaceTriangulator::regions() const {
    return impl_->regions;
}

std::int32_t SurfaceTriangulator::region_of(const Vec2& p) const {
    Face_handle hint;
    return impl_->region_at(p, hint);
}

namespace {

bool visible(const FinalFaces& ff, const std::vector<RegionInfo>& regions, const Face_handle& f,
             int side) {
    const std::int32_t i = f->info().index;
    return i >= 0 && !regions[std::size_t(ff.region[std::size_t(i)])].hidden[side];
}

// Splits the fan of faces around v on one side into wedges (maximal runs of visible faces
// not separated by a contact line) and gives each wedge its own vertex copy; copies of a
// vertex with several wedges move off the line into their wedge by settings.nudge.
template <typename IsCut>
void split_vertex(const Cdt& cdt, const Vertex_handle& v, const FinalFaces& ff,
                  const std::vector<RegionInfo>& regions, int side, const IsCut& is_cut,
                  const RefineSettings& settings, SideMesh& out,
                  std::vector<std::array<std::uint32_t, 3>>& corner) {
    std::vector<Face_handle> fan;
    auto fc = cdt.incident_faces(v), done = fc;
    do
        fan.push_back(fc);
    while (++fc != done);
    const std::size_t n = fan.size();
    // breaks[i]: a wedge boundary lies between fan[i] and fan[i + 1].
    std::vector<bool> breaks(n, false);
    std::size_t first_break = n;
    for (std::size_t i = 0; i < n; ++i) {
        const Face_handle& f = fan[i];
        const Face_handle& g = fan[(i + 1) % n];
        breaks[i] = !visible(ff, regions, f, side) || !visible(ff, regions, g, side) ||
                    is_cut(f, f->index(g));
        if (breaks[i] && first_break == n)
            first_break = i;
    }
    std::vector<std::vector<std::size_t>> wedges;
    const std::size_t start = first_break == n ? 0 : first_break + 1;
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t i = (start + k) % n;
        if (!visible(ff, regions, fan[i], side))
            continue;
        if (wedges.empty() || breaks[(i + n - 1) % n])
            wedges.emplace_back();
        wedges.back().push_back(i);
    }
    const Vec2 p = to_vec(v->point());
    for (const auto& wedge : wedges) {
        Vec2 dir{0, 0};
        for (std::size_t i : wedge) {
            const Vec2 d = centroid(fan[i]) - p;
            dir = dir + d * (1.0 / std::max(length(d), 1e-300));
        }
        const double len = length(dir);
        const bool move = wedges.size() > 1 && len > 0;
        const auto copy = std::uint32_t(out.points.size());
        out.points.push_back(move ? p + dir * (settings.nudge / len) : p);
        for (std::size_t i : wedge)
            corner[std::size_t(fan[i]->info().index)][std::size_t(fan[i]->index(v))] = copy;
    }
}

} // namespace

SurfaceTriangulation SurfaceTriangulator::refine(const std::vector<Segment2>& extra,
                                                 const RefineSettings& settings) const {
    try {
        return refine_impl(extra, settings);
    } catch (const CGAL::Failure_exception& e) {
        throw ExternalError(fmt::format("CGAL: {}", e.what()));
    }
}

namespace {

// Delaunay refinement of the faces in the domain; false if it stopped at max_steps.
bool refine_cdt(Cdt& cdt, const std::vector<Segment2>& extra, const RefineSettings& settings) {
    const SizeField field(extra, settings.max_edge, settings.near_factor);
    CGAL::Delaunay_mesher_2<Cdt, Criteria> mesher(
        cdt, Criteria(settings.max_edge, settings.min_edge, extra.empty() ? nullptr : &field));
    mesher.init(true);
    std::size_t steps = 0;
    while (!mesher.is_refinement_done()) {
        if (++steps > settings.max_steps)
            return false;
        mesher.step_by_step_refine_mesh();
    }
    return true;
}

// One side's triangles, with vertex copies per wedge.
template <typename IsCut>
SideMesh side_mesh(const Cdt& cdt, const FinalFaces& ff, const std::vector<RegionInfo>& regions,
                   int side, const IsCut& is_cut, const RefineSettings& settings) {
    SideMesh out;
    std::vector<std::array<std::uint32_t, 3>> corner(ff.faces.size());
    for (Vertex_handle v : cdt.finite_vertex_handles())
        split_vertex(cdt, v, ff, regions, side, is_cut, settings, out, corner);
    for (std::size_t i = 0; i < ff.faces.size(); ++i) {
        if (regions[std::size_t(ff.region[i])].hidden[side]) {
            out.hidden_area += face_area(ff.faces[i]);
            continue;
        }
        out.triangles.push_back(corner[i]);
        out.face.push_back(std::uint32_t(i));
    }
    return out;
}

} // namespace

// The faces of the refined triangulation inside the outline (creases of constraint
// polylines dropped), numbered densely.
FinalFaces SurfaceTriangulator::Impl::final_faces(Cdt& cdt) const {
    FinalFaces ff;
    for (Face_handle f : cdt.finite_face_handles())
        if (f->info().region >= 0 && crease(cdt, f))
            f->info().region = -1;
    for (Face_handle f : cdt.finite_face_handles()) {
        if (f->info().region < 0)
            continue;
        f->info().index = std::int32_t(ff.faces.size());
        ff.faces.push_back(f);
        ff.region.push_back(f->info().region);
    }
    std::uint32_t vertex_id = 0;
    for (Vertex_handle v : cdt.finite_vertex_handles())
        v->info() = vertex_id++;
    return ff;
}

SurfaceTriangulation SurfaceTriangulator::refine_impl(const std::vector<Segment2>& extra,
                                                      const RefineSettings& settings) const {
    Cdt cdt;
    std::vector<Segment2> constraints = impl_->cuts;
    constraints.insert(constraints.end(), extra.begin(), extra.end());
    insert_constraints(cdt, impl_->outline, constraints, impl_->merge);
    const std::vector<RegionInfo>& regions = impl_->regions;
    auto fully_hidden = [&](std::int32_t r) {
        return regions[std::size_t(r)].hidden[0] &&
               (regions[std::size_t(r)].hidden[1] || !settings.two_sided);
    };
    Face_handle hint;
    for (Face_handle f : cdt.all_face_handles()) {
        const bool inside = !cdt.is_infinite(f) && f->info().inside;
        f->info().region = inside ? impl_->region_at(centroid(f), hint) : -1;
        f->set_in_domain(f->info().region >= 0 && !fully_hidden(f->info().region));
    }
    SurfaceTriangulation result;
    if (cdt.dimension() < 2 || regions.empty())
        return result; // collapsed below the merge distance: nothing to mesh
    result.capped = !refine_cdt(cdt, extra, settings);
    impl_->classify_refined(cdt, fully_hidden, hint);
    const FinalFaces ff = impl_->final_faces(cdt);
    result.face_count = ff.faces.size();
    // Cut edges (contact lines) separate vertex copies; discontinuity edges do not.
    std::unordered_map<std::uint64_t, bool> cut_cache;
    auto is_cut = [&](const Face_handle& f, int i) {
        if (!f->is_constrained(i))
            return false;
        const Vertex_handle a = f->vertex(Cdt::ccw(i)), b = f->vertex(Cdt::cw(i));
        const std::uint64_t key =
            (std::uint64_t(std::min(a->info(), b->info())) << 32) | std::max(a->info(), b->info());
        auto [it, fresh] = cut_cache.try_emplace(key, false);
        if (fresh)
            it->second =
                impl_->on_cut((to_vec(a->point()) + to_vec(b->point())) * 0.5, impl_->merge);
        return it->second;
    };
    for (int side = 0; side < (settings.two_sided ? 2 : 1); ++side)
        result.sides[side] = side_mesh(cdt, ff, regions, side, is_cut, settings);
    return result;
}

} // namespace penumbra::mesher
