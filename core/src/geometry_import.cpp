// Geometry import through assimp (Open Asset Import Library, 5.2).
// Deliberately no post-processing flags: aiProcess_Triangulate would split quads that the
// mesher wants whole, and FindDegenerates / FlipWindingOrder / MakeLeftHanded would hide or
// change what the file says. Bad faces are reported by validate_scene instead.
// Node transforms are accumulated in double precision; assimp stores vertices as float.

#include "geometry_import.h"

#include <algorithm>
#include <filesystem>
#include <set>
#include <sstream>

#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include "core/error.h"
#include "core/files.h"

namespace penumbra {

namespace {

using Transform = aiMatrix4x4t<double>;

Material convert_material(const aiMaterial& source, unsigned index) {
    Material material;
    aiString name;
    if (source.Get(AI_MATKEY_NAME, name) == aiReturn_SUCCESS && name.length > 0)
        material.name = name.C_Str();
    else
        material.name = fmt::format("material_{}", index);
    aiColor3D color;
    if (source.Get(AI_MATKEY_COLOR_DIFFUSE, color) == aiReturn_SUCCESS)
        material.reflectance = Rgb(color.r, color.g, color.b);
    // OBJ `Ke` and glTF `emissiveFactor` both arrive here (checked with assimp 5.2.5).
    if (source.Get(AI_MATKEY_COLOR_EMISSIVE, color) == aiReturn_SUCCESS)
        material.emission = Rgb(color.r, color.g, color.b);
    float strength = 1.0f; // glTF KHR_materials_emissive_strength
    if (source.Get(AI_MATKEY_EMISSIVE_INTENSITY, strength) == aiReturn_SUCCESS)
        material.emission *= strength;
    return material;
}

// The second UV channel of the face's corners. assimp flips v (1 − v) on import to its
// bottom-left origin; flipping back gives glTF's top-left one (Polygon::lightmap_uv).
std::vector<Vec2> lightmap_uv(const aiMesh& mesh, const aiFace& face) {
    std::vector<Vec2> uv;
    for (unsigned k = 0; k < face.mNumIndices; ++k) {
        const aiVector3D& t = mesh.mTextureCoords[1][face.mIndices[k]];
        uv.push_back({double(t.x), 1.0 - double(t.y)});
    }
    return uv;
}

/// Walks the node tree, accumulating transforms, and emits one Polygon per face of three or
/// more vertices.
class PolygonCollector {
public:
    PolygonCollector(const aiScene& scene, const std::string& label, double metres_per_unit)
        : scene_(scene), label_(label), scale_(metres_per_unit) {}

    void visit(const aiNode& node, const Transform& parent) {
        const Transform global = parent * static_cast<Transform>(node.mTransformation);
        for (unsigned i = 0; i < node.mNumMeshes; ++i) {
            const aiMesh& mesh = *scene_.mMeshes[node.mMeshes[i]];
            const std::string name =
                node.mName.length > 0 ? node.mName.C_Str() : mesh.mName.C_Str();
            add_mesh(mesh, name, global);
        }
        for (unsigned i = 0; i < node.mNumChildren; ++i)
            visit(*node.mChildren[i], global);
    }

