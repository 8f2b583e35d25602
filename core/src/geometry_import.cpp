// Geometry import through assimp (Open Asset Import Library, 5.2).
// Deliberately no post-processing flags: aiProcess_Triangulate would split quads that the
// mesher wants whole, and FindDegenerates / FlipWindingOrder / MakeLeftHanded would hide or
// change what the file says. Bad faces are reported by validate_scene instead.
// Node transforms are accumulated in double precision; assimp stores vertices as float.

#include "geometry_import.h"

#include <algorithm>
#include <filesystem>
#include <iterator>
#include <memory>
#include <set>
#include <sstream>

#include <assimp/BaseImporter.h>
#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include "core/error.h"
#include "core/files.h"

#include "imported_material.h"

namespace penumbra {

namespace {

using Transform = aiMatrix4x4t<double>;

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
        // Normals transform by the inverse transpose (a non-uniform scale tilts them).
        Transform normal_transform = transform;
        normal_transform.Inverse().Transpose();
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
            if (mesh.HasNormals())
                polygon.normals = face_normals(mesh, face, normal_transform);
            // A mirror turns counter-clockwise into clockwise; reversing the order (keeping
            // vertex 1 first) restores the file's front side.
            if (mirrored) {
                std::reverse(polygon.vertices.begin() + 1, polygon.vertices.end());
                if (!polygon.lightmap_uv.empty())
                    std::reverse(polygon.lightmap_uv.begin() + 1, polygon.lightmap_uv.end());
                if (!polygon.normals.empty())
                    std::reverse(polygon.normals.begin() + 1, polygon.normals.end());
            }
            polygons_.push_back(std::move(polygon));
        }
    }

    /// The vertex normals of \p face, through \p transform (its 3 × 3 part), normalised;
    /// none (flat) if one is zero or not finite (assimp fills a face without `vn` in a mesh
    /// with normals with zeros).
    static std::vector<Vec3> face_normals(const aiMesh& mesh, const aiFace& face,
                                          const Transform& transform) {
        std::vector<Vec3> normals;
        normals.reserve(face.mNumIndices);
        for (unsigned k = 0; k < face.mNumIndices; ++k) {
            const aiVector3D& n = mesh.mNormals[face.mIndices[k]];
            const Transform& t = transform;
            const Vec3 v(t.a1 * n.x + t.a2 * n.y + t.a3 * n.z, t.b1 * n.x + t.b2 * n.y + t.b3 * n.z,
                         t.c1 * n.x + t.c2 * n.y + t.c3 * n.z);
            if (!(is_finite(v) && length(v) > 0))
                return {};
            normals.push_back(normalize(v));
        }
        return normals;
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
        Material material =
            import_material(*scene.mMaterials[i], i, material_convention(path), path);
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

// A file is read as the format its extension names. Left to itself, assimp tries every reader
// by content when the extension's own readers refuse a file, and reports a broken .gltf as an
// OBJ error (issue #32). Throws the own reader's complaint; a file it can read, or an
// extension assimp does not know, is left to Importer::ReadFile.
void check_extension_reader(Assimp::Importer& importer, const std::string& path) {
    const std::string dotted = lowercase_extension(path);
    if (dotted.empty())
        return;
    const std::string extension = dotted.substr(1); // assimp lists extensions without the dot
    Assimp::BaseImporter* own = nullptr;
    for (std::size_t i = 0; i < importer.GetImporterCount(); ++i) {
        std::istringstream listed(importer.GetImporterInfo(i)->mFileExtensions);
        if (std::find(std::istream_iterator<std::string>(listed),
                      std::istream_iterator<std::string>(),
                      extension) == std::istream_iterator<std::string>())
            continue;
        own = importer.GetImporter(i);
        if (own->CanRead(path, importer.GetIOHandler(), false))
            return;
    }
    if (!own)
        return;
    // The last reader of the extension is the newest format's (glTF 2.0 after 1.0): its error.
    std::unique_ptr<aiScene> scene(own->ReadFile(&importer, path, importer.GetIOHandler()));
    const std::string why =
        own->GetErrorText().empty() ? "its reader refuses it" : own->GetErrorText();
    throw InputError(path, "geometry", fmt::format("not a readable .{} file: {}", extension, why));
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
    check_extension_reader(importer, path);
    const aiScene* scene = importer.ReadFile(path, 0); // no post-processing, see above
    if (!scene || !scene->mRootNode)
        throw InputError(path, "geometry",
                         fmt::format("cannot import: {}", importer.GetErrorString()));
    PolygonCollector collector(*scene, label, metres_per_unit);
    collector.visit(*scene->mRootNode, Transform());
    return collect_materials(*scene, collector.take(), path);
}

} // namespace penumbra
