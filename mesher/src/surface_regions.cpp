// Hidden-region classification. A region side is hidden when a cover of that side contains
// the region, or when EnclosureTest finds it enclosed. Passes repeat with the previous pass's
// result as the HiddenAt oracle (Jacobi style, so the outcome does not depend on thread
// scheduling): the inside of a block standing on a floor sees the floor under the block,
// which the first pass has found hidden.

#include "surface_regions.h"

#include <array>

#include "constraint_cleanup.h"
#include "core/error.h"
#include "core/parallel.h"
#include "hidden.h"

namespace penumbra::mesher {

namespace {

std::vector<Segment2> cut_constraints(const Surface& s, const SurfaceContacts& c,
                                      const MeshParams& params) {
    std::vector<Segment2> raw = c.cuts;
    for (const Cover& cover : c.covers)
        for (std::size_t i = 0; i < cover.polygon.size(); ++i)
            raw.push_back({cover.polygon[i], cover.polygon[(i + 1) % cover.polygon.size()]});
    return clean_segments(s.outline2d, raw, {}, params.snap, params.merge);
}

PreparedSurface prepare_one(const Surface& s, const SurfaceContacts& c,
                            const std::vector<ReceiverSegment>& disc, const MeshParams& params) {
    PreparedSurface out;
    out.cuts = cut_constraints(s, c, params);
    if (params.split_contacts)
        out.triangulator =
            std::make_unique<SurfaceTriangulator>(s.outline2d, out.cuts, params.merge);
    std::vector<Segment2> raw;
    for (const ReceiverSegment& d : disc)
        raw.push_back(d.segment);
    out.extra = clean_segments(s.outline2d, raw, out.cuts, params.snap, params.merge);
    return out;
}

bool covered(const std::vector<Cover>& covers, const Vec2& p, int side) {
    for (const Cover& c : covers)
        if ((side == 0 ? c.front : c.back) && point_in_polygon(p, c.polygon))
            return true;
    return false;
}

using Flags = std::vector<std::vector<std::array<bool, 2>>>; // [surface][region][side]

// One classification pass over every region side not yet hidden.
Flags classify_pass(const std::vector<Surface>& surfaces,
                    const std::vector<SurfaceContacts>& contacts,
                    const std::vector<PreparedSurface>& prepared, const EnclosureTest& enclosure,
                    const Flags& previous, bool use_previous, const Context& ctx) {
    Flags next = previous;
    const EnclosureTest::HiddenAt hidden_at = [&](std::uint32_t t, const Vec3& p, bool back) {
        const std::int32_t r = prepared[t].triangulator->region_of(surfaces[t].to_2d(p));
        return r >= 0 && previous[t][std::size_t(r)][back ? 1 : 0];
    };
    run_in_arena(ctx, [&] {
        parallel_for_index(surfaces.size(), 4, [&](std::size_t i) {
            const Surface& s = surfaces[i];
            const auto& regions = prepared[i].triangulator->regions();
            for (std::size_t r = 0; r < regions.size(); ++r) {
                for (int side = 0; side < (s.two_sided ? 2 : 1); ++side) {
                    if (previous[i][r][std::size_t(side)])
                        continue;
                    const Vec2 p = regions[r].sample;
                    next[i][r][std::size_t(side)] =
                        covered(contacts[i].covers, p, side) ||
                        enclosure.enclosed(s.to_3d(p), side == 0 ? s.normal : -s.normal, s.id,
                                           regions[r].inradius,
                                           use_previous ? hidden_at : EnclosureTest::HiddenAt());
                }
            }
        });
    });
    return next;
}

void classify_regions(const Scene& scene, const std::vector<Surface>& surfaces,
                      const SurfaceBvh& bvh, const std::vector<SurfaceContacts>& contacts,
                      std::vector<PreparedSurface>& prepared, const MeshParams& params,
                      const Context& ctx) {
    const EnclosureTest enclosure(scene, surfaces, bvh, params);
    Flags flags(surfaces.size());
    for (std::size_t i = 0; i < surfaces.size(); ++i)
        flags[i].assign(prepared[i].triangulator->regions().size(), {false, false});
    for (int pass = 0; pass < 4; ++pass) {
        Flags next = classify_pass(surfaces, contacts, prepared, enclosure, flags, pass > 0, ctx);
        const bool stable = next == flags && pass > 0;
        flags = std::move(next);
        if (stable)
            break;
    }
    for (std::size_t i = 0; i < surfaces.size(); ++i) {
        auto& regions = prepared[i].triangulator->regions();
        for (std::size_t r = 0; r < regions.size(); ++r)
            for (int side = 0; side < 2; ++side)
                regions[r].hidden[side] = flags[i][r][std::size_t(side)];
    }
}

} // namespace

std::vector<PreparedSurface>
prepare_surfaces(const Scene& scene, const std::vector<Surface>& surfaces, const SurfaceBvh& bvh,
                 const std::vector<SurfaceContacts>& contacts,
                 const std::vector<std::vector<ReceiverSegment>>& discontinuities,
                 const MeshParams& params, const Context& ctx) {
    std::vector<PreparedSurface> prepared(surfaces.size());
    run_in_arena(ctx, [&] {
        parallel_for_index(surfaces.size(), 4, [&](std::size_t i) {
            try {
                prepared[i] = prepare_one(surfaces[i], contacts[i], discontinuities[i], params);
            } catch (const ExternalError& e) {
                throw InputError(
                    "", "",
                    fmt::format("cannot triangulate surface {}: {}", surfaces[i].name, e.what()));
            }
        });
    });
    if (params.split_contacts)
        classify_regions(scene, surfaces, bvh, contacts, prepared, params, ctx);
    return prepared;
}

} // namespace penumbra::mesher