    std::vector<Polygon> take() { return std::move(polygons_); }

private:
    void add_mesh(const aiMesh& mesh, const std::string& name, const Transform& transform) {
        const bool mirrored = transform.Determinant() < 0;
        // 0 · NaN is NaN: an identity product would smear one bad coordinate over all three.
        const bool identity = transform == Transform();
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
            const aiFace& face = mesh.mFaces[f];
            if (face.mNumIndices < 3)
                continue; // points and lines have no area to light
            Polygon polygon;
            polygon.name = name;
            polygon.material = mesh.mMaterialIndex;
            polygon.source = fmt::format("{}:face {}", label_, ++face_count_);
            polygon.vertices.reserve(face.mNumIndices);
            for (unsigned k = 0; k < face.mNumIndices; ++k) {
                const aiVector3D& v = mesh.mVertices[face.mIndices[k]];
                aiVector3t<double> p(v.x, v.y, v.z);
                if (!identity)
                    p = transform * p;
                polygon.vertices.emplace_back(p.x * scale_, p.y * scale_, p.z * scale_);
            }
            if (mesh.HasTextureCoords(1))
                polygon.lightmap_uv = lightmap_uv(mesh, face);
            // A mirror turns counter-clockwise into clockwise; reversing the order (keeping
            // vertex 1 first) restores the file's front side.
            if (mirrored) {
                std::reverse(polygon.vertices.begin() + 1, polygon.vertices.end());
                if (!polygon.lightmap_uv.empty())
                    std::reverse(polygon.lightmap_uv.begin() + 1, polygon.lightmap_uv.end());
            }
            polygons_.push_back(std::move(polygon));
        }
    }

    const aiScene& scene_;
    const std::string& label_;
    double scale_;
    std::size_t face_count_ = 0;
    std::vector<Polygon> polygons_;
};

/// Converts the materials that faces use (which drops assimp's default materials: OBJ's
/// "DefaultMaterial", glTF's unnamed one), makes names unique within the file ("name#2") and
/// renumbers the polygons' material indices.
ImportedGeometry collect_materials(const aiScene& scene, std::vector<Polygon> polygons,
                                   const std::string& path) {
    std::vector<bool> used(scene.mNumMaterials, false);
    for (const Polygon& polygon : polygons) {
        if (polygon.material >= scene.mNumMaterials)
            throw InputError(path, "geometry",
                             fmt::format("{} refers to material {} of {}", polygon.source,
                                         polygon.material, scene.mNumMaterials));
        used[polygon.material] = true;
    }
    ImportedGeometry result;
    std::vector<std::uint32_t> remap(scene.mNumMaterials, 0);
    std::set<std::string> names;
    for (unsigned i = 0; i < scene.mNumMaterials; ++i) {
        if (!used[i])
            continue;
        Material material = convert_material(*scene.mMaterials[i], i);
        const std::string base = material.name;
        for (int k = 2; names.count(material.name) > 0; ++k)
            material.name = fmt::format("{}#{}", base, k);
        names.insert(material.name);
        remap[i] = std::uint32_t(result.materials.size());
        result.materials.push_back(std::move(material));
    }
    for (Polygon& polygon : polygons)
        polygon.material = remap[polygon.material];
    result.polygons = std::move(polygons);
    return result;
}

} // namespace

namespace {

// assimp imports an OBJ whose mtllib is missing with default materials and no word: every
// emitter of the scene would be lost without a message.
void check_obj_material_libraries(const std::string& path) {
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    std::istringstream in(read_text_file(path));
    int number = 0;
    for (std::string line; std::getline(in, line);) {
        ++number;
        std::istringstream tokens(line);
        std::string keyword;
        if (!(tokens >> keyword) || keyword != "mtllib")
            continue;
        for (std::string library; tokens >> library;) {
            std::error_code ec;
            if (!std::filesystem::is_regular_file(folder / library, ec))
                throw InputError(path, "", fmt::format("material library '{}' not found", library),
                                 number);
        }
    }
}

} // namespace

ImportedGeometry import_geometry(const std::string& path, const std::string& label,
                                 double metres_per_unit) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw InputError(path, "geometry", "geometry file not found");
    if (std::filesystem::path(path).extension() == ".obj")
        check_obj_material_libraries(path);
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(path, 0); // no post-processing, see above
    if (!scene || !scene->mRootNode)
        throw InputError(path, "geometry",
                         fmt::format("cannot import: {}", importer.GetErrorString()));
    PolygonCollector collector(*scene, label, metres_per_unit);
    collector.visit(*scene->mRootNode, Transform());
    return collect_materials(*scene, collector.take(), path);
}

} // namespace penumbra
