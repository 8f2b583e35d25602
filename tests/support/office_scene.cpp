// The office-floor generator. Geometry with the default furniture and no windows is exactly
// the floor mesh_bench has always meshed, so its figures stay comparable across versions.

#include "office_scene.h"

#include "core/error.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace penumbra::bench {

namespace {

constexpr double k_room_w = 4.0, k_room_d = 3.5, k_height = 2.8;
constexpr double k_sill = 0.9, k_head = 2.1, k_window_w = 1.2;
constexpr std::uint32_t k_wall = 0, k_desk = 1, k_panel = 2;

// Desk and cabinet corners in an office, clear of each other, the doors and the sensor.
constexpr std::pair<double, double> k_desk_slots[] = {
    {0.4, 0.5}, {2.1, 2.2}, {2.1, 0.5}, {0.4, 2.2}};
constexpr std::pair<double, double> k_cabinet_slots[] = {{3.0, 0.0}, {2.1, 0.0}};
constexpr char k_slot_names[] = "abcd";

/// Appends rectangles (o, o + u, o + u + v, o + v), each split into k × k quads.
class FloorBuilder {
public:
    FloorBuilder(Scene& scene, int k) : scene_(scene), k_(k) {}

    void rect(const std::string& name, std::uint32_t m, const Vec3& o, const Vec3& u,
              const Vec3& v) {
        // Neighbouring quads compute shared corners by the same expression: bitwise equal.
        auto at = [&](int i, int j) { return o + u * (double(i) / k_) + v * (double(j) / k_); };
        const std::string source = "office:" + name;
        for (int j = 0; j < k_; ++j)
            for (int i = 0; i < k_; ++i) {
                Polygon quad{
                    {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}, m, name, source};
                scene_.polygons.push_back(std::move(quad));
            }
    }

    // An axis-aligned box [lo, hi] with outward faces; without a bottom face if open_bottom.
    void box(const std::string& name, std::uint32_t m, const Vec3& lo, const Vec3& hi,
             bool open_bottom) {
        const Vec3 d = hi - lo;
        const Vec3 ex(d.x, 0, 0), ey(0, d.y, 0), ez(0, 0, d.z);
        rect(name + "_top", m, lo + ez, ex, ey);
        rect(name + "_y0", m, lo, ex, ez);
        rect(name + "_y1", m, lo + ey + ex, ex * -1.0, ez);
        rect(name + "_x0", m, lo + ey, ey * -1.0, ez);
        rect(name + "_x1", m, lo + ex, ey, ez);
        if (!open_bottom)
            rect(name + "_bottom", m, lo, ey, ex);
    }

    void desk(const std::string& name, double x, double y) {
        box(name + "_top", k_desk, {x, y, 0.69}, {x + 1.6, y + 0.8, 0.72}, false);
        for (double lx : {x + 0.05, x + 1.5})
            for (double ly : {y + 0.05, y + 0.7})
                box(name + "_leg", k_desk, {lx, ly, 0}, {lx + 0.05, ly + 0.05, 0.69}, true);
    }

    // A partition along x = x0 from y0 to y1 with a 0.9 × 2.1 m door, as three rectangles.
    void partition_x(double x0, double y0, double y1) {
        const double door = y0 + 0.5;
        rect("partition", k_wall, {x0, y0, 0}, {0, 0, k_height}, {0, door - y0, 0});
        rect("partition", k_wall, {x0, door + 0.9, 0}, {0, 0, k_height}, {0, y1 - door - 0.9, 0});
        rect("lintel", k_wall, {x0, door, 2.1}, {0, 0, k_height - 2.1}, {0, 0.9, 0});
    }

    void partition_y(double y0, double x0, double x1) {
        const double door = x0 + 0.5;
        rect("partition", k_wall, {x0, y0, 0}, {door - x0, 0, 0}, {0, 0, k_height});
        rect("partition", k_wall, {door + 0.9, y0, 0}, {x1 - door - 0.9, 0, 0}, {0, 0, k_height});
        rect("lintel", k_wall, {door, y0, 2.1}, {0.9, 0, 0}, {0, 0, k_height - 2.1});
    }

