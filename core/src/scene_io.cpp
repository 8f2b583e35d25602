// Scene loading (format v1, docs/scene-format.md): the JSON file is parsed by scene_json.cpp,
// its geometry files are imported by geometry_import.cpp, and this file merges them, reads
// sensor files, and validates the result. validate_scene also turns `emission_flux_lm` into
// radiance, since only then is the emitting area known.

#include "core/scene_io.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numeric>
#include <optional>
#include <sstream>
#include <tuple>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.h"
#include "core/files.h"

#include "geometry_import.h"
#include "radiance/radiance_import.h"
#include "radiance/scene_builder.h"
#include "scene_json.h"
#include "sensor_grids.h"

namespace penumbra {

namespace fs = std::filesystem;

namespace {

void check(bool ok, const Scene& scene, const std::string& key, const std::string& what);

std::string resolve(const std::string& base_dir, const std::string& file) {
    return (fs::path(base_dir) / file).string(); // an absolute `file` replaces base_dir
}

std::optional<std::uint32_t> find_material(const Scene& scene, const std::string& name) {
    for (std::size_t i = 0; i < scene.materials.size(); ++i)
        if (scene.materials[i].name == name)
            return std::uint32_t(i);
    return std::nullopt;
}

std::uint32_t find_or_add_material(Scene& scene, const std::string& name) {
    if (auto found = find_material(scene, name))
        return *found;
    Material material;
    material.name = name;
    scene.materials.push_back(std::move(material));
    return std::uint32_t(scene.materials.size() - 1);
}

/// Materials are shared by name across geometry files; the first definition wins.
void merge_geometry(Scene& scene, ImportedGeometry geometry) {
    std::vector<std::uint32_t> remap;
    for (Material& material : geometry.materials) {
        auto found = find_material(scene, material.name);
        if (!found) {
            found = std::uint32_t(scene.materials.size());
            scene.materials.push_back(std::move(material));
        }
        remap.push_back(*found);
    }
    for (Polygon& polygon : geometry.polygons) {
        polygon.material = remap[polygon.material];
        scene.polygons.push_back(std::move(polygon));
    }
}

void add_geometry_file(Scene& scene, const std::string& base_dir, const std::string& file,
                       double metres_per_unit, RadianceImport& radiance) {
    const std::string path = resolve(base_dir, file);
    std::error_code ec;
    if (fs::is_directory(path, ec))
        throw InputError(
            path, "geometry",
            fmt::format("is a folder, not a geometry file (listed in '{}')", scene.file));
    if (!fs::is_regular_file(path, ec))
        throw InputError(path, "geometry",
                         fmt::format("geometry file not found (listed in '{}')", scene.file));
    merge_geometry(scene, is_radiance_file(path) ? radiance.read(path)
                                                 : import_geometry(path, file, metres_per_unit));
}

/// The sun and sky of the Radiance files; the scene file must not give them too.
void add_radiance_sources(Scene& scene, const radiance::Sources& sources) {
    if (sources.sun) {
        if (scene.sun)
            throw InputError(scene.file, "sun",
                             fmt::format("the sun is given twice: here and by {}",
                                         radiance::describe(sources.sun_where)));
        scene.sun = sources.sun;
    }
    if (sources.sky) {
        if (scene.sky)
            throw InputError(scene.file, "sky",
                             fmt::format("the sky is given twice: here and by {}",
                                         radiance::describe(sources.sky_where)));
        scene.sky = sources.sky;
    }
}

/// Overrides only the keys \p spec gives.
void apply_material_spec(Material& material, const MaterialSpec& spec) {
    if (spec.reflectance)
        material.reflectance = *spec.reflectance;
    if (spec.diffuse_transmittance)
        material.diffuse_transmittance = *spec.diffuse_transmittance;
    if (spec.emission) {
        material.emission = *spec.emission;
        material.emission_flux_lm.reset();
    }
    if (spec.emission_flux_lm) {
        material.emission = spec.emission_color.value_or(Rgb(1.0f)); // scaled later
        material.emission_flux_lm = spec.emission_flux_lm;
    }
    if (spec.two_sided)
        material.two_sided = *spec.two_sided;
    if (spec.emission_two_sided)
        material.emission_two_sided = *spec.emission_two_sided;
    if (spec.lightmap_mode)
        material.lightmap_mode = *spec.lightmap_mode;
    if (spec.lobe) {
        material.lobe = *spec.lobe;
        // A metal, a mirror or glass reflects only through its lobe.
        if (material.lobe && !spec.reflectance)
            material.reflectance = diffuse_reflectance(material);
    }
}

/// A new name defines a new material.
void apply_materials(Scene& scene, const std::vector<MaterialSpec>& specs) {
    for (const MaterialSpec& spec : specs)
        apply_material_spec(scene.materials[find_or_add_material(scene, spec.name)], spec);
}

/// `annual.blinds`: copies of the named scene materials with the entries' keys applied.
void apply_blinds(Scene& scene, const std::vector<MaterialSpec>& specs) {
    for (const MaterialSpec& spec : specs) {
        const auto found = find_material(scene, spec.name);
        if (!found)
            throw InputError(scene.file, "annual.blinds." + spec.name,
                             "no material of this name in the scene: the blinds' entries change "
                             "the scene's materials");
        Material material = scene.materials[*found];
        apply_material_spec(material, spec);
        scene.annual.blinds.push_back(std::move(material));
    }
}

/// The top-level `emission_two_sided`, for the materials whose entry does not give theirs.
void apply_default_emission_sides(Scene& scene, const SceneSpec& spec) {
    if (!spec.emission_two_sided)
        return;
    for (Material& material : scene.materials) {
        const auto own =
            std::find_if(spec.materials.begin(), spec.materials.end(), [&](const MaterialSpec& m) {
                return m.name == material.name && m.emission_two_sided;
            });
        if (own == spec.materials.end())
            material.emission_two_sided = *spec.emission_two_sided;
    }
}

/// `smooth_objects`: only the listed objects keep their vertex normals; each must have some.
void apply_smooth_objects(Scene& scene, const std::optional<std::vector<std::string>>& names) {
    if (!names)
        return;
    std::vector<bool> smooth(names->size(), false);
    for (Polygon& polygon : scene.polygons) {
        const auto found = std::find(names->begin(), names->end(), polygon.name);
        if (found == names->end())
            polygon.normals.clear();
        else if (!polygon.normals.empty())
            smooth[std::size_t(found - names->begin())] = true;
    }
    for (std::size_t i = 0; i < names->size(); ++i)
        check(smooth[i], scene, fmt::format("smooth_objects[{}]", i),
              fmt::format("no polygon of an object named '{}' has vertex normals in its geometry "
                          "file",
                          (*names)[i]));
}

void add_inline_polygons(Scene& scene, const std::vector<PolygonSpec>& specs) {
    for (const PolygonSpec& spec : specs) {
        const auto material = find_material(scene, spec.material);
        if (!material) {
            std::vector<std::string> names;
            for (const Material& m : scene.materials)
                names.push_back(m.name);
            throw InputError(scene.file, spec.key + ".material",
                             fmt::format("unknown material '{}' (known: {})", spec.material,
                                         fmt::join(names, ", ")));
        }
        scene.polygons.push_back(Polygon{.vertices = spec.vertices,
                                         .material = *material,
                                         .name = spec.name,
                                         .source = spec.key});
    }
}

/// At most this many characters of a bad input line are quoted in a message.
constexpr std::size_t k_quoted_chars = 80;

/// One Radiance-style sensor line "x y z nx ny nz"; false if it does not hold 6 numbers.
bool parse_sensor_line(const std::string& line, double metres_per_unit, Sensor& sensor) {
    std::istringstream tokens(line);
    std::vector<double> v;
    for (std::string token; tokens >> token;) {
        char* end = nullptr;
        v.push_back(std::strtod(token.c_str(), &end));
        if (*end != '\0' || !std::isfinite(v.back()))
            return false;
    }
    if (v.size() != 6)
        return false;
    sensor.position = Vec3(v[0], v[1], v[2]) * metres_per_unit;
    sensor.normal = Vec3(v[3], v[4], v[5]);
    return true;
}

std::vector<Sensor> read_sensor_file(const std::string& path, double metres_per_unit) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
        throw InputError(path, "sensors.file", "sensor file not found");
    std::istringstream in(read_text_file(path));
    std::vector<Sensor> sensors;
    int number = 0;
    for (std::string line; std::getline(in, line);) {
        ++number;
        line = line.substr(0, line.find('#'));
        if (line.find_first_not_of(" \t\r") == std::string::npos)
            continue;
        Sensor sensor;
        if (!parse_sensor_line(line, metres_per_unit, sensor))
            throw InputError(path, "",
                             fmt::format("expected 6 numbers 'x y z nx ny nz', got '{}'",
                                         excerpt(line, k_quoted_chars)),
                             number);
        if (length(sensor.normal) == 0)
            throw InputError(path, "", "the sensor normal is zero", number);
        sensor.normal = normalize(sensor.normal);
        sensors.push_back(sensor);
    }
    return sensors;
}

// ---- Validation -----------------------------------------------------------------------------

void check(bool ok, const Scene& scene, const std::string& key, const std::string& what) {
    if (!ok)
        throw InputError(scene.file, key, what);
}

std::string format_vec(const Vec3& v) {
    return fmt::format("({}, {}, {})", v.x, v.y, v.z);
}
std::string format_rgb(const Rgb& c) {
    return fmt::format("({}, {}, {})", c.r, c.g, c.b);
}

/// Newell's normal: its length is twice the polygon's area, also for non-planar polygons.
Vec3 newell_normal(const std::vector<Vec3>& vertices) {
    Vec3 normal;
    for (std::size_t i = 0; i < vertices.size(); ++i)
        normal += cross(vertices[i], vertices[(i + 1) % vertices.size()]);
    return normal;
}

double polygon_area_m2(const Polygon& polygon) {
    return 0.5 * length(newell_normal(polygon.vertices));
}

[[noreturn]] void fail_polygon(const Scene& scene, const Polygon& polygon,
                               const std::string& what) {
    // Inline polygons have their key path as source; imported ones "file.obj:face N".
    const bool inline_polygon = polygon.source.starts_with("polygons[");
    const std::string key =
        inline_polygon ? polygon.source : (polygon.source.empty() ? "" : "geometry");
    const std::string where =
        inline_polygon || polygon.source.empty() ? "" : fmt::format(" ({})", polygon.source);
    throw InputError(scene.file, key, fmt::format("polygon '{}'{}: {}", polygon.name, where, what));
}

/// Positions lie at most this far from the origin, metres: the solver's float geometry and its
/// squared distances stay finite (a sensor at 1e308 m gave a row of NaN).
constexpr double k_max_coordinate_m = 1e9;

/// Finite and within k_max_coordinate_m of the origin in every axis.
bool in_world(const Vec3& p) {
    return is_finite(p) && std::abs(p.x) <= k_max_coordinate_m &&
           std::abs(p.y) <= k_max_coordinate_m && std::abs(p.z) <= k_max_coordinate_m;
}

std::string outside_world(const Vec3& p) {
    return fmt::format("must be finite and within {:g} m of the origin, got {}", k_max_coordinate_m,
                       format_vec(p));
}

// The first pair (i, j), i < j, of equal vertices that are not neighbours around the outline.
// A face of one triangle's indices repeated 10 000 times took a minute and gigabytes to mesh;
// neighbours that repeat are merged by the mesher.
std::optional<std::pair<std::size_t, std::size_t>> repeated_vertex(const std::vector<Vec3>& v) {
    std::vector<std::size_t> order(v.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    const auto key = [&](std::size_t i) { return std::tie(v[i].x, v[i].y, v[i].z); };
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
    std::optional<std::pair<std::size_t, std::size_t>> first;
    for (std::size_t k = 1; k < order.size(); ++k) {
        const std::size_t i = std::min(order[k - 1], order[k]),
                          j = std::max(order[k - 1], order[k]);
        const bool neighbours = j == i + 1 || (i == 0 && j + 1 == v.size());
        if (key(i) == key(j) && !neighbours && (!first || std::pair(i, j) < *first))
            first = std::pair(i, j);
    }
    return first;
}

void validate_polygon(const Scene& scene, const Polygon& polygon) {
    const std::size_t count = polygon.vertices.size();
    if (count < 3)
        fail_polygon(scene, polygon, fmt::format("has {} vertices, needs at least 3", count));
    BBox box;
    for (std::size_t i = 0; i < count; ++i) {
        if (!in_world(polygon.vertices[i]))
            fail_polygon(scene, polygon,
                         fmt::format("vertex {} {}", i + 1, outside_world(polygon.vertices[i])));
        box.extend(polygon.vertices[i]);
    }
    if (!polygon.lightmap_uv.empty() && polygon.lightmap_uv.size() != count)
        fail_polygon(
            scene, polygon,
            fmt::format("has {} lightmap UVs for {} vertices", polygon.lightmap_uv.size(), count));
    for (std::size_t i = 0; i < polygon.lightmap_uv.size(); ++i)
        if (!std::isfinite(polygon.lightmap_uv[i].x) || !std::isfinite(polygon.lightmap_uv[i].y))
            fail_polygon(scene, polygon, fmt::format("lightmap UV {} is not finite", i + 1));
    if (polygon.material >= scene.materials.size())
        fail_polygon(scene, polygon,
                     fmt::format("material index {} is out of range ({} materials)",
                                 polygon.material, scene.materials.size()));
    const double size = box.diagonal();
    if (!(length(newell_normal(polygon.vertices)) > 1e-12 * size * size))
        fail_polygon(scene, polygon, "zero-area face (collinear or repeated vertices)");
    if (const auto repeat = repeated_vertex(polygon.vertices))
        fail_polygon(scene, polygon,
                     fmt::format("vertex {} repeats vertex {}: a face visits each point once",
                                 repeat->second + 1, repeat->first + 1));
    if (!polygon.normals.empty() && polygon.normals.size() != count)
        fail_polygon(
            scene, polygon,
            fmt::format("has {} vertex normals for {} vertices", polygon.normals.size(), count));
    for (std::size_t i = 0; i < polygon.normals.size(); ++i)
        if (!(is_finite(polygon.normals[i]) && std::abs(length(polygon.normals[i]) - 1) < 1e-6))
            fail_polygon(scene, polygon,
                         fmt::format("vertex normal {} {} is not a finite unit vector", i + 1,
                                     format_vec(polygon.normals[i])));
}

/// The largest radiance (W/(sr·m²)), intensity (W/sr) or irradiance (W/m²) a source may have:
/// 13 orders above the sun's disc, and low enough that the solver's float sums of power over
/// millions of elements stay finite (a radiance of 1e36 overflowed to NaN in the solve).
constexpr double k_max_source_value = 1e20;

bool within_source_range(const Rgb& c) {
    return c.max_component() <= k_max_source_value;
}

std::string beyond_source_range(const Rgb& c, const char* unit) {
    return fmt::format("{} {} exceeds the largest value a source may have, {:g}", format_rgb(c),
                       unit, k_max_source_value);
}

// τ passes to the other side: a one-sided surface has none, and ρ + τ < 1 keeps the solve
// convergent (each side returns less than it receives).
void validate_diffuse_transmittance(const Scene& scene, const Material& m, const std::string& key) {
    const Rgb& tau = m.diffuse_transmittance;
    if (tau.is_black())
        return;
    bool ok = true;
    for (int c = 0; c < 3; ++c)
        ok = ok && tau[c] >= 0 && m.reflectance[c] + tau[c] < 1;
    check(ok, scene, key + ".diffuse_transmittance",
          fmt::format("must be >= 0 with reflectance + diffuse_transmittance < 1 per channel, got "
                      "{} and reflectance {}",
                      format_rgb(tau), format_rgb(m.reflectance)));
    check(m.two_sided, scene, key + ".two_sided",
          "a diffusely transmitting material must be two-sided (its light passes to the other "
          "side)");
    check(!m.lobe, scene, key + ".diffuse_transmittance",
          "diffuse transmission takes a diffuse material, not thin glass or another lobe");
}

bool in_unit_range(const Rgb& c) {
    return c.r >= 0 && c.r <= 1 && c.g >= 0 && c.g <= 1 && c.b >= 0 && c.b <= 1;
}

/// The same ranges as the scene file's material types (scene_json.cpp), for materials built in
/// code or imported.
void validate_lobe(const Scene& scene, const Lobe& lobe, const std::string& key) {
    const auto check_ior = [&](double ior, const char* what) {
        check(ior >= 1 && ior <= 10, scene, key + ".ior",
              fmt::format("{} must be in [1, 10], got {}", what, ior));
    };
    const auto check_colour = [&](const Rgb& c, const char* name) {
        check(in_unit_range(c), scene, key + "." + name,
              "must be in [0, 1] per channel, got " + format_rgb(c));
    };
    if (const auto* g = std::get_if<GgxGlossy>(&lobe)) {
        check(g->alpha > 0 && g->alpha <= 1, scene, key + ".alpha",
              fmt::format("must be in (0, 1] (GGX's α), got {}", g->alpha));
        check_colour(g->specular, "specular");
        if (const auto* f = std::get_if<FresnelDielectric>(&g->fresnel))
            check_ior(f->ior, "the Fresnel factor's refractive index");
    } else if (const auto* mirror = std::get_if<Mirror>(&lobe)) {
        check_colour(mirror->colour, "specular");
    } else if (const auto* d = std::get_if<Dielectric>(&lobe)) {
        check_ior(d->ior, "the refractive index");
        check_colour(d->transmittance, "transmittance");
    } else if (const auto* glass = std::get_if<ThinGlass>(&lobe)) {
        check_ior(glass->ior, "the refractive index");
        check_colour(glass->transmissivity, "transmissivity");
    }
}

void validate_material(const Scene& scene, const Material& m,
                       const std::string& key_prefix = "materials.") {
    const std::string key = key_prefix + m.name;
    if (m.lobe)
        validate_lobe(scene, *m.lobe, key);
    bool reflectance_ok = true;
    for (int c = 0; c < 3; ++c)
        reflectance_ok = reflectance_ok && m.reflectance[c] >= 0 && m.reflectance[c] < 1;
    check(reflectance_ok, scene, key + ".reflectance",
          "must be in [0, 1) per channel, got " + format_rgb(m.reflectance));
    check(m.emission.is_finite() && m.emission.r >= 0 && m.emission.g >= 0 && m.emission.b >= 0,
          scene, key + (m.emission_flux_lm ? ".emission_color" : ".emission"),
          "must be finite and >= 0, got " + format_rgb(m.emission));
    check(within_source_range(m.emission), scene, key + ".emission",
          beyond_source_range(m.emission, "W/(sr·m²)"));
    if (m.emission_flux_lm)
        check(std::isfinite(*m.emission_flux_lm) && *m.emission_flux_lm >= 0, scene,
              key + ".emission_flux_lm", fmt::format("must be >= 0, got {}", *m.emission_flux_lm));
    validate_diffuse_transmittance(scene, m, key);
}

// The same ranges as the scene file's "spot" (scene_json.cpp), for spots built in code; the
// direction is normalised in place.
void validate_spot(const Scene& scene, SpotCone& spot, const std::string& key) {
    check(is_finite(spot.direction) && length(spot.direction) > 0, scene, key + ".direction",
          "must be a finite, non-zero vector, got " + format_vec(spot.direction));
    spot.direction = normalize(spot.direction);
    check(spot.cutoff_deg > 0 && spot.cutoff_deg <= 180, scene, key + ".cutoff_deg",
          fmt::format("must be in (0, 180] (a half-angle), got {}", spot.cutoff_deg));
    check(spot.beam_deg >= 0 && spot.beam_deg <= spot.cutoff_deg, scene, key + ".beam_deg",
          fmt::format("must be in [0, cutoff_deg = {}] (a half-angle), got {}", spot.cutoff_deg,
                      spot.beam_deg));
}

// The same ranges as the scene file's "sun" (scene_json.cpp), for suns built in code; the
// direction is normalised in place.
void validate_sun(const Scene& scene, Sun& sun) {
    check(is_finite(sun.direction) && length(sun.direction) > 0, scene, "sun.direction",
          "must be a finite, non-zero vector (toward the sun), got " + format_vec(sun.direction));
    sun.direction = normalize(sun.direction);
    const Rgb& e = sun.irradiance;
    check(e.is_finite() && e.r >= 0 && e.g >= 0 && e.b >= 0, scene, "sun",
          "irradiance must be finite and >= 0, got " + format_rgb(e));
    check(within_source_range(e), scene, "sun", beyond_source_range(e, "W/m²"));
    check(sun.angular_diameter_deg >= 0 && sun.angular_diameter_deg <= 10, scene,
          "sun.angular_diameter_deg",
          fmt::format("must be in [0, 10] degrees (the sun: 0.533), got {}",
                      sun.angular_diameter_deg));
}

void validate_lights_and_sensors(Scene& scene) {
    for (std::size_t i = 0; i < scene.point_lights.size(); ++i) {
        PointLight& light = scene.point_lights[i];
        const std::string key = fmt::format("point_lights[{}]", i);
        check(in_world(light.position), scene, key + ".position", outside_world(light.position));
        const Rgb& c = light.intensity;
        check(c.is_finite() && c.r >= 0 && c.g >= 0 && c.b >= 0, scene, key,
              "intensity must be finite and >= 0, got " + format_rgb(c));
        check(within_source_range(c), scene, key, beyond_source_range(c, "W/sr"));
        if (light.spot)
            validate_spot(scene, *light.spot, key + ".spot");
    }
    if (scene.sun)
        validate_sun(scene, *scene.sun);
    for (std::size_t i = 0; i < scene.sensors.size(); ++i) {
        Sensor& sensor = scene.sensors[i];
        const std::string key = fmt::format("sensors[{}]", i);
        check(in_world(sensor.position), scene, key + ".position", outside_world(sensor.position));
        check(is_finite(sensor.normal) && length(sensor.normal) > 0, scene, key + ".normal",
              "must be a finite, non-zero vector");
        sensor.normal = normalize(sensor.normal);
    }
}

void validate_camera(const Scene& scene, const Camera& camera) {
    check(in_world(camera.eye), scene, "camera.eye", outside_world(camera.eye));
    check(in_world(camera.look_at) && length(camera.look_at - camera.eye) > 0, scene,
          "camera.look_at", "must be finite and differ from 'eye'");
    const Vec3 view = normalize(camera.look_at - camera.eye);
    check(is_finite(camera.up) && length(cross(normalize(camera.up), view)) > 1e-6, scene,
          "camera.up", "must be a non-zero vector not parallel to the view direction");
    check(camera.fov_deg > 0 && camera.fov_deg < 180, scene, "camera.fov_deg",
          fmt::format("must be in (0, 180), got {}", camera.fov_deg));
    check(camera.width >= 1 && camera.width <= 16384, scene, "image.width",
          fmt::format("must be in [1, 16384], got {}", camera.width));
    check(camera.height >= 1 && camera.height <= 16384, scene, "image.height",
          fmt::format("must be in [1, 16384], got {}", camera.height));
    check(camera.samples_per_pixel >= 1, scene, "image.spp", "must be >= 1");
    check(std::isfinite(camera.exposure) && camera.exposure >= 0, scene, "image.exposure",
          fmt::format("must be >= 0 (0 = automatic), got {}", camera.exposure));
    check(std::isfinite(camera.aperture_radius_m) && camera.aperture_radius_m >= 0, scene,
          "camera.aperture_radius",
          fmt::format("must be >= 0 (0 = pinhole), got {}", camera.aperture_radius_m));
    check(!camera.focus_distance_m ||
              (std::isfinite(*camera.focus_distance_m) && *camera.focus_distance_m > 0),
          scene, "camera.focus_distance",
          fmt::format("must be > 0, got {}", camera.focus_distance_m.value_or(0)));
}

void validate_settings(const Scene& scene) {
    const MesherSettings& mesher = scene.mesher;
    check(std::isfinite(mesher.max_edge_length) && mesher.max_edge_length >= 0, scene,
          "mesher.max_edge_length", "must be >= 0 (0 = automatic)");
    check(std::isfinite(mesher.planarity_tolerance) && mesher.planarity_tolerance >= 0, scene,
          "mesher.planarity_tolerance", "must be >= 0");
    check(!mesher.contact_tolerance ||
              (std::isfinite(*mesher.contact_tolerance) && *mesher.contact_tolerance >= 0),
          scene, "mesher.contact_tolerance", "must be >= 0");
    // A tolerance near the scene's size merges everything and hid the emitters (0 lm).
    const double diagonal = scene.bounds().diagonal();
    check(!mesher.contact_tolerance || *mesher.contact_tolerance <= 0.01 * diagonal, scene,
          "mesher.contact_tolerance",
          fmt::format("must be at most 1 % of the scene's diagonal ({:g} m), got {:g} m",
                      0.01 * diagonal, mesher.contact_tolerance.value_or(0)));
    check(mesher.element_budget >= 0, scene, "mesher.element_budget",
          "must be >= 0 (0 = no limit)");
    check(mesher.discontinuity.max_order >= 0 && mesher.discontinuity.max_order <= 2, scene,
          "mesher.discontinuity.max_order", "must be 0, 1 or 2");
    const SolverSettings& solver = scene.solver;
    check(solver.residual > 0 && solver.residual < 1, scene, "solver.residual",
          fmt::format("must be in (0, 1), got {}", solver.residual));
    check(solver.max_shots >= 0, scene, "solver.max_shots", "must be >= 0 (0 = automatic)");
    check(solver.visibility_rays >= 1, scene, "solver.visibility_rays", "must be >= 1");
    check(std::isfinite(solver.row_cache_mb) && solver.row_cache_mb >= 0, scene,
          "solver.row_cache_mb", "must be >= 0");
    const RenderSettings& render = scene.render;
    check(render.max_bounces >= 0 && render.max_bounces <= 1024, scene, "render.max_bounces",
          fmt::format("must be in [0, 1024], got {}", render.max_bounces));
    check(render.filter_width_px >= 0.01 && render.filter_width_px <= 16, scene,
          "render.filter_width_px",
          fmt::format("must be in [0.01, 16] pixels, got {}", render.filter_width_px));
    check(render.caustic_photons >= 0, scene, "render.caustic_photons",
          fmt::format("must be >= 0 (0 = no caustic map), got {}", render.caustic_photons));
    check(!render.caustic_radius_m ||
              (std::isfinite(*render.caustic_radius_m) && *render.caustic_radius_m > 0),
          scene, "render.caustic_radius", "must be finite and > 0");
    const auto& cache = render.irradiance_cache;
    check(!cache || (cache->rays >= 16 && cache->rays <= 1 << 16), scene,
          "render.irradiance_cache.rays", "must be in [16, 65536]");
    check(!cache || (cache->error >= 1e-3 && cache->error <= 1), scene,
          "render.irradiance_cache.error", "must be in [0.001, 1]");
    check(render.light_samples >= 1 && render.light_samples <= 1024, scene, "render.light_samples",
          fmt::format("must be in [1, 1024], got {}", render.light_samples));
    check(render.gather_rays >= 1 && render.gather_rays <= 1024, scene, "render.gather_rays",
          fmt::format("must be in [1, 1024], got {}", render.gather_rays));
    check(std::isfinite(render.edge_tolerance) && render.edge_tolerance >= 0, scene,
          "render.edge_tolerance", "must be finite and >= 0 (0 = no edge refinement)");
    check(!scene.lightmap ||
              (scene.lightmap->atlas_size >= 16 && scene.lightmap->atlas_size <= 16384),
          scene, "lightmap.size", "must be in [16, 16384]");
    check(scene.background.is_finite() && scene.background.r >= 0 && scene.background.g >= 0 &&
              scene.background.b >= 0,
          scene, "background", "must be finite and >= 0, got " + format_rgb(scene.background));
}

/// L = Φ / (π A) with A the area of every polygon of the material (twice if it emits from both
/// sides); `emission` holds the colour until then. Idempotent: the colour is renormalised.
void resolve_emission_flux(Scene& scene) {
    std::vector<double> area_m2(scene.materials.size(), 0.0);
    for (const Polygon& polygon : scene.polygons)
        area_m2[polygon.material] += polygon_area_m2(polygon);
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        Material& m = scene.materials[i];
        if (!m.emission_flux_lm || *m.emission_flux_lm == 0) {
            if (m.emission_flux_lm)
                m.emission = Rgb{};
            continue;
        }
        const double area = area_m2[i] * (m.emission_two_sided ? 2.0 : 1.0);
        const std::string key = "materials." + m.name;
        check(area > 0, scene, key + ".emission_flux_lm",
              "no polygon has this material, so the flux has no area to leave from");
        check(to_photometric(m.emission) > 0, scene, key + ".emission_color",
              "has zero luminance, so it cannot carry a flux");
        m.emission = from_photometric(*m.emission_flux_lm / (k_pi * area), m.emission);
        // A finite flux can still overflow the float radiance every stage reads.
        check(m.emission.is_finite() && within_source_range(m.emission), scene,
              key + ".emission_flux_lm",
              fmt::format("{:g} lm over {:g} m² is a radiance beyond the largest a source may "
                          "have, {:g} W/(sr·m²)",
                          *m.emission_flux_lm, area, k_max_source_value));
    }
}

} // namespace

