#include "lightmap_emitters.h"

#include <algorithm>
#include <array>

#include "core/parallel.h"

namespace penumbra::app {

namespace {

struct Emitter {
    std::uint32_t element = 0;
    Vec3 normal;
    std::array<Vec3, 4> targets; ///< centroid, corners pulled 2 % towards it; lifted off
};

struct PolygonProbe {
    Vec3 normal;
    std::vector<Vec3> points; ///< element centroids, lifted off the polygon
    bool planar = true;       ///< every element's normal the first one's
};

std::vector<Emitter> emitters_of(const RadiosityMesh& sources, double lift) {
    std::vector<Emitter> out;
    for (std::uint32_t e = 0; e < sources.element_count(); ++e) {
        const Patch& patch = sources.patch_of(e);
        if (patch.emission.is_black())
            continue;
        const auto& t = sources.triangles[e];
        const std::array<Vec3, 3> v{sources.vertex(t[0]), sources.vertex(t[1]),
                                    sources.vertex(t[2])};
        const Vec3 c = (v[0] + v[1] + v[2]) / 3.0, up = patch.normal * lift;
        out.push_back({e,
                       patch.normal,
                       {c + up, v[0] * 0.98 + c * 0.02 + up, v[1] * 0.98 + c * 0.02 + up,
                        v[2] * 0.98 + c * 0.02 + up}});
    }
    return out;
}

// Per polygon, its probe points: two per front element, lifted off the polygon.
std::vector<PolygonProbe> probes_of(const RadiosityMesh& mesh, double lift) {
    std::uint32_t polygons = 0;
    for (const Patch& p : mesh.patches)
        polygons = std::max(polygons, p.polygon + 1);
    std::vector<std::vector<std::uint32_t>> elements(polygons);
    for (std::uint32_t e = 0; e < mesh.element_count(); ++e) {
        const Patch& patch = mesh.patch_of(e);
        if (!patch.back)
            elements[patch.polygon].push_back(e);
    }
    std::vector<PolygonProbe> out(polygons);
    for (std::uint32_t p = 0; p < polygons; ++p) {
        const std::vector<std::uint32_t>& list = elements[p];
        if (list.empty())
            continue;
        out[p].normal = mesh.patch_of(list[0]).normal;
        for (const std::uint32_t e : list)
            out[p].planar = out[p].planar && dot(mesh.patch_of(e).normal, out[p].normal) > 1 - 1e-6;
        // Every element gives two points, its centroid and one corner pulled a fifth of the way
        // in: a lamp seen through a door from part of a corridor's floor shows on some of them.
        for (std::size_t k = 0; k < list.size(); ++k) {
            const auto& t = mesh.triangles[list[k]];
            const Vec3 c = (mesh.vertex(t[0]) + mesh.vertex(t[1]) + mesh.vertex(t[2])) / 3.0;
            const Vec3 corner = mesh.vertex(t[k % 3]) * 0.8 + c * 0.2;
            out[p].points.push_back(c + out[p].normal * lift);
            out[p].points.push_back(corner + out[p].normal * lift);
        }
    }
    return out;
}

// Whether \p emitter faces some probe point and some of its targets lies in front of the
// polygon: else no point of the polygon receives its light.
bool facing(const PolygonProbe& probe, const Emitter& emitter) {
    const auto in_front_of_emitter = [&](const Vec3& p) {
        return dot(p - emitter.targets[0], emitter.normal) > 0;
    };
    const auto in_front_of_polygon = [&](const Vec3& t) {
        return dot(t - probe.points[0], probe.normal) > 0;
    };
    return std::any_of(probe.points.begin(), probe.points.end(), in_front_of_emitter) &&
           std::any_of(emitter.targets.begin(), emitter.targets.end(), in_front_of_polygon);
}

} // namespace

std::vector<std::vector<std::uint32_t>> emitters_seen_by_polygons(const RadiosityMesh& mesh,
                                                                  const RadiosityMesh& sources,
                                                                  const VisibilityQuery& visibility,
                                                                  const Context& ctx) {
    // Ten ray offsets off each surface, as the fill's own probes start.
    const double lift = 1e-4 * std::max(mesh.scene_diagonal, 1e-3);
    const std::vector<Emitter> emitters = emitters_of(sources, lift);
    const std::vector<PolygonProbe> probes = probes_of(mesh, lift);
    std::vector<std::vector<std::uint32_t>> seen(probes.size());
    run_in_arena(ctx, [&] {
        parallel_for_index(probes.size(), 4, [&](std::size_t p) {
            const PolygonProbe& probe = probes[p];
            if (probe.points.empty())
                return;
            // A curved polygon's parts face different ways: its probes would not speak for
            // all of it, so it keeps every emitter.
            if (!probe.planar) {
                for (const Emitter& emitter : emitters)
                    seen[p].push_back(emitter.element);
                return;
            }
            // Per emitter, a line from every probe point to its targets in turn, until one is
            // open.
            std::vector<Segment> lines;
            std::vector<std::uint8_t> blocked;
            for (const Emitter& emitter : emitters) {
                if (!facing(probe, emitter))
                    continue;
                lines.clear();
                for (std::size_t k = 0; k < probe.points.size(); ++k) {
                    const Vec3& from = probe.points[k];
                    const Vec3& to = emitter.targets[k % 4];
                    lines.push_back({Vec3f(from), Vec3f(to - from), 0.0f, 1.0f});
                }
                blocked.resize(lines.size());
                visibility.occluded(lines, blocked);
                if (std::any_of(blocked.begin(), blocked.end(), [](std::uint8_t b) { return !b; }))
                    seen[p].push_back(emitter.element);
            }
        });
    });
    std::size_t listed = 0, polygons = 0;
    for (std::size_t p = 0; p < seen.size(); ++p)
        if (!probes[p].points.empty()) {
            listed += seen[p].size();
            ++polygons;
        }
    ctx.debug("lightmap: {} polygons see {:.1f} of {} emitting triangles on average", polygons,
              double(listed) / double(std::max<std::size_t>(polygons, 1)), emitters.size());
    return seen;
}

} // namespace penumbra::app
