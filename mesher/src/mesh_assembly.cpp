#include "mesh_assembly.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <fmt/format.h>

#include <algorithm>
#include <limits>

#include "core/error.h"
#include "core/material.h"
#include "core/parallel.h"

namespace penumbra::mesher {

namespace {

double area_2d(const SideMesh& side, const std::array<std::uint32_t, 3>& t) {
    const Vec2 a = side.points[t[0]], b = side.points[t[1]], c = side.points[t[2]];
    return 0.5 * std::abs(cross(b - a, c - a));
}

/// Where one surface's patches, vertices, elements and geometry elements start.
struct Offsets {
    std::size_t patch = 0, vertex = 0, element = 0, geometry = 0;
};

bool has_front(const SurfaceTriangulation& t) {
    return !t.sides[0].triangles.empty();
}
bool has_back(const Surface& s, const SurfaceTriangulation& t) {
    return s.two_sided && !t.sides[1].triangles.empty();
}

// What surface \p s adds to the mesh.
Offsets counts(const Surface& s, const SurfaceTriangulation& t) {
    Offsets n;
    std::vector<bool> visible(t.face_count, false);
    for (int side = 0; side < 2; ++side) {
        if (side == 0 ? !has_front(t) : !has_back(s, t))
            continue;
        ++n.patch;
        n.vertex += t.sides[side].points.size();
        n.element += t.sides[side].triangles.size();
        for (std::uint32_t f : t.sides[side].face)
            visible[f] = true;
    }
    n.geometry = std::size_t(std::count(visible.begin(), visible.end(), true));
    return n;
}

// Writes one side as patch \p at.patch; returns the element of each face (-1 where absent).
std::vector<std::int32_t> write_side(RadiosityMesh& mesh, const Surface& s, const SideMesh& side,
                                     const Patch& patch, std::size_t face_count, Offsets& at) {
    std::vector<std::int32_t> element_of(face_count, -1);
    const auto patch_id = std::uint32_t(at.patch++);
    mesh.patches[patch_id] = patch;
    const auto base = std::uint32_t(at.vertex);
    for (const Vec2& p : side.points) {
        mesh.positions[at.vertex] = Vec3f(s.to_3d(p));
        mesh.vertex_patch[at.vertex++] = patch_id;
    }
    for (std::size_t i = 0; i < side.triangles.size(); ++i) {
        const auto& t = side.triangles[i];
        std::array<std::uint32_t, 3> tri =
            patch.back ? std::array<std::uint32_t, 3>{t[0], t[2], t[1]} : t;
        for (auto& v : tri)
            v += base;
        const std::size_t e = at.element++;
        element_of[side.face[i]] = std::int32_t(e);
        mesh.triangles[e] = tri;
        mesh.element_patch[e] = patch_id;
        mesh.element_twin[e] = -1;
        mesh.element_area[e] = area_2d(side, t);
        mesh.element_level[e] = 0;
    }
    return element_of;
}

void write_surface(RadiosityMesh& mesh, const Scene& scene, const Surface& s,
                   const SurfaceTriangulation& tri, Offsets at, std::size_t surface_index) {
    const Polygon& poly = scene.polygons[s.polygon];
    const RadiosityResponse response = radiosity_response(scene.materials[poly.material]);
    Patch front;
    front.polygon = s.polygon;
    front.surface = s.id;
    front.material = poly.material;
    front.normal = s.normal;
    front.reflectance = response.reflectance;
    front.diffuse_transmittance = response.diffuse_transmittance;
    front.specular_only = response.specular_only;
    front.emission = response.emission * float(k_pi);
    front.glazing = glazing_of(scene.materials[poly.material]);
    Patch back = front;
    back.back = true;
    back.normal = -s.normal;
    back.emission = response.emission_two_sided ? front.emission : Rgb{};
    const auto none = std::vector<std::int32_t>(tri.face_count, -1);
    const auto f =
        has_front(tri) ? write_side(mesh, s, tri.sides[0], front, tri.face_count, at) : none;
    const auto b =
        has_back(s, tri) ? write_side(mesh, s, tri.sides[1], back, tri.face_count, at) : none;
    for (std::size_t i = 0; i < tri.face_count; ++i) {
        if (f[i] >= 0 && b[i] >= 0) {
            mesh.element_twin[std::size_t(f[i])] = b[i];
            mesh.element_twin[std::size_t(b[i])] = f[i];
        }
        if (f[i] >= 0 || b[i] >= 0)
            mesh.geometry_elements[at.geometry++] = std::uint32_t(f[i] >= 0 ? f[i] : b[i]);
    }
    mesh.surfaces[surface_index] = {s.polygon, s.area, tri.sides[0].hidden_area,
                                    s.two_sided ? tri.sides[1].hidden_area : 0.0};
}

} // namespace

void append_surfaces(RadiosityMesh& mesh, const Scene& scene, const std::vector<Surface>& surfaces,
                     const std::vector<SurfaceTriangulation>& tris, const Context& ctx) {
    std::vector<Offsets> at(surfaces.size() + 1);
    at[0] = {mesh.patches.size(), mesh.vertex_count(), mesh.element_count(),
             mesh.geometry_elements.size()};
    run_in_arena(ctx, [&] {
        parallel_for_index(surfaces.size(), 64,
                           [&](std::size_t i) { at[i + 1] = counts(surfaces[i], tris[i]); });
    });
    for (std::size_t i = 0; i < surfaces.size(); ++i) { // prefix sums
        at[i + 1].patch += at[i].patch;
        at[i + 1].vertex += at[i].vertex;
        at[i + 1].element += at[i].element;
        at[i + 1].geometry += at[i].geometry;
    }
    const Offsets& end = at.back();
    const std::size_t first_surface = mesh.surfaces.size();
    mesh.patches.resize(end.patch);
    mesh.positions.resize(end.vertex);
    mesh.vertex_patch.resize(end.vertex);
    mesh.triangles.resize(end.element);
    mesh.element_patch.resize(end.element);
    mesh.element_twin.resize(end.element);
    mesh.element_area.resize(end.element);
    mesh.element_level.resize(end.element);
    mesh.geometry_elements.resize(end.geometry);
    mesh.surfaces.resize(first_surface + surfaces.size());
    run_in_arena(ctx, [&] {
        parallel_for_index(surfaces.size(), 64, [&](std::size_t i) {
            write_surface(mesh, scene, surfaces[i], tris[i], at[i], first_surface + i);
        });
    });
}

void check_patches(const RadiosityMesh& mesh, const Context& ctx) {
    using TriMesh = OpenMesh::TriMesh_ArrayKernelT<>;
    // The elements of each patch, grouped by a counting sort (linear in the mesh size).
    std::vector<std::uint32_t> first(mesh.patches.size() + 1, 0);
    for (std::size_t e = 0; e < mesh.element_count(); ++e)
        ++first[mesh.element_patch[e] + 1];
    for (std::size_t p = 0; p < mesh.patches.size(); ++p)
        first[p + 1] += first[p];
    std::vector<std::uint32_t> elements(mesh.element_count());
    std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
    for (std::size_t e = 0; e < mesh.element_count(); ++e)
        elements[fill[mesh.element_patch[e]]++] = std::uint32_t(e);
    // Per thread: one vertex-handle table for all its patches; only the entries a patch used
    // are reset. The first non-manifold element of each failing patch, lowest patch wins.
    struct Scratch {
        std::vector<TriMesh::VertexHandle> handle;
        std::vector<std::uint32_t> used;
        std::size_t failed_patch = std::numeric_limits<std::size_t>::max();
        std::uint32_t failed_element = 0;
    };
    tbb::enumerable_thread_specific<Scratch> scratch;
    run_in_arena(ctx, [&] {
        parallel_for_index(mesh.patches.size(), 256, [&](std::size_t p) {
            Scratch& s = scratch.local();
            if (s.handle.empty())
                s.handle.resize(mesh.vertex_count());
            TriMesh tm;
            for (std::uint32_t i = first[p]; i < first[p + 1]; ++i) {
                const std::uint32_t e = elements[i];
                std::array<TriMesh::VertexHandle, 3> vh;
                for (std::size_t k = 0; k < 3; ++k) {
                    const std::uint32_t v = mesh.triangles[e][k];
                    if (!s.handle[v].is_valid()) {
                        s.handle[v] = tm.add_vertex(TriMesh::Point(0, 0, 0));
                        s.used.push_back(v);
                    }
                    vh[k] = s.handle[v];
                }
                if (!tm.add_face(vh[0], vh[1], vh[2]).is_valid()) {
                    if (p < s.failed_patch) {
                        s.failed_patch = p;
                        s.failed_element = e;
                    }
                    break;
                }
            }
            for (std::uint32_t v : s.used)
                s.handle[v] = TriMesh::VertexHandle();
            s.used.clear();
        });
    });
    const Scratch* worst = nullptr;
    for (const Scratch& s : scratch)
        if (!worst || s.failed_patch < worst->failed_patch)
            worst = &s;
    if (worst && worst->failed_patch < mesh.patches.size())
        throw InternalError(fmt::format(
            "mesher: patch {} (surface {}) is not a manifold "
            "triangle mesh at element {}",
            worst->failed_patch, mesh.patches[worst->failed_patch].surface, worst->failed_element));
}

} // namespace penumbra::mesher