Scene load_scene(const std::string& path, SceneLight light) {
    const std::string text = read_text_file(path);
    return parse_scene(text, path, fs::path(path).parent_path().string(), light);
}

Scene parse_scene(const std::string& json_text, const std::string& file_name,
                  const std::string& base_dir, SceneLight light) {
    SceneSpec spec = parse_scene_json(json_text, file_name);
    Scene scene = std::move(spec.scene);
    RadianceImport radiance(spec.metres_per_unit);
    for (const std::string& file : spec.geometry)
        add_geometry_file(scene, base_dir, file, spec.metres_per_unit, radiance);
    add_radiance_sources(scene, radiance.sources());
    apply_materials(scene, spec.materials);
    apply_default_emission_sides(scene, spec);
    apply_blinds(scene, spec.blinds);
    add_inline_polygons(scene, spec.polygons);
    apply_smooth_objects(scene, spec.smooth_objects);
    if (spec.sensor_file) {
        const auto sensors =
            read_sensor_file(resolve(base_dir, *spec.sensor_file), spec.metres_per_unit);
        scene.sensors.insert(scene.sensors.end(), sensors.begin(), sensors.end());
    }
    validate_scene(scene, light);
    // Grids lie on validated polygons, so their points are finite.
    add_sensor_grids(scene, spec.grids);
    validate_sensor_grids(scene);
    return scene;
}

void validate_scene(Scene& scene, SceneLight light) {
    for (const Polygon& polygon : scene.polygons)
        validate_polygon(scene, polygon);
    for (const Material& material : scene.materials)
        validate_material(scene, material);
    for (const Material& material : scene.annual.blinds)
        validate_material(scene, material, "annual.blinds.");
    validate_lights_and_sensors(scene);
    validate_sensor_grids(scene);
    if (scene.camera)
        validate_camera(scene, *scene.camera);
    // Keys named as the main camera's: a named camera's own are the same keys of `cameras`.
    for (const NamedCamera& named : scene.cameras)
        validate_camera(scene, named.camera);
    validate_settings(scene);
    resolve_emission_flux(scene);
    check(light == SceneLight::weather || scene.has_emitter(), scene, "",
          "scene has no emitter: give a material 'emission' or add 'point_lights' or a 'sun'");
}

} // namespace penumbra
