// The caustic map's kd-tree and density estimate (photon_map.h). nanoflann 1.4's searches
// take and return squared distances; its tree is built on one thread and searched read-only,
// and the sum runs in the tree's fixed order, so estimates do not depend on the thread count.

#include "photon_map.h"

#include <nanoflann.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace penumbra::raytrace {

namespace {

/// Photons whose surface normal turns further than this from the query's belong to another
/// surface (a corner's other wall).
constexpr double k_min_normal_cos = 0.9;

/// nanoflann's dataset adaptor over the photons' positions.
struct PhotonCloud {
    const std::vector<CausticPhoton>& photons;

    std::size_t kdtree_get_point_count() const { return photons.size(); }
    double kdtree_get_pt(std::size_t i, std::size_t axis) const {
        const Vec3& p = photons[i].position;
        return axis == 0 ? p.x : axis == 1 ? p.y : p.z;
    }
    template <typename Box> bool kdtree_get_bbox(Box&) const { return false; }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<
    nanoflann::L2_Simple_Adaptor<double, PhotonCloud, double, std::size_t>, PhotonCloud, 3,
    std::size_t>;

/// The reflected flux of one photon at \p s, if it landed on the same side of a surface
/// facing the same way.
RgbD reflected_flux(const CausticPhoton& photon, const Bsdf& bsdf, const SurfaceHit& s,
                    const Vec3& wo) {
    if (dot(photon.normal, s.normal) < k_min_normal_cos ||
        !SurfaceGeometry::geometric_side_agrees(s, wo, photon.incoming, false))
        return {};
    return RgbD(bsdf.f(wo, photon.incoming) * photon.power_w);
}

/// A radius search's result set that sums the photons' reflected flux as it finds them.
struct ReflectedFlux {
    const std::vector<CausticPhoton>& photons;
    const Bsdf& bsdf;
    const SurfaceHit& s;
    const Vec3& wo;
    double radius2;
    RgbD sum;

    std::size_t size() const { return 0; }
    bool full() const { return true; }
    double worstDist() const { return radius2; }
    bool addPoint(double dist2, std::size_t index) {
        if (dist2 < radius2)
            sum += reflected_flux(photons[index], bsdf, s, wo);
        return true;
    }
};

} // namespace

struct CausticMap::Tree {
    PhotonCloud cloud;
    KdTree tree;
    explicit Tree(const std::vector<CausticPhoton>& photons)
        : cloud{photons}, tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {}
};

std::size_t CausticMap::nearest_within(const double query[3], double radius2,
                                       std::array<std::size_t, k_neighbours>& index,
                                       std::array<double, k_neighbours>& dist2) const {
    // The k-nearest search starts with the cap as its worst distance instead of infinity, so
    // it prunes every branch beyond the cap from the start; the photons it keeps are those
    // of the uncapped search within the cap, in the same order. One ulp above the cap keeps
    // a photon exactly on it.
    nanoflann::KNNResultSet<double, std::size_t> nearest(k_neighbours);
    nearest.init(index.data(), dist2.data());
    dist2[k_neighbours - 1] = std::nextafter(radius2, std::numeric_limits<double>::infinity());
    tree_->tree.findNeighbors(nearest, query, nanoflann::SearchParams());
    return nearest.size();
}

CausticMap::CausticMap(CausticPhotons photons) : photons_(std::move(photons)) {
    if (!photons_.photons.empty())
        tree_ = std::make_unique<Tree>(photons_.photons);
}

CausticMap::~CausticMap() = default;

bool CausticMap::empty() const {
    return !tree_;
}

Rgb CausticMap::radiance(const Bsdf& bsdf, const SurfaceHit& s, const Vec3& wo) const {
    if (!tree_)
        return {};
    const double query[3] = {s.p.x, s.p.y, s.p.z};
    double r2 = photons_.radius_m * photons_.radius_m;
    RgbD sum;
    if (photons_.fixed_radius) {
        ReflectedFlux flux{photons_.photons, bsdf, s, wo, r2, {}};
        tree_->tree.radiusSearchCustomCallback(query, flux, nanoflann::SearchParams(32, 0, false));
        sum = flux.sum;
    } else {
        // The disc that holds the nearest photons: small in a focused caustic, wide where the
        // photons spread thin (a metal sphere's reflection over the walls).
        std::array<std::size_t, k_neighbours> index{};
        std::array<double, k_neighbours> dist2{};
        const std::size_t found = nearest_within(query, r2, index, dist2);
        if (found == k_neighbours)
            r2 = dist2[found - 1];
        for (std::size_t i = 0; i < found; ++i)
            sum += reflected_flux(photons_.photons[index[i]], bsdf, s, wo);
    }
    if (!(r2 > 0))
        return {};
    const double scale = 1.0 / (k_pi * r2);
    return {float(sum.r * scale), float(sum.g * scale), float(sum.b * scale)};
}

} // namespace penumbra::raytrace