    /// The wall rectangle (o, u, v), whose horizontal side is u if u_horizontal, else v, with
    /// window openings [a, b] (metres along the horizontal side, sorted, disjoint) from sill
    /// to head: a strip below the sills, one above the heads and the piers between openings.
    void wall(const std::string& name, const Vec3& o, const Vec3& u, const Vec3& v,
              bool u_horizontal, const std::vector<std::pair<double, double>>& openings) {
        if (openings.empty()) {
            rect(name, k_wall, o, u, v);
            return;
        }
        const Vec3 along = u_horizontal ? u : v, up = u_horizontal ? v : u;
        const double run = length(along), rise = length(up);
        // The part [a, b] × [c, d] (metres along and up), wound as the wall.
        auto piece = [&](double a, double b, double c, double d) {
            const Vec3 corner = o + along * (a / run) + up * (c / rise);
            const Vec3 du = along * ((b - a) / run), dv = up * ((d - c) / rise);
            if (u_horizontal)
                rect(name, k_wall, corner, du, dv);
            else
                rect(name, k_wall, corner, dv, du);
        };
        piece(0, run, 0, k_sill);
        piece(0, run, k_head, rise);
        double from = 0;
        for (const auto& [a, b] : openings) {
            piece(from, a, k_sill, k_head);
            from = b;
        }
        piece(from, run, k_sill, k_head);
    }

private:
    Scene& scene_;
    int k_;
};

/// Window openings along an exterior wall of \p rooms offices of width \p side each.
std::vector<std::pair<double, double>> openings(int rooms, double side, int per_room) {
    std::vector<std::pair<double, double>> out;
    const double half = 0.5 * std::min(k_window_w, 0.6 * side / std::max(per_room, 1));
    for (int r = 0; r < rooms; ++r)
        for (int w = 0; w < per_room; ++w) {
            const double centre = side * (r + (w + 0.5) / per_room);
            out.emplace_back(centre - half, centre + half);
        }
    return out;
}

void check(const OfficeParams& p) {
    if (p.rooms_x < 1 || p.rooms_y < 1 || p.tessellation < 1)
        throw ConfigError(fmt::format("office floor: rooms {} x {} and tessellation {} must be "
                                      "at least 1",
                                      p.rooms_x, p.rooms_y, p.tessellation));
    auto in = [](int value, int hi) { return value >= 0 && value <= hi; };
    if (!in(p.desks_per_room, 4) || !in(p.cabinets_per_room, 2) || !in(p.windows_per_room, 2))
        throw ConfigError(fmt::format("office floor: {} desks, {} cabinets and {} windows per "
                                      "office are out of range (0-4, 0-2, 0-2)",
                                      p.desks_per_room, p.cabinets_per_room, p.windows_per_room));
}

void add_shell(FloorBuilder& b, const OfficeParams& p) {
    const double W = k_room_w * p.rooms_x, D = k_room_d * p.rooms_y, h = k_height;
    const auto along_x = openings(p.rooms_x, k_room_w, p.windows_per_room);
    const auto along_y = openings(p.rooms_y, k_room_d, p.windows_per_room);
    b.rect("floor", k_wall, {0, 0, 0}, {W, 0, 0}, {0, D, 0});
    b.rect("ceiling", k_wall, {0, 0, h}, {0, D, 0}, {W, 0, 0});
    b.wall("wall_y0", {0, 0, 0}, {0, 0, h}, {W, 0, 0}, false, along_x);
    b.wall("wall_y1", {0, D, 0}, {W, 0, 0}, {0, 0, h}, true, along_x);
    b.wall("wall_x0", {0, 0, 0}, {0, D, 0}, {0, 0, h}, true, along_y);
    b.wall("wall_x1", {W, 0, 0}, {0, 0, h}, {0, D, 0}, false, along_y);
    for (int i = 1; i < std::max(p.rooms_x, p.rooms_y); ++i) {
        if (i < p.rooms_x)
            b.partition_x(k_room_w * i, 0, D);
        if (i < p.rooms_y)
            b.partition_y(k_room_d * i, 0, W);
    }
}

void add_office(FloorBuilder& b, Scene& s, const OfficeParams& p, int i, int j) {
    const double x = k_room_w * i, y = k_room_d * j;
    const std::string tag = std::to_string(i) + "_" + std::to_string(j);
    for (int d = 0; d < p.desks_per_room; ++d)
        b.desk(std::string("desk_") + k_slot_names[d] + tag, x + k_desk_slots[d].first,
               y + k_desk_slots[d].second);
    for (int c = 0; c < p.cabinets_per_room; ++c) {
        const Vec3 lo(x + k_cabinet_slots[c].first, y + k_cabinet_slots[c].second, 0);
        b.box((c == 0 ? "cabinet" : "cabinet_b") + tag, k_desk, lo, lo + Vec3(0.8, 0.4, 1.2), true);
    }
    b.rect("panel" + tag, k_panel, {x + 1.4, y + 1.45, k_height - 0.01}, {0, 0.6, 0}, {1.2, 0, 0});
    s.sensors.push_back({"workplane" + tag, {x + 2.0, y + 1.75, 0.8}, {0, 0, 1}});
}

} // namespace

