// Material mapping of geometry files (checked with assimp 5.2.5: the MTL keys arrive as
// $mat.illum, $clr.specular, $mat.shininess, $mat.roughnessFactor (only when Pr is given),
// $mat.refracti, $clr.transparent and $mat.opacity (d, or 1 − Tr); glTF's as $clr.base,
// $mat.metallicFactor and $mat.roughnessFactor (their glTF defaults 1 when absent),
// $mat.transmission.factor, $mat.refracti and $mat.volume.thicknessFactor when given).

#include "imported_material.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

#include <assimp/ObjMaterial.h>
#include <assimp/material.h>
#include <fmt/format.h>

#include "core/error.h"

namespace penumbra {

namespace {

/// The smallest GGX α an imported material gets: a roughness of 0 (glTF) or a smooth coat
/// (MTL) is not a lobe of its own, and α = 0.001 reflects like a mirror to within a degree.
constexpr double k_min_imported_alpha = 1e-3;

/// glTF's Fresnel reflectance at normal incidence of a non-metal (ior 1.5).
constexpr float k_gltf_dielectric_f0 = 0.04f;

struct Source {
    const aiMaterial& material;
    const std::string& name;
    const std::string& path;

    std::optional<float> number(const char* key, unsigned type, unsigned index) const {
        float value = 0;
        if (material.Get(key, type, index, value) != aiReturn_SUCCESS)
            return std::nullopt;
        return value;
    }
    std::optional<Rgb> colour(const char* key, unsigned type, unsigned index) const {
        aiColor4D c; // reads three or four components
        if (material.Get(key, type, index, c) != aiReturn_SUCCESS)
            return std::nullopt;
        return Rgb(c.r, c.g, c.b);
    }
    [[noreturn]] void fail(const char* key, const std::string& what) const {
        throw InputError(path, fmt::format("{}.{}", name, key), what);
    }
    /// \p value within [lo, hi] (per channel), else an error naming the file's key.
    void expect_range(const char* key, double value, double lo, double hi) const {
        if (!(value >= lo && value <= hi))
            fail(key, fmt::format("must be in [{}, {}], got {}", lo, hi, value));
    }
    void expect_unit(const char* key, const Rgb& c) const {
        for (int i = 0; i < 3; ++i)
            expect_range(key, c[i], 0, 1);
    }
};

// ---- MTL ----------------------------------------------------------------------------------------

/// GGX α of an MTL material: Pr², else √(2 / (Ns + 2)) for Ns > 0; none for a smooth surface
/// (Pr 0, or neither Pr nor Ns: assimp reads a missing Ns as 0).
std::optional<double> mtl_alpha(const Source& s) {
    if (const auto pr = s.number(AI_MATKEY_ROUGHNESS_FACTOR)) {
        s.expect_range("Pr", *pr, 0, 1);
        return *pr > 0 ? std::optional(double(*pr) * *pr) : std::nullopt;
    }
    const float ns = s.number(AI_MATKEY_SHININESS).value_or(0);
    if (!(ns >= 0))
        s.fail("Ns", fmt::format("must be >= 0, got {}", ns));
    return ns > 0 ? std::optional(std::sqrt(2.0 / (ns + 2.0))) : std::nullopt;
}

/// illum 3: mirror-like reflection of colour Ks, rough by Pr or Ns; a coat over Kd if any.
std::optional<Lobe> mtl_reflection(const Source& s, const Rgb& diffuse) {
    const Rgb ks = s.colour(AI_MATKEY_COLOR_SPECULAR).value_or(Rgb{});
    s.expect_unit("Ks", ks);
    if (ks.is_black())
        return std::nullopt;
    const std::optional<double> alpha = mtl_alpha(s);
    if (!alpha && diffuse.is_black())
        return Mirror{ks};
    return GgxGlossy{std::max(alpha.value_or(0), k_min_imported_alpha), ks, FresnelNone{},
                     !diffuse.is_black()};
}

std::optional<Lobe> mtl_lobe(const Source& s, const Rgb& diffuse) {
    const int illum = [&] {
        int value = 0;
        return s.material.Get(AI_MATKEY_OBJ_ILLUM, value) == aiReturn_SUCCESS ? value : 0;
    }();
    const float ni = s.number(AI_MATKEY_REFRACTI).value_or(1);
    const Rgb tf = s.colour(AI_MATKEY_COLOR_TRANSPARENT).value_or(Rgb(1.0f));
    const float d = s.number(AI_MATKEY_OPACITY).value_or(1);
    if (illum == 6 || illum == 7) { // refraction: a solid dielectric
        s.expect_range("Ni", ni, 1, 10);
        s.expect_unit("Tf", tf);
        return Dielectric{ni, true, tf};
    }
    if (d < 1) { // dissolve: a pane that passes (1 − d) Tf
        s.expect_range("d", d, 0, 1);
        s.expect_unit("Tf", tf);
        return ThinGlass{tf * (1.0f - d), ni > 1 ? double(ni) : ThinGlass{}.ior};
    }
    if (illum == 3)
        return mtl_reflection(s, diffuse);
    return std::nullopt;
}

// ---- glTF ---------------------------------------------------------------------------------------

/// KHR_materials_transmission: glass tinted by the base colour times the transmission factor;
/// a solid body with KHR_materials_volume (thickness > 0), else thin-walled (thin glass).
Lobe gltf_transmission(const Source& s, const Rgb& base, float transmission) {
    const float ior = s.number(AI_MATKEY_REFRACTI).value_or(1.5f);
    s.expect_range("KHR_materials_ior", ior, 1, 10);
    const Rgb passed = base * transmission;
    s.expect_unit("baseColorFactor", passed);
    if (s.number(AI_MATKEY_VOLUME_THICKNESS_FACTOR).value_or(0) > 0)
        return Dielectric{ior, true, passed};
    return ThinGlass{passed, ior};
}

/// Metallic-roughness: a coat of Schlick F0 = mix(0.04, base, m) over a diffuse part
/// (1 − m) base; a pure metal (m = 1) has no diffuse part. α = r².
void gltf_metallic_roughness(const Source& s, const Rgb& base, Material& material) {
    const float metallic = s.number(AI_MATKEY_METALLIC_FACTOR).value_or(1);
    const float roughness = s.number(AI_MATKEY_ROUGHNESS_FACTOR).value_or(1);
    s.expect_range("metallicFactor", metallic, 0, 1);
    s.expect_range("roughnessFactor", roughness, 0, 1);
    s.expect_unit("baseColorFactor", base);
    GgxGlossy coat;
    coat.alpha = std::max(double(roughness) * roughness, k_min_imported_alpha);
    coat.specular = Rgb(k_gltf_dielectric_f0) * (1.0f - metallic) + base * metallic;
    coat.fresnel = FresnelSchlick{};
    coat.diffuse_base = metallic < 1;
    material.reflectance = coat.diffuse_base ? base * (1.0f - metallic) : Rgb{};
    material.lobe = coat;
}

void gltf_lobe(const Source& s, Material& material) {
    const Rgb base = s.colour(AI_MATKEY_BASE_COLOR).value_or(material.reflectance);
    const float transmission = s.number(AI_MATKEY_TRANSMISSION_FACTOR).value_or(0);
    s.expect_range("KHR_materials_transmission", transmission, 0, 1);
    if (transmission > 0) {
        material.reflectance = Rgb{};
        material.lobe = gltf_transmission(s, base, transmission);
        return;
    }
    gltf_metallic_roughness(s, base, material);
}

} // namespace

std::string lowercase_extension(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

MaterialConvention material_convention(const std::string& path) {
    const std::string extension = lowercase_extension(path);
    if (extension == ".obj")
        return MaterialConvention::mtl;
    if (extension == ".gltf" || extension == ".glb")
        return MaterialConvention::gltf;
    return MaterialConvention::other;
}

Material import_material(const aiMaterial& source, unsigned index, MaterialConvention convention,
                         const std::string& path) {
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
    const Source s{source, material.name, path};
    if (convention == MaterialConvention::mtl) {
        material.lobe = mtl_lobe(s, material.reflectance);
        material.reflectance = diffuse_reflectance(material);
    } else if (convention == MaterialConvention::gltf)
        gltf_lobe(s, material);
    return material;
}

} // namespace penumbra
