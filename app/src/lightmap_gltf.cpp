// The glTF copy of a lightmap bake, built as a tinygltf::Model. Each chart's vertices are the
// glTF vertices (a vertex on a seam between charts is repeated: it has two lightmap UVs), split
// again where triangles of one chart have different flat normals. glTF asks for numbered
// attribute sets from 0, so TEXCOORD_0 repeats TEXCOORD_1 (no base colour texture reads it).
// tinygltf writes buffers beside a file only without a temporary name, so the model is
// serialized to a string and the buffer's entry (scene.bin) added to that JSON here.

#include "lightmap_gltf.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>
#include <unordered_map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "core/error.h"
#include "core/files.h"
#include "core/material.h"

namespace penumbra::app {

namespace {

namespace fs = std::filesystem;

// The rotation that turns the scene's up onto +Y by the smallest angle (Rodrigues): z-up
// scenes get (x, y, z) → (x, z, −y); a scene whose up is −Y turns 180° about x.
struct Rotation {
    Vec3 rows[3];
    Vec3 operator()(const Vec3& v) const {
        return {dot(rows[0], v), dot(rows[1], v), dot(rows[2], v)};
    }
};

Rotation up_to_y(const Vec3& up_in) {
    const Vec3 u = normalize(up_in), y{0, 1, 0};
    const double c = dot(u, y);
    if (c < -1 + 1e-12)
        return {{{1, 0, 0}, {0, -1, 0}, {0, 0, -1}}};
    const Vec3 k = cross(u, y);
    const double f = 1 / (1 + c);
    // R = I + [k]× + [k]×² / (1 + c), with [k]×² = k kᵀ − |k|² I.
    const double kk = dot(k, k);
    return {{{1 + f * (k.x * k.x - kk), -k.z + f * k.x * k.y, k.y + f * k.x * k.z},
             {k.z + f * k.y * k.x, 1 + f * (k.y * k.y - kk), -k.x + f * k.y * k.z},
             {-k.y + f * k.z * k.x, k.x + f * k.z * k.y, 1 + f * (k.z * k.z - kk)}}};
}

// Appends accessors and their buffer views to the model's single buffer.
class BufferWriter {
public:
    explicit BufferWriter(tinygltf::Model& model) : model_(model) {}

    template <typename T>
    int add(const std::vector<T>& values, int component_type, int type, int count, int target,
            std::vector<double> min = {}, std::vector<double> max = {}) {
        tinygltf::BufferView view;
        view.buffer = 0;
        view.byteOffset = bytes_.size();
        view.byteLength = values.size() * sizeof(T);
        view.target = target;
        bytes_.resize(bytes_.size() + view.byteLength);
        std::memcpy(bytes_.data() + view.byteOffset, values.data(), view.byteLength);
        model_.bufferViews.push_back(view);
        tinygltf::Accessor accessor;
        accessor.bufferView = int(model_.bufferViews.size() - 1);
        accessor.componentType = component_type;
        accessor.type = type;
        accessor.count = std::size_t(count);
        accessor.minValues = std::move(min);
        accessor.maxValues = std::move(max);
        model_.accessors.push_back(accessor);
        return int(model_.accessors.size() - 1);
    }
    const std::vector<unsigned char>& bytes() const { return bytes_; }

private:
    tinygltf::Model& model_;
    std::vector<unsigned char> bytes_; ///< float and uint32 data only: 4-byte aligned throughout
};

// The triangles of one object with one material in one atlas.
struct PrimitiveData {
    std::vector<float> positions, normals, uv;
    std::vector<std::uint32_t> indices;
    // (chart, chart vertex, flat normal) → glTF vertex.
    std::map<std::tuple<std::uint32_t, std::uint32_t, float, float, float>, std::uint32_t> index_of;