Scene office_floor(const OfficeParams& params) {
    check(params);
    Scene s;
    s.name = "office";
    s.materials = {{"wall", Rgb(0.7f)}, {"desk", Rgb(0.4f)}, {"panel", Rgb(0.0f), Rgb(30.0f)}};
    // The panel keeps its back side (the default): black, it absorbs what light reaches the
    // 1 cm gap above it, which a one-sided panel would lose from the power balance.
    FloorBuilder b(s, params.tessellation);
    add_shell(b, params);
    for (int i = 0; i < params.rooms_x; ++i)
        for (int j = 0; j < params.rooms_y; ++j)
            add_office(b, s, params, i, j);
    Camera camera;
    camera.eye = {0.3, 0.3, 1.6};
    camera.look_at = {k_room_w, k_room_d, 0.9};
    camera.up = {0, 0, 1};
    camera.fov_deg = 75;
    camera.width = 320;
    camera.height = 240;
    s.camera = camera;
    return s;
}

std::int64_t input_triangle_count(const Scene& scene) {
    std::int64_t n = 0;
    for (const Polygon& p : scene.polygons)
        n += std::max<std::int64_t>(std::int64_t(p.vertices.size()) - 2, 0);
    return n;
}

OfficeParams office_params_for_triangles(std::int64_t target, const OfficeParams& base) {
    OfficeParams p = base;
    p.tessellation = std::max(1, int(std::pow(double(target) / 1000.0, 0.25)));
    const auto per_k2 = std::int64_t(p.tessellation) * p.tessellation;
    auto triangles = [&](int nx, int ny) {
        OfficeParams flat = p;
        flat.rooms_x = nx;
        flat.rooms_y = ny;
        flat.tessellation = 1; // every polygon is a rectangle: k × k splits multiply by k²
        return input_triangle_count(office_floor(flat)) * per_k2;
    };
    // Grow 1×1, 2×1, 2×2, 3×2, ... until the target is passed; keep the closer of the last two.
    int nx = 1, ny = 1;
    std::int64_t count = triangles(nx, ny);
    while (count < target) {
        const int next_x = nx == ny ? nx + 1 : nx, next_y = nx == ny ? ny : ny + 1;
        const std::int64_t next = triangles(next_x, next_y);
        if (next - target > target - count)
            break;
        nx = next_x;
        ny = next_y;
        count = next;
    }
    p.rooms_x = nx;
    p.rooms_y = ny;
    return p;
}

void mesh_input_as_is(Scene& scene) {
    double shortest = std::numeric_limits<double>::infinity(), longest = 0;
    for (const Polygon& p : scene.polygons)
        for (std::size_t i = 0; i < p.vertices.size(); ++i) {
            const double l = length(p.vertices[(i + 1) % p.vertices.size()] - p.vertices[i]);
            shortest = std::min(shortest, l);
            longest = std::max(longest, l);
        }
    // See the header for why 75 shortest edges; rounded to millimetres for the scene file.
    scene.mesher.max_edge_length = std::floor(std::min(longest, 75.0 * shortest) * 1e3) / 1e3;
    scene.mesher.element_budget = 0;
    scene.mesher.split_contacts = false;
    scene.mesher.discontinuity.enabled = false;
}

} // namespace penumbra::bench
