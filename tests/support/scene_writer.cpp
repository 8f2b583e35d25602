// Scene → scene.json + OBJ/MTL. Only what the scene format can say is written; settings equal
// to their defaults are left out so that the file reads like a hand-written one.

#include "scene_writer.h"

#include "core/error.h"
#include "core/files.h"
#include "core/rng.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <bit>
#include <cctype>
#include <filesystem>
#include <iterator>
#include <type_traits>
#include <unordered_map>

namespace penumbra::bench {

namespace {

using Json = nlohmann::ordered_json;

/// OBJ and MTL names end at white space: replace it.
std::string obj_name(const std::string& name, const char* fallback) {
    std::string out = name.empty() ? fallback : name;
    for (char& c : out)
        if (std::isspace(static_cast<unsigned char>(c)))
            c = '_';
    return out;
}

struct VertexHash {
    std::size_t operator()(const Vec3& v) const {
        return std::size_t(
            hash_words({std::bit_cast<std::uint64_t>(v.x), std::bit_cast<std::uint64_t>(v.y),
                        std::bit_cast<std::uint64_t>(v.z)}));
    }
};

std::string obj_text(const Scene& scene, const std::string& mtl_file) {
    fmt::memory_buffer out;
    auto put = std::back_inserter(out);
    fmt::format_to(put, "# {}: {} polygons\nmtllib {}\n", scene.name, scene.polygons.size(),
                   mtl_file);
    std::unordered_map<Vec3, std::size_t, VertexHash> index;
    std::vector<std::size_t> face;
    const Polygon* previous = nullptr;
    for (const Polygon& p : scene.polygons) {
        if (p.material >= scene.materials.size())
            throw ConfigError(
                fmt::format("polygon '{}': material {} does not exist", p.name, p.material));
        face.clear();
        for (const Vec3& v : p.vertices) {
            const auto [it, added] = index.try_emplace(v, index.size() + 1); // OBJ counts from 1
            if (added)
                fmt::format_to(put, "v {} {} {}\n", v.x, v.y, v.z);
            face.push_back(it->second);
        }
        if (!previous || previous->name != p.name || previous->material != p.material)
            fmt::format_to(put, "o {}\nusemtl {}\n", obj_name(p.name, "polygon"),
                           obj_name(scene.materials[p.material].name, "material"));
        fmt::format_to(put, "f {}\n", fmt::join(face, " "));
        previous = &p;
    }
    return fmt::to_string(out);
}

std::string mtl_text(const Scene& scene) {
    fmt::memory_buffer out;
    auto put = std::back_inserter(out);
    for (const Material& m : scene.materials) {
        const Rgb& kd = m.reflectance;
        fmt::format_to(put, "newmtl {}\nKd {} {} {}\n", obj_name(m.name, "material"), kd.r, kd.g,
                       kd.b);
        if (!m.emission.is_black())
            fmt::format_to(put, "Ke {} {} {}\n", m.emission.r, m.emission.g, m.emission.b);
    }
    return fmt::to_string(out);
}

/// One line: {"key": value, ...} and [a, b, ...].
std::string flat(const Json& j) {
    if (!j.is_structured())
        return j.dump();
    std::string out = j.is_object() ? "{" : "[";
    for (auto it = j.begin(); it != j.end(); ++it) {
        out += it == j.begin() ? "" : ", ";
        if (j.is_object())
            out += Json(it.key()).dump() + ": ";
        out += flat(*it);
    }
    return out + (j.is_object() ? "}" : "]");
}

/// Indented, with values that fit in 100 columns on one line, as the bundled scenes are.
void pretty(std::string& out, const Json& j, std::size_t indent) {
    const std::string line = flat(j);
    if (indent + line.size() <= 100 || j.empty()) {
        out += line;
        return;
    }
    out += j.is_object() ? "{\n" : "[\n";
    for (auto it = j.begin(); it != j.end(); ++it) {
        out += it == j.begin() ? "" : ",\n";
        out.append(indent + 2, ' ');
        if (j.is_object())
            out += Json(it.key()).dump() + ": ";
        pretty(out, *it, indent + 2);
    }
    out += "\n" + std::string(indent, ' ') + (j.is_object() ? "}" : "]");
}

Json xyz(const Vec3& v) {
    return Json::array({v.x, v.y, v.z});
}

/// Sets j[key] = value unless value is the default.
template <typename T> void put_changed(Json& j, const char* key, const T& value, const T& dflt) {
    if (value == dflt)
        return;
    if constexpr (std::is_enum_v<T>)
        j[key] = std::string(enum_name(value)); // as the scene file spells it
    else
        j[key] = value;
}

Json mesher_json(const MesherSettings& m) {
    const MesherSettings d;
    Json j = Json::object();
    put_changed(j, "max_edge_length", m.max_edge_length, d.max_edge_length);
    put_changed(j, "planarity_tolerance", m.planarity_tolerance, d.planarity_tolerance);
    put_changed(j, "split_contacts", m.split_contacts, d.split_contacts);
    if (m.contact_tolerance)
        j["contact_tolerance"] = *m.contact_tolerance;
    put_changed(j, "element_budget", m.element_budget, d.element_budget);
    Json disc = Json::object();
    put_changed(disc, "enabled", m.discontinuity.enabled, d.discontinuity.enabled);
    put_changed(disc, "max_order", m.discontinuity.max_order, d.discontinuity.max_order);
    if (!disc.empty())
        j["discontinuity"] = disc;
    return j;
}

Json solver_json(const SolverSettings& s) {
    const SolverSettings d;
    Json j = Json::object();
    j["method"] = std::string(enum_name(s.method));
    put_changed(j, "residual", s.residual, d.residual);
    put_changed(j, "epsilon", s.epsilon, d.epsilon);
    put_changed(j, "oracle", s.oracle, d.oracle);
    put_changed(j, "clustering", s.clustering, d.clustering);
    put_changed(j, "iteration", s.iteration, d.iteration);
    put_changed(j, "min_area", s.min_area, d.min_area);
    put_changed(j, "max_sweeps", s.max_sweeps, d.max_sweeps);
    put_changed(j, "ambient", s.ambient, d.ambient);
    put_changed(j, "max_shots", s.max_shots, d.max_shots);
    put_changed(j, "visibility_rays", s.visibility_rays, d.visibility_rays);
    put_changed(j, "row_cache_mb", s.row_cache_mb, d.row_cache_mb);
    return j;
}

// Imported materials are two-sided and emit from the front only: record what differs.
Json materials_json(const Scene& scene) {
    Json j = Json::object();
    for (const Material& m : scene.materials) {
        Json flags = Json::object();
        put_changed(flags, "two_sided", m.two_sided, true);
        put_changed(flags, "emission_two_sided", m.emission_two_sided, false);
        if (!flags.empty())
            j[obj_name(m.name, "material")] = flags;
    }
    return j;
}

void put_lights_and_sensors(Json& j, const Scene& scene) {
    for (const PointLight& l : scene.point_lights) {
        // intensity = from_photometric(cd, color) with the intensity itself as the colour.
        const Rgb& c = l.intensity;
        Json light = {{"name", l.name},
                      {"position", xyz(l.position)},
                      {"intensity_cd", to_photometric(c)}, // on the axis for a spot
                      {"color", {c.r, c.g, c.b}}};
        if (l.spot)
            light["spot"] = {{"direction", xyz(l.spot->direction)},
                             {"beam_deg", l.spot->beam_deg},
                             {"cutoff_deg", l.spot->cutoff_deg}};
        j["point_lights"].push_back(light);
    }
    if (scene.sun) {
        const Rgb& e = scene.sun->irradiance;
        j["sun"] = {{"direction", xyz(scene.sun->direction)},
                    {"irradiance_w_m2", {e.r, e.g, e.b}},
                    {"angular_diameter_deg", scene.sun->angular_diameter_deg}};
    }
    for (const Sensor& s : scene.sensors)
        j["sensors"].push_back(
            {{"name", s.name}, {"position", xyz(s.position)}, {"normal", xyz(s.normal)}});
}

void put_camera(Json& j, const Camera& c) {
    j["camera"] = {{"eye", xyz(c.eye)},
                   {"look_at", xyz(c.look_at)},
                   {"up", xyz(c.up)},
                   {"fov_deg", c.fov_deg},
                   {"fov_axis", c.fov_axis_x ? "x" : "y"}};
    j["image"] = {{"width", c.width}, {"height", c.height}, {"spp", c.samples_per_pixel}};
    if (c.exposure > 0)
        j["image"]["exposure"] = c.exposure;
}

std::string scene_json(const Scene& scene, const std::string& obj_file) {
    Json j;
    j["name"] = scene.name;
    j["units"] = "m";
    j["geometry"] = obj_file;
    if (Json m = materials_json(scene); !m.empty())
        j["materials"] = m;
    put_lights_and_sensors(j, scene);
    if (scene.camera)
        put_camera(j, *scene.camera);
    if (Json m = mesher_json(scene.mesher); !m.empty())
        j["mesher"] = m;
    j["solver"] = solver_json(scene.solver);
    std::string out;
    pretty(out, j, 0);
    return out + "\n";
}

} // namespace

void write_scene(const Scene& scene, const std::string& dir, const std::string& stem) {
    const std::filesystem::path folder(dir);
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (ec)
        throw ConfigError(fmt::format("cannot create output folder '{}': {}", dir, ec.message()));
    write_text_file((folder / (stem + ".mtl")).string(), mtl_text(scene));
    write_text_file((folder / (stem + ".obj")).string(), obj_text(scene, stem + ".mtl"));
    write_text_file((folder / "scene.json").string(), scene_json(scene, stem + ".obj"));
}

} // namespace penumbra::bench
