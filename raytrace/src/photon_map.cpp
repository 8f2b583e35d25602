// The caustic map's kd-tree and density estimate (photon_map.h). nanoflann 1.4's searches
// take and return squared distances; its tree is built on one thread and searched read-only,
// each photon's disc is computed on its own, and every sum runs in the tree's fixed order, so
// estimates do not depend on the thread count.

#include "photon_map.h"

#include "core/parallel.h"

#include <nanoflann.hpp>

#include <array>
#include <cmath>
#include <limits>

namespace penumbra::raytrace {

namespace {

/// Photons whose surface normal turns further than this from the query's belong to another
/// surface (a corner's other wall).
constexpr double k_min_normal_cos = 0.9;

/// Photons of the nearest-photon estimate (Jensen 1996 uses 50 to 100).
constexpr std::size_t k_neighbours = 64;

/// Photons looked at for the nearest one on the query's surface and side: at a corner the
/// nearest few may lie on the other wall.
constexpr std::size_t k_nearest_candidates = 8;

/// The photons whose estimate is precomputed: every this many (Christensen 1999 takes every
/// fourth). They lie about twice the photons' spacing apart, a quarter of the 64 nearest
/// photons' disc: the blur this adds stays below the estimate's own.
constexpr std::size_t k_precomputed_stride = 4;

/// nanoflann's dataset adaptor over the positions of every \p stride -th photon (point i is
/// photon i × stride).
struct PhotonCloud {
    const std::vector<CausticPhoton>& photons;
    std::size_t stride = 1;

