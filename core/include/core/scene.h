#pragma once
// The scene description: polygons with materials, point lights, the sun, sensors, camera and
// the settings of each stage. Everything is in metres and radiometric RGB after loading; the
// scene file's units and photometric quantities are converted by the loader.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/light.h"
#include "core/rgb.h"
#include "core/vec.h"

namespace penumbra {

/// \brief A diffuse material. Emission is the emitted radiance of the front side (and of the
///        back side too when emission_two_sided).
struct Material {
    std::string name;
    Rgb reflectance{0.5f}; ///< diffuse reflectance ρ, each channel in [0, 1)
    Rgb emission{};        ///< emitted radiance, W/(sr·m²)
    bool two_sided = true; ///< front and back are separate receiving elements
    bool emission_two_sided = false;
    /// If set, the loader scales emission so that all polygons of this material together emit
    /// this luminous flux (lm); emission then holds the colour until scaling.
    std::optional<double> emission_flux_lm;
};

/// \brief A planar (or nearly planar) input polygon, counter-clockwise seen from its front.
struct Polygon {
    std::vector<Vec3> vertices; ///< metres
    std::uint32_t material = 0; ///< index into Scene::materials
    std::string name;           ///< object name from the file, for messages and output
    std::string source;         ///< "file:face-index" for messages
};

/// \brief A sensor: a point and the normal of the receiving plane.
struct Sensor {
    std::string name;
    Vec3 position; ///< metres
    Vec3 normal;   ///< unit
};

struct Camera {
    Vec3 eye{0, 0, 0}, look_at{0, 0, -1}, up{0, 1, 0}; ///< metres
    double fov_deg = 45.0;
    bool fov_axis_x = true; ///< the field of view spans the image width (else height)
    int width = 512, height = 512;
    int samples_per_pixel = 16; ///< stratified, rounded up to a square number
    double exposure = 0.0;      ///< 0 = automatic; else multiplier on radiance before sRGB
};

/// \brief Discontinuity meshing (issue #5): shadow boundaries of emissive polygons, point
///        lights and the sun inserted as element edges.
struct DiscontinuitySettings {
    bool enabled = true;
    int max_order = 2; ///< highest order inserted: 0 = D0 only, 1 = D0 and D1, 2 = D0 to D2
};

struct MesherSettings {
    double max_edge_length = 0.0;      ///< metres; 0 = scene diagonal / 20
    double planarity_tolerance = 1e-4; ///< relative to the polygon's size
    /// Split surfaces where others touch or cut them, close near-contacts and drop hidden parts.
    bool split_contacts = true;
    /// Metres; gaps up to this count as contacts. Unset = min(2 mm, 1e-3 × scene diagonal).
    std::optional<double> contact_tolerance;
    std::int64_t element_budget = 200000; ///< most elements (both sides); 0 = no limit
    DiscontinuitySettings discontinuity;
};

struct SolverSettings {
    /// "hierarchical" (default), "shooting", "gathering" (= "gauss_seidel"), "jacobi",
    /// "gauss_seidel" or "matrix".
    std::string method = "hierarchical";
    double residual = 1e-3; ///< stop when unshot (or changing) power / emitted falls below
    double epsilon = 1e-3; ///< hierarchical: refine links whose estimate > ε × brightest exitance
    /// hierarchical: "variation" (ΔF·B, the form factor's spread over the receiver times the
    /// source radiosity) or "bf" (F·B, Hanrahan et al. 1991).
    std::string oracle = "variation";
    double min_area = 0; ///< hierarchical: m², smallest element; 0 = (diagonal / 200)²
    /// hierarchical: "auto" (clusters when the mesh has more than 3 000 elements), "on", "off".
    std::string clustering = "auto";
    /// hierarchical: how each solve between refinements iterates: "jacobi", "gauss_seidel"
    /// (by blocks of 32 roots) or "shooting" (progressive, Southwell, on the hierarchy).
    std::string iteration = "jacobi";
    int max_sweeps = 500;       ///< gathering: most sweeps per solve
    bool ambient = false;       ///< add the ambient term (previews only)
    std::int64_t max_shots = 0; ///< 0 = 10 000 × element count
    int visibility_rays = 16;   ///< rays per element pair its probes do not show fully visible
    double row_cache_mb = 2048; ///< memory for cached form-factor rows
};

struct Scene {
    std::string name;
    std::string file; ///< the scene file, for messages
    std::vector<Material> materials;
    std::vector<Polygon> polygons;
    std::vector<PointLight> point_lights;
    std::optional<Sun> sun;
    std::vector<Sensor> sensors;
    std::optional<Camera> camera;
    MesherSettings mesher;
    SolverSettings solver;

    BBox bounds() const;
    /// Some polygon emits, or a point light or the sun has a non-zero intensity.
    bool has_emitter() const;
};

} // namespace penumbra
