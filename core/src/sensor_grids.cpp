// Sensor grids (scene key `grids`, docs/scene-format.md): a square lattice laid over the
// bounding box of a floor's or wall's outline in the plane's own axes, centred in it so that
// the margins left and right (and top and bottom) are equal; the points inside the outline and
// at least `wall_offset` from it become sensors. A name may cover several polygons (a
// triangulated floor): their outline is the edges no two of them share.

#include "sensor_grids.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>
#include <variant>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.h"

namespace penumbra {

namespace {

/// Lattices larger than this are refused before they are allocated.
constexpr double k_max_grid_points = 1e6;
/// A floor may tilt this much from horizontal: `height` is measured along `up`.
constexpr double k_max_floor_tilt_deg = 1.0;

struct Edge2 {
    Vec2 p, q;
};

/// The grid's plane and axes: sensor normal w = u × v; the plane is dot(x, w) = level.
struct GridFrame {
    Vec3 u, v, w;
    double level = 0;

    Vec2 to_plane(const Vec3& p) const { return {dot(p, u), dot(p, v)}; }
    Vec3 to_space(const Vec2& q) const { return q.x * u + q.y * v + level * w; }
};

[[noreturn]] void fail(const Scene& scene, const std::string& key, const std::string& what) {
    throw InputError(scene.file, key, what);
}

std::string polygon_key(const GridSpec& spec) {
    return spec.key + (spec.kind == GridKind::work_plane ? ".floor" : ".wall");
}

/// At most 8 distinct polygon names, for a message.
std::string some_polygon_names(const Scene& scene) {
    std::vector<std::string> names;
    for (const Polygon& p : scene.polygons)
        if (std::find(names.begin(), names.end(), p.name) == names.end())
            names.push_back(p.name);
    const bool more = names.size() > 8;
    names.resize(std::min<std::size_t>(names.size(), 8));
    return fmt::format("{}{}", fmt::join(names, ", "), more ? ", …" : "");
}

std::vector<std::vector<Vec3>> grid_polygons(const Scene& scene, const GridSpec& spec) {
    if (const auto* vertices = std::get_if<std::vector<Vec3>>(&spec.polygon))
        return {*vertices};
    const std::string& name = std::get<std::string>(spec.polygon);
    std::vector<std::vector<Vec3>> found;
    for (const Polygon& p : scene.polygons)
        if (p.name == name)
            found.push_back(p.vertices);
    if (found.empty())
        fail(scene, polygon_key(spec),
             fmt::format("no polygon is named '{}' (names: {})", name, some_polygon_names(scene)));
    return found;
}

/// Newell's normal: twice the area times the unit normal, toward the polygon's front.
Vec3 newell_normal(const std::vector<Vec3>& vertices) {
    Vec3 normal;
    for (std::size_t i = 0; i < vertices.size(); ++i)
        normal += cross(vertices[i], vertices[(i + 1) % vertices.size()]);
    return normal;
}

/// An in-plane axis for normal \p w: horizontal on a wall; the x axis (or y) seen from above.
Vec3 first_axis(const Vec3& w, const Vec3& up) {
    const Vec3 side = cross(up, w);
    if (length(side) > 1e-6)
        return normalize(side);
    const Vec3 axis = std::abs(w.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    return normalize(axis - dot(axis, w) * w);
}

/// The front normal of all \p polygons, which must share one plane (within 1e-4 of their size).
Vec3 common_normal(const Scene& scene, const GridSpec& spec,
                   const std::vector<std::vector<Vec3>>& polygons) {
    Vec3 sum;
    BBox box;
    for (const auto& vertices : polygons) {
        if (!(length(newell_normal(vertices)) > 0))
            fail(scene, polygon_key(spec), "the polygon has zero area");
        sum += newell_normal(vertices);
        for (const Vec3& p : vertices)
            box.extend(p);
    }
    const Vec3 n = normalize(sum);
    const double level = dot(polygons[0][0], n), tolerance = 1e-4 * box.diagonal();
    for (const auto& vertices : polygons) {
        const bool parallel = dot(normalize(newell_normal(vertices)), n) > 1 - 1e-4;
        for (const Vec3& p : vertices)
            if (!parallel || !(std::abs(dot(p, n) - level) <= tolerance))
                fail(scene, polygon_key(spec),
                     fmt::format("the {} polygons do not lie in one plane", polygons.size()));
    }
    return n;
}

GridFrame grid_frame(const Scene& scene, const GridSpec& spec,
                     const std::vector<std::vector<Vec3>>& polygons) {
    const Vec3 n = common_normal(scene, spec, polygons);
    GridFrame frame;
    frame.w = n;
    if (spec.kind == GridKind::work_plane) {
        const double tilt_deg = std::acos(std::min(1.0, std::abs(dot(n, spec.up)))) * 180 / k_pi;
        if (tilt_deg > k_max_floor_tilt_deg)
            fail(scene, polygon_key(spec),
                 fmt::format("a work plane's floor must be horizontal (within {}° of `up`), this "
                             "one tilts {:.3g}°",
                             k_max_floor_tilt_deg, tilt_deg));
        frame.w = spec.up;
    }
    frame.u = first_axis(frame.w, spec.up);
    frame.v = cross(frame.w, frame.u);
    double sum = 0;
    std::size_t count = 0;
    for (const auto& vertices : polygons)
        for (const Vec3& p : vertices) {
            sum += dot(p, frame.w);
            ++count;
        }
    frame.level = sum / double(count) + spec.offset_m;
    return frame;
}

/// The edges of \p polygons that no other edge of theirs covers (either direction), in the plane.
std::vector<Edge2> outline_edges(const std::vector<std::vector<Vec3>>& polygons,
                                 const GridFrame& frame) {
    using Key = std::tuple<double, double, double>;
    const auto key = [](const Vec3& p) { return Key(p.x, p.y, p.z); };
    std::multiset<std::pair<Key, Key>> edges;
    for (const auto& vertices : polygons)
        for (std::size_t i = 0; i < vertices.size(); ++i) {
            const Key a = key(vertices[i]), b = key(vertices[(i + 1) % vertices.size()]);
            edges.insert(std::minmax(a, b));
        }
    std::vector<Edge2> outline;
    for (const auto& vertices : polygons)
        for (std::size_t i = 0; i < vertices.size(); ++i) {
            const Vec3& a = vertices[i];
            const Vec3& b = vertices[(i + 1) % vertices.size()];
            if (edges.count(std::minmax(key(a), key(b))) == 1)
                outline.push_back({frame.to_plane(a), frame.to_plane(b)});
        }
    return outline;
}

bool inside_even_odd(const std::vector<Edge2>& edges, const Vec2& x) {
    bool inside = false;
    for (const Edge2& e : edges)
        if ((e.p.y > x.y) != (e.q.y > x.y) &&
            x.x < e.p.x + (x.y - e.p.y) * (e.q.x - e.p.x) / (e.q.y - e.p.y))
            inside = !inside;
    return inside;
}

double distance_to_edges(const std::vector<Edge2>& edges, const Vec2& x) {
    double best = std::numeric_limits<double>::infinity();
    for (const Edge2& e : edges) {
        const double dx = e.q.x - e.p.x, dy = e.q.y - e.p.y, len2 = dx * dx + dy * dy;
        const double t =
            len2 > 0 ? std::clamp(((x.x - e.p.x) * dx + (x.y - e.p.y) * dy) / len2, 0.0, 1.0) : 0;
        best = std::min(best, std::hypot(x.x - e.p.x - t * dx, x.y - e.p.y - t * dy));
    }
    return best;
}

/// The lattice over the outline's bounding box, centred in it: its first point and size.
struct Lattice {
    Vec2 first;
    int columns = 0, rows = 0;
};

Lattice centred_lattice(const Scene& scene, const GridSpec& spec,
                        const std::vector<Edge2>& outline) {
    Vec2 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    Vec2 hi{-lo.x, -lo.y};
    for (const Edge2& e : outline)
        for (const Vec2& p : {e.p, e.q}) {
            lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
            hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
        }
    const double s = spec.spacing_m;
    // The 1e-9 keeps a side that is a whole number of spacings from losing its last point.
    const double columns = std::floor((hi.x - lo.x) / s + 1e-9) + 1;
    const double rows = std::floor((hi.y - lo.y) / s + 1e-9) + 1;
    if (columns * rows > k_max_grid_points)
        fail(scene, spec.key + ".spacing",
             fmt::format("{:g} m gives {:g} × {:g} lattice points, more than {:g}: use a larger "
                         "spacing",
                         s, columns, rows, k_max_grid_points));
    Lattice lattice;
    lattice.columns = int(columns);
    lattice.rows = int(rows);
    lattice.first = {lo.x + (hi.x - lo.x - (columns - 1) * s) / 2,
                     lo.y + (hi.y - lo.y - (rows - 1) * s) / 2};
    return lattice;
}

/// Whether each lattice point (row-major) lies inside the outline, wall_offset or more from
/// it; a point on the outline counts as inside. The tolerance is 1e-6 of the spacing.
std::vector<bool> kept_points(const GridSpec& spec, const std::vector<Edge2>& outline,
                              const Lattice& lattice) {
    const double tolerance = 1e-6 * spec.spacing_m;
    std::vector<bool> kept(std::size_t(lattice.rows) * std::size_t(lattice.columns));
    for (int r = 0; r < lattice.rows; ++r)
        for (int c = 0; c < lattice.columns; ++c) {
            const Vec2 x{lattice.first.x + c * spec.spacing_m,
                         lattice.first.y + r * spec.spacing_m};
            const double d = distance_to_edges(outline, x);
            kept[std::size_t(r) * std::size_t(lattice.columns) + std::size_t(c)] =
                (d <= tolerance || inside_even_odd(outline, x)) &&
                d >= spec.wall_offset_m - tolerance;
        }
    return kept;
}

void add_grid(Scene& scene, const GridSpec& spec) {
    const auto polygons = grid_polygons(scene, spec);
    const GridFrame frame = grid_frame(scene, spec, polygons);
    const std::vector<Edge2> outline = outline_edges(polygons, frame);
    const Lattice lattice = centred_lattice(scene, spec, outline);
    const std::vector<bool> kept = kept_points(spec, outline, lattice);
    // The rows and columns that hold points: the stored lattice starts at the first of them.
    int r0 = lattice.rows, r1 = -1, c0 = lattice.columns, c1 = -1;
    for (int r = 0; r < lattice.rows; ++r)
        for (int c = 0; c < lattice.columns; ++c)
            if (kept[std::size_t(r) * std::size_t(lattice.columns) + std::size_t(c)]) {
                r0 = std::min(r0, r), r1 = std::max(r1, r);
                c0 = std::min(c0, c), c1 = std::max(c1, c);
            }
    if (r1 < 0)
        fail(scene, spec.key,
             fmt::format("no lattice point (spacing {:g} m) lies inside the outline at least "
                         "wall_offset = {:g} m from it",
                         spec.spacing_m, spec.wall_offset_m));
    const double s = spec.spacing_m;
    SensorGrid grid{.name = spec.name,
                    .kind = spec.kind,
                    .origin = frame.to_space({lattice.first.x + c0 * s, lattice.first.y + r0 * s}),
                    .u = frame.u,
                    .v = frame.v,
                    .spacing_m = s,
                    .rows = r1 - r0 + 1,
                    .columns = c1 - c0 + 1};
    for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c) {
            if (!kept[std::size_t(r) * std::size_t(lattice.columns) + std::size_t(c)]) {
                grid.sensors.emplace_back();
                continue;
            }
            grid.sensors.emplace_back(std::uint32_t(scene.sensors.size()));
            const Vec2 x{lattice.first.x + c * s, lattice.first.y + r * s};
            scene.sensors.push_back(
                {fmt::format("{}:{}:{}", spec.name, r - r0, c - c0), frame.to_space(x), frame.w});
        }
    for (const Edge2& e : outline)
        grid.outline.push_back({frame.to_space(e.p), frame.to_space(e.q)});
    scene.grids.push_back(std::move(grid));
}

/// Grid names become file names (grid_NAME.png): letters, digits, '_', '-' and '.', not first.
bool usable_in_file_names(const std::string& name) {
    if (name.empty() || name.size() > 64 || name[0] == '.')
        return false;
    return std::all_of(name.begin(), name.end(), [](char ch) {
        return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-' || ch == '.';
    });
}

} // namespace

std::optional<std::uint32_t> SensorGrid::sensor_at(int row, int column) const {
    if (row < 0 || row >= rows || column < 0 || column >= columns)
        return std::nullopt;
    return sensors[std::size_t(row) * std::size_t(columns) + std::size_t(column)];
}

Vec3 SensorGrid::point(double row, double column) const {
    return origin + (column * spacing_m) * u + (row * spacing_m) * v;
}

bool SensorGrid::covers(double row, double column) const {
    const auto plane = [&](const Vec3& p) { return Vec2{dot(p, u), dot(p, v)}; };
    std::vector<Edge2> edges;
    for (const auto& [a, b] : outline)
        edges.push_back({plane(a), plane(b)});
    return inside_even_odd(edges, plane(point(row, column)));
}

void add_sensor_grids(Scene& scene, const std::vector<GridSpec>& specs) {
    for (const GridSpec& spec : specs)
        add_grid(scene, spec);
}

void validate_sensor_grids(const Scene& scene) {
    std::set<std::string> names;
    for (const SensorGrid& grid : scene.grids) {
        const std::string key = "grids." + grid.name;
        if (!usable_in_file_names(grid.name))
            fail(scene, key,
                 "a grid name names its files: 1 to 64 letters, digits, '_', '-' or '.', "
                 "not starting with '.'");
        if (!names.insert(grid.name).second)
            fail(scene, key, "two grids have this name");
        const bool lattice_ok =
            grid.rows > 0 && grid.columns > 0 && std::isfinite(grid.spacing_m) &&
            grid.spacing_m > 0 &&
            grid.sensors.size() == std::size_t(grid.rows) * std::size_t(grid.columns);
        if (!lattice_ok)
            fail(scene, key,
                 fmt::format("a lattice of {} × {} points, spacing {} m, has {} entries", grid.rows,
                             grid.columns, grid.spacing_m, grid.sensors.size()));
        for (const auto& index : grid.sensors)
            if (index && *index >= scene.sensors.size())
                fail(scene, key,
                     fmt::format("sensor index {} is out of range ({} sensors)", *index,
                                 scene.sensors.size()));
    }
}

} // namespace penumbra