    std::size_t kdtree_get_point_count() const { return (photons.size() + stride - 1) / stride; }
    double kdtree_get_pt(std::size_t i, std::size_t axis) const {
        const Vec3& p = photons[i * stride].position;
        return axis == 0 ? p.x : axis == 1 ? p.y : p.z;
    }
    template <typename Box> bool kdtree_get_bbox(Box&) const { return false; }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<
    nanoflann::L2_Simple_Adaptor<double, PhotonCloud, double, std::size_t>, PhotonCloud, 3,
    std::size_t>;

/// Whether \p photon counts at a point of a surface facing \p normal seen from \p wo: it
/// landed on a surface facing the same way, from wo's side.
bool counts_at(const CausticPhoton& photon, const Vec3& normal, const Vec3& wo) {
    return dot(photon.normal, normal) >= k_min_normal_cos &&
           dot(wo, normal) * dot(photon.incoming, normal) > 0;
}

/// The \p k photons nearest to \p query within \p radius2 (squared), or all within it if
/// fewer, nearest first; returns how many. The search starts with the cap as its worst
/// distance instead of infinity, so it prunes every branch beyond the cap from the start.
/// One ulp above the cap keeps a photon exactly on it.
template <std::size_t k>
std::size_t nearest_within(const KdTree& tree, const double query[3], double radius2,
                           std::array<std::size_t, k>& index, std::array<double, k>& dist2) {
    nanoflann::KNNResultSet<double, std::size_t> nearest(k);
    nearest.init(index.data(), dist2.data());
    dist2[k - 1] = std::nextafter(radius2, std::numeric_limits<double>::infinity());
    tree.findNeighbors(nearest, query, nanoflann::SearchParams());
    return nearest.size();
}

/// A radius search's result set that hands every photon within the radius to a visitor.
template <typename Visit> struct WithinRadius {
    double radius2;
    Visit& visit;

    std::size_t size() const { return 0; }
    bool full() const { return true; }
    double worstDist() const { return radius2; }
    bool addPoint(double dist2, std::size_t index) {
        if (dist2 < radius2)
            visit(index);
        return true;
    }
};

/// Calls \p visit with the index of every photon in the estimate's disc around \p query;
/// returns the disc's squared radius.
template <typename Visit>
double visit_disc(const KdTree& tree, const CausticPhotons& photons, const double query[3],
                  Visit&& visit) {
    const double cap2 = photons.radius_m * photons.radius_m;
    if (photons.fixed_radius) {
        WithinRadius<Visit> within{cap2, visit};
        tree.radiusSearchCustomCallback(query, within, nanoflann::SearchParams(32, 0, false));
        return cap2;
    }
    // The disc that holds the nearest photons: small in a focused caustic, wide where the
    // photons spread thin (a metal sphere's reflection over the walls).
    std::array<std::size_t, k_neighbours> index{};
    std::array<double, k_neighbours> dist2{};
    const std::size_t found = nearest_within(tree, query, cap2, index, dist2);
    for (std::size_t i = 0; i < found; ++i)
        visit(index[i]);
    return found == k_neighbours ? dist2[found - 1] : cap2;
}

} // namespace

struct CausticMap::Tree {
    PhotonCloud cloud;
    KdTree tree;
    PhotonCloud precomputed_cloud; ///< the photons with a disc_ (k_precomputed_stride)
    KdTree precomputed;
    explicit Tree(const std::vector<CausticPhoton>& photons)
        : cloud{photons}, tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16)),
          precomputed_cloud{photons, k_precomputed_stride},
          precomputed(3, precomputed_cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {}
};

CausticMap::CausticMap(CausticPhotons photons) : photons_(std::move(photons)) {
    if (photons_.photons.empty())
        return;
    tree_ = std::make_unique<Tree>(photons_.photons);
    discs_.resize(tree_->precomputed_cloud.kdtree_get_point_count());
    parallel_for_index(discs_.size(), 64, [&](std::size_t i) {
        discs_[i] = disc_at(photons_.photons[i * k_precomputed_stride]);
    });
}

CausticMap::~CausticMap() = default;

bool CausticMap::empty() const {
    return !tree_;
}

Rgb CausticMap::radiance(const Bsdf& bsdf, const SurfaceHit& s, const Vec3& wo) const {
    if (!tree_)
        return {};
    return std::holds_alternative<LambertLobe>(bsdf.lobes()) ? precomputed(bsdf, s, wo)
                                                             : estimate(bsdf, s, wo);
}

CausticMap::PhotonDisc CausticMap::disc_at(const CausticPhoton& photon) const {
    const double query[3] = {photon.position.x, photon.position.y, photon.position.z};
    RgbD flux;
    const double r2 = visit_disc(tree_->tree, photons_, query, [&](std::size_t index) {
        const CausticPhoton& other = photons_.photons[index];
        if (counts_at(other, photon.normal, photon.incoming))
            flux += RgbD(other.power_w);
    });
    return {r2 > 0 ? flux * (1.0 / (k_pi * r2)) : RgbD{}, r2};
}

Rgb CausticMap::estimate(const Bsdf& bsdf, const SurfaceHit& s, const Vec3& wo) const {
    const double query[3] = {s.p.x, s.p.y, s.p.z};
    RgbD sum;
    const double r2 = visit_disc(tree_->tree, photons_, query, [&](std::size_t index) {
        const CausticPhoton& photon = photons_.photons[index];
        if (counts_at(photon, s.normal, wo))
            sum += RgbD(bsdf.f(wo, photon.incoming) * photon.power_w);
    });
    if (!(r2 > 0))
        return {};
    const double scale = 1.0 / (k_pi * r2);
    return {float(sum.r * scale), float(sum.g * scale), float(sum.b * scale)};
}

Rgb CausticMap::precomputed(const Bsdf& bsdf, const SurfaceHit& s, const Vec3& wo) const {
    const double query[3] = {s.p.x, s.p.y, s.p.z};
    std::array<std::size_t, k_nearest_candidates> index{};
    std::array<double, k_nearest_candidates> dist2{};
    const std::size_t found = nearest_within(tree_->precomputed, query,
                                             photons_.radius_m * photons_.radius_m, index, dist2);
    for (std::size_t i = 0; i < found; ++i) {
        const CausticPhoton& photon = photons_.photons[index[i] * k_precomputed_stride];
        if (!counts_at(photon, s.normal, wo))
            continue;
        // Outside the nearest such photon's disc the point is beyond the caustic's edge.
        const PhotonDisc& disc = discs_[index[i]];
        if (dist2[i] > disc.radius2)
            return {};
        const RgbD e = disc.irradiance_w_m2;
        const Rgb f = bsdf.f(wo, photon.incoming);
        return {float(f.r * e.r), float(f.g * e.g), float(f.b * e.b)};
    }
    return {};
}

} // namespace penumbra::raytrace
