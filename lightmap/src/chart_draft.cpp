#include "chart_draft.h"

#include <algorithm>
#include <unordered_map>

#include "chart_checks.h"

namespace penumbra::lightmap {

ChartDraft make_draft(const InputMesh& mesh, std::vector<std::uint32_t> triangles) {
    ChartDraft draft;
    draft.triangles = std::move(triangles);
    std::unordered_map<std::uint32_t, std::uint32_t> local;
    for (std::uint32_t t : draft.triangles) {
        std::array<std::uint32_t, 3> c{};
        for (std::size_t k = 0; k < 3; ++k) {
            const std::uint32_t v = mesh.triangles[t].corners[k];
            const auto [it, added] = local.try_emplace(v, std::uint32_t(draft.vertices.size()));
            if (added)
                draft.vertices.push_back(v);
            c[k] = it->second;
        }
        draft.corners.push_back(c);
    }
    draft.uv.assign(draft.vertices.size(), Vec2{});
    return draft;
}

void project_onto_plane(const InputMesh& mesh, const Vec3& normal, ChartDraft& draft) {
    const Frame frame = Frame::from_normal(normal);
    const Vec3 origin = mesh.positions[draft.vertices[0]];
    for (std::size_t i = 0; i < draft.vertices.size(); ++i) {
        const Vec3 d = mesh.positions[draft.vertices[i]] - origin;
        draft.uv[i] = {dot(d, frame.s), dot(d, frame.t)};
    }
}

bool draft_valid(const InputMesh& mesh, const ChartDraft& draft) {
    std::vector<Triangle2> uv;
    std::vector<double> area;
    for (std::size_t i = 0; i < draft.triangles.size(); ++i) {
        uv.push_back(draft.uv_triangle(i));
        area.push_back(mesh.triangles[draft.triangles[i]].area_m2);
    }
    return uv_layout_valid(uv, area, false);
}

} // namespace penumbra::lightmap