    std::uint32_t vertex(std::uint32_t chart, std::uint32_t v, const Vec3f& p, const Vec3f& n,
                         const Vec2& texcoord) {
        const auto [it, added] =
            index_of.try_emplace({chart, v, n.x, n.y, n.z}, std::uint32_t(positions.size() / 3));
        if (added) {
            positions.insert(positions.end(), {p.x, p.y, p.z});
            normals.insert(normals.end(), {n.x, n.y, n.z});
            uv.insert(uv.end(), {float(texcoord.x), float(texcoord.y)});
        }
        return it->second;
    }
};

// Per object (in the order of their first chart), its primitives by (material, atlas).
struct ObjectData {
    std::string name;
    std::map<std::pair<std::uint32_t, std::uint32_t>, PrimitiveData> primitives;
};

std::vector<ObjectData> collect_objects(const Scene& scene, const LightmapResult& r,
                                        const Rotation& rotate) {
    std::vector<ObjectData> objects;
    std::unordered_map<std::string, std::size_t> object_of;
    const double size = r.layout.size;
    for (std::uint32_t c = 0; c < r.charts.charts.size(); ++c) {
        const lightmap::Chart& chart = r.charts.charts[c];
        const lightmap::ChartPlacement& place = r.layout.placements[c];
        const auto [it, added] = object_of.try_emplace(chart.object, objects.size());
        if (added)
            objects.push_back({chart.object, {}});
        for (const lightmap::ChartTriangle& t : chart.triangles) {
            PrimitiveData& prim =
                objects[it->second].primitives[{scene.polygons[t.polygon].material, place.atlas}];
            auto v = t.vertices;
            const Vec3 a = chart.vertices[v[0]].position, b = chart.vertices[v[1]].position,
                       d = chart.vertices[v[2]].position;
            // glTF's front faces are counter-clockwise; the chart covers the side of its normal.
            if (dot(cross(b - a, d - a), t.normal) < 0)
                std::swap(v[1], v[2]);
            const Vec3f n(normalize(rotate(t.normal)));
            for (std::uint32_t k : v)
                prim.indices.push_back(prim.vertex(c, k, Vec3f(rotate(chart.vertices[k].position)),
                                                   n, place.texel_uv[k] * (1.0 / size)));
        }
    }
    return objects;
}

std::pair<std::vector<double>, std::vector<double>> bounds(const std::vector<float>& xyz) {
    std::vector<double> lo(3, std::numeric_limits<double>::infinity()), hi(3, -lo[0]);
    for (std::size_t i = 0; i < xyz.size(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], double(xyz[i]));
        hi[i % 3] = std::max(hi[i % 3], double(xyz[i]));
    }
    return {lo, hi};
}

tinygltf::Primitive add_primitive(BufferWriter& out, const PrimitiveData& p, int material) {
    const int vertices = int(p.positions.size() / 3);
    const auto [lo, hi] = bounds(p.positions);
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.material = material;
    prim.attributes["POSITION"] =
        out.add(p.positions, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, vertices,
                TINYGLTF_TARGET_ARRAY_BUFFER, lo, hi);
    prim.attributes["NORMAL"] = out.add(p.normals, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                        TINYGLTF_TYPE_VEC3, vertices, TINYGLTF_TARGET_ARRAY_BUFFER);
    const int uv = out.add(p.uv, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, vertices,
                           TINYGLTF_TARGET_ARRAY_BUFFER);
    prim.attributes["TEXCOORD_0"] = uv;
    prim.attributes["TEXCOORD_1"] = uv;
    prim.indices = out.add(p.indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR,
                           int(p.indices.size()), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    return prim;
}

// A material: the scene material's diffuse colour and emission, the atlas's lightmap.
tinygltf::Material make_material(const Material& m, std::uint32_t atlas, int atlases,
                                 double intensity) {
    tinygltf::Material out;
    out.name = atlases > 1 ? fmt::format("{} (lightmap {})", m.name, atlas) : m.name;
    const Rgb rho = diffuse_reflectance(m);
    out.pbrMetallicRoughness.baseColorFactor = {rho.r, rho.g, rho.b, 1.0};
    out.pbrMetallicRoughness.metallicFactor = 0;
    out.pbrMetallicRoughness.roughnessFactor = 1;
    out.emissiveFactor = {0, 0, 0};
    // Emitted luminance in cd/m² (179 lm/W × radiance), the units of the lightmaps' lux × ρ/π.
    const double peak = std::max({m.emission.r, m.emission.g, m.emission.b});
    if (peak > 0) {
        out.emissiveFactor = {m.emission.r / peak, m.emission.g / peak, m.emission.b / peak};
        out.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(tinygltf::Value::Object{
            {"emissiveStrength", tinygltf::Value(k_luminous_efficacy_lm_per_w * peak)}});
    }
    tinygltf::Value::Object texture{{"index", tinygltf::Value(int(atlas))},
                                    {"texCoord", tinygltf::Value(1)}};
    out.extensions["MOZ_lightmap"] = tinygltf::Value(tinygltf::Value::Object{
        {"texture", tinygltf::Value(texture)}, {"intensity", tinygltf::Value(intensity)}});
    return out;
}

// One texture per atlas (texture N = image N = lightmap_N.png), sampled linearly, clamped.
void add_atlas_textures(tinygltf::Model& model, std::size_t atlases) {
    tinygltf::Sampler sampler;
    sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    sampler.wrapS = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    sampler.wrapT = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    model.samplers.push_back(sampler);
    for (std::size_t a = 0; a < atlases; ++a) {
        tinygltf::Image image;
        image.uri = fmt::format("lightmap_{}.png", a);
        image.mimeType = "image/png";
        model.images.push_back(image);
        tinygltf::Texture texture;
        texture.source = int(a);
        texture.sampler = 0;
        model.textures.push_back(texture);
    }
}

// The scene camera as a node: glTF cameras look along their local −Z with +Y up.
void add_camera(tinygltf::Model& model, const Camera& c, const Rotation& rotate,
                double scene_diagonal) {
    tinygltf::Camera camera;
    camera.type = "perspective";
    camera.name = "camera";
    const double aspect = double(c.width) / double(c.height);
    const double tan_half = std::tan(c.fov_deg * k_pi / 360.0);
    camera.perspective.aspectRatio = aspect;
    camera.perspective.yfov = 2 * std::atan(c.fov_axis_x ? tan_half / aspect : tan_half);
    camera.perspective.znear = 1e-3 * scene_diagonal;
    camera.perspective.zfar = 10 * scene_diagonal;
    model.cameras.push_back(camera);
    const Vec3 eye = rotate(c.eye), forward = normalize(rotate(c.look_at - c.eye));
    const Vec3 right = normalize(cross(forward, rotate(c.up))), up = cross(right, forward);
    tinygltf::Node node;
    node.name = "camera";
    node.camera = 0;
    node.matrix = {right.x,    right.y,    right.z,    0, up.x,  up.y,  up.z,  0,
                   -forward.x, -forward.y, -forward.z, 0, eye.x, eye.y, eye.z, 1};
    model.nodes.push_back(node);
}

tinygltf::Model build_model(const Scene& scene, const LightmapResult& r,
                            const std::vector<double>& intensities,
                            std::vector<unsigned char>& bytes) {
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "penumbra lightmap";
    model.extensionsUsed = {"MOZ_lightmap"};
    const Rotation rotate = up_to_y(scene.up);
    BufferWriter out(model);
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> material_of;
    tinygltf::Scene root;
    for (const ObjectData& object : collect_objects(scene, r, rotate)) {
        tinygltf::Mesh mesh;
        mesh.name = object.name;
        for (const auto& [key, data] : object.primitives) {
            const auto [it, added] = material_of.try_emplace(key, int(model.materials.size()));
            if (added)
                model.materials.push_back(make_material(scene.materials[key.first], key.second,
                                                        r.layout.atlas_count,
                                                        intensities[key.second]));
            mesh.primitives.push_back(add_primitive(out, data, it->second));
        }
        model.meshes.push_back(mesh);
        tinygltf::Node node;
        node.name = object.name;
        node.mesh = int(model.meshes.size() - 1);
        root.nodes.push_back(int(model.nodes.size()));
        model.nodes.push_back(node);
    }
    if (std::any_of(model.materials.begin(), model.materials.end(), [](const auto& m) {
            return m.extensions.count("KHR_materials_emissive_strength") > 0;
        }))
        model.extensionsUsed.push_back("KHR_materials_emissive_strength");
    add_atlas_textures(model, r.atlases.size());
    if (scene.camera) {
        root.nodes.push_back(int(model.nodes.size()));
        add_camera(model, *scene.camera, rotate, scene.bounds().diagonal());
    }
    model.scenes.push_back(root);
    model.defaultScene = 0;
    bytes = out.bytes();
    return model;
}

// The model as glTF JSON with its one buffer in \p bin_uri (tinygltf's stream writer would
// embed it as base64).
std::string gltf_json(const tinygltf::Model& model, std::size_t bin_bytes,
                      const std::string& bin_uri) {
    tinygltf::TinyGLTF writer;
    writer.SetImageWriter(nullptr, nullptr); // images stay references to lightmap_N.png
    std::ostringstream stream;
    if (!writer.WriteGltfSceneToStream(&model, stream, false, false))
        throw ExternalError("tinygltf could not serialize the lightmap glTF");
    auto json = nlohmann::ordered_json::parse(stream.str());
    json["buffers"] = nlohmann::ordered_json::array(
        {nlohmann::ordered_json{{"byteLength", bin_bytes}, {"uri", bin_uri}}});
    return json.dump(2) + "\n";
}

} // namespace

std::vector<double> lightmap_intensities(const std::vector<Image>& atlases) {
    std::vector<double> out;
    for (const Image& atlas : atlases) {
        double peak = 0;
        for (const Rgb& e : atlas.pixels)
            peak = std::max({peak, double(e.r), double(e.g), double(e.b)});
        out.push_back(peak > 0 ? k_luminous_efficacy_lm_per_w * peak : 1.0);
    }
    return out;
}

void write_moz_lightmaps(const std::string& dir, const std::vector<Image>& atlases,
                         const std::vector<double>& intensities) {
    for (std::size_t a = 0; a < atlases.size(); ++a)
        write_png((fs::path(dir) / fmt::format("lightmap_{}.png", a)).string(), atlases[a],
                  k_luminous_efficacy_lm_per_w / intensities[a]);
}

void write_lightmap_gltf(const std::string& dir, const Scene& scene, const LightmapResult& r,
                         const std::vector<double>& intensities) {
    std::vector<unsigned char> bytes;
    const tinygltf::Model model = build_model(scene, r, intensities, bytes);
    write_atomically((fs::path(dir) / "scene.bin").string(), [&](const std::string& temp) {
        std::ofstream file(temp, std::ios::binary);
        file.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        if (!file.flush())
            throw ExternalError(fmt::format("cannot write '{}'", temp));
    });
    write_text_file((fs::path(dir) / "scene.gltf").string(),
                    gltf_json(model, bytes.size(), "scene.bin"));
}

} // namespace penumbra::app
