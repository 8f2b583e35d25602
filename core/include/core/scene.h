#pragma once
// The scene description: polygons with materials, point lights, the sun, sensors, camera and
// the settings of each stage. Everything is in metres and radiometric RGB after loading; the
// scene file's units and photometric quantities are converted by the loader.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/enum_names.h"
#include "core/light.h"
#include "core/material.h"
#include "core/rgb.h"
#include "core/sky.h"
#include "core/vec.h"

namespace penumbra {

/// \brief A planar (or nearly planar) input polygon, counter-clockwise seen from its front.
struct Polygon {
    std::vector<Vec3> vertices; ///< metres
    std::uint32_t material = 0; ///< index into Scene::materials
    std::string name;           ///< object name from the file, for messages and output
    std::string source;         ///< "file:face-index" for messages
    /// The file's lightmap UV per vertex (glTF TEXCOORD_1: assimp's second UV channel), in
    /// glTF's convention: u right, v down, (0, 0) at the image's top-left. Empty when the file
    /// has none (OBJ has one UV set only: its objects always get generated charts).
    std::vector<Vec2> lightmap_uv;
    /// Shading normals (unit) per vertex, for the renderer to interpolate (issue #28): from the
    /// geometry file's vertex normals, only on objects the scene shades smoothly
    /// (`smooth_objects`); empty = flat. The mesher and the solver ignore them.
    std::vector<Vec3> normals;
};

/// \brief A sensor: a point and the normal of the receiving plane.
struct Sensor {
    std::string name;
    Vec3 position; ///< metres
    Vec3 normal;   ///< unit
};

/// \brief What a sensor grid covers (SensorGrid::kind).
enum class GridKind {
    work_plane, ///< `floor`: a plane at a height over a floor, sensors facing up
    wall,       ///< `wall`: points on a polygon, sensors facing its front
};
inline constexpr EnumName<GridKind> k_grid_kind_names[] = {
    {"work_plane", GridKind::work_plane},
    {"wall", GridKind::wall},
};
template <>
inline constexpr std::span<const EnumName<GridKind>> k_enum_names<GridKind> = k_grid_kind_names;

/// \brief A square lattice of sensors on a plane (scene key `grids`). Its points are sensors
///        of Scene::sensors; the lattice lets the outputs compute per-grid statistics and draw
///        plans. Lattice point (row r, column c) lies at origin + c·spacing·u + r·spacing·v.
struct SensorGrid {
    std::string name; ///< also names its output files: letters, digits, '_', '-', '.'
    GridKind kind = GridKind::work_plane;
    Vec3 origin;     ///< metres: lattice point (0, 0), present or not
    Vec3 u{1, 0, 0}; ///< unit: the direction of growing column index
    Vec3 v{0, 1, 0}; ///< unit, perpendicular to u: growing row index; u × v = sensor normal
    double spacing_m = 1.0;
    int rows = 0, columns = 0;
    /// rows × columns, row-major: each lattice point's index in Scene::sensors, or none where
    /// the point lies outside the outline or closer to it than the wall offset.
    std::vector<std::optional<std::uint32_t>> sensors;
    /// The boundary edges of the grid's polygon(s), moved onto the grid's plane (metres).
    std::vector<std::array<Vec3, 2>> outline;

    /// \brief The sensor at (\p row, \p column), none if absent or outside the lattice.
    std::optional<std::uint32_t> sensor_at(int row, int column) const;
    /// \brief The point at fractional lattice coordinates (\p row, \p column), metres.
    Vec3 point(double row, double column) const;
    /// \brief Whether the point at fractional lattice coordinates lies inside the outline
    ///        (even-odd rule), as plans colour it.
    bool covers(double row, double column) const;
};

struct Camera {
    Vec3 eye{0, 0, 0}, look_at{0, 0, -1}, up{0, 1, 0}; ///< metres
    double fov_deg = 45.0;
    bool fov_axis_x = true; ///< the field of view spans the image width (else height)
    int width = 512, height = 512;
    int samples_per_pixel = 16; ///< stratified, rounded up to a square number
    double exposure = 0.0;      ///< 0 = automatic; else multiplier on radiance before sRGB
    /// Thin-lens depth of field (the final gather, issue #28): radius of the lens, metres;
    /// 0 = a pinhole (everything sharp).
    double aperture_radius_m = 0.0;
    /// Distance from the eye to the plane in focus (perpendicular to the view axis), metres;
    /// unset = the distance to look_at.
    std::optional<double> focus_distance_m;
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

/// \brief Radiosity methods (SolverSettings::method).
enum class SolverMethod {
    hierarchical, ///< hierarchical radiosity with clustering (Hanrahan et al. 1991)
    shooting,     ///< progressive refinement on fixed elements (Cohen et al. 1988)
    jacobi,       ///< Jacobi gathering on fixed elements
    gauss_seidel, ///< Gauss–Seidel gathering on fixed elements
    matrix,       ///< a dense direct solve on fixed elements (small scenes)
};
inline constexpr EnumName<SolverMethod> k_solver_method_names[] = {
    {"hierarchical", SolverMethod::hierarchical},
    {"shooting", SolverMethod::shooting},
    {"jacobi", SolverMethod::jacobi},
    {"gauss_seidel", SolverMethod::gauss_seidel},
    {"gathering", SolverMethod::gauss_seidel},
    {"matrix", SolverMethod::matrix},
};
template <>
inline constexpr std::span<const EnumName<SolverMethod>> k_enum_names<SolverMethod> =
    k_solver_method_names;

/// \brief The hierarchical solver's refinement oracle (SolverSettings::oracle).
enum class RefinementOracle {
    variation, ///< ΔF·B: the form factor's spread over the receiver times the source radiosity
    bf,        ///< F·B (Hanrahan et al. 1991)
};
inline constexpr EnumName<RefinementOracle> k_refinement_oracle_names[] = {
    {"variation", RefinementOracle::variation},
    {"bf", RefinementOracle::bf},
};
template <>
inline constexpr std::span<const EnumName<RefinementOracle>> k_enum_names<RefinementOracle> =
    k_refinement_oracle_names;

/// \brief Whether the hierarchical solver starts from a cluster tree (SolverSettings::clustering).
enum class Clustering {
    automatic, ///< "auto": clusters when the mesh has more than 3 000 elements
    on,
    off,
};
inline constexpr EnumName<Clustering> k_clustering_names[] = {
    {"auto", Clustering::automatic},
    {"on", Clustering::on},
    {"off", Clustering::off},
};
template <>
inline constexpr std::span<const EnumName<Clustering>> k_enum_names<Clustering> =
    k_clustering_names;

/// \brief How each hierarchical solve between refinements iterates (SolverSettings::iteration).
enum class SolverIteration {
    jacobi,       ///< Jacobi sweeps
    gauss_seidel, ///< Gauss–Seidel sweeps by blocks of 32 roots
    shooting,     ///< progressive shooting (Southwell) on the hierarchy
};
inline constexpr EnumName<SolverIteration> k_solver_iteration_names[] = {
    {"jacobi", SolverIteration::jacobi},
    {"gauss_seidel", SolverIteration::gauss_seidel},
    {"shooting", SolverIteration::shooting},
};
template <>
inline constexpr std::span<const EnumName<SolverIteration>> k_enum_names<SolverIteration> =
    k_solver_iteration_names;

struct SolverSettings {
    SolverMethod method = SolverMethod::hierarchical;
    double residual = 1e-3; ///< stop when unshot (or changing) power / emitted falls below
    double epsilon = 1e-3; ///< hierarchical: refine links whose estimate > ε × brightest exitance
    RefinementOracle oracle = RefinementOracle::variation; ///< hierarchical
    double min_area = 0; ///< hierarchical: m², smallest element; 0 = (diagonal / 200)²
    Clustering clustering = Clustering::automatic;       ///< hierarchical
    SolverIteration iteration = SolverIteration::jacobi; ///< hierarchical
    int max_sweeps = 500;                                ///< gathering: most sweeps per solve
    bool ambient = false;                                ///< add the ambient term (previews only)
    std::int64_t max_shots = 0;                          ///< 0 = 10 000 × element count
    int visibility_rays = 16;   ///< rays per element pair its probes do not show fully visible
    double row_cache_mb = 2048; ///< memory for cached form-factor rows
};

/// \brief The pixel filter of rendered images (RenderSettings::pixel_filter).
enum class PixelFilter {
    box,      ///< every sample in the footprint weighs the same
    gaussian, ///< a Gaussian truncated to the footprint
};
inline constexpr EnumName<PixelFilter> k_pixel_filter_names[] = {
    {"box", PixelFilter::box},
    {"gaussian", PixelFilter::gaussian},
};
template <>
inline constexpr std::span<const EnumName<PixelFilter>> k_enum_names<PixelFilter> =
    k_pixel_filter_names;

/// \brief Ward's irradiance cache for the final gather's indirect light at Lambertian camera
///        hits (scene key `render.irradiance_cache`, issue #28; docs/rendering.md).
struct IrradianceCacheSettings {
    int rays = 256;     ///< stratified gather rays per record (rounded up to a square), >= 16
    double error = 0.2; ///< Ward's a in (0, 1]: records reach further as it grows
};

/// \brief Settings of `penumbra render` (scene key `render`, issue #28); its samples per pixel
///        are Camera::samples_per_pixel.
struct RenderSettings {
    int max_bounces = 16; ///< most scattering events along a path
    PixelFilter pixel_filter = PixelFilter::box;
    double filter_width_px = 1.0; ///< width of the filter's square footprint, in pixels
    /// Caustic photons the final gather stores (issue #28); 0 = no caustic photon map.
    int caustic_photons = 100000;
    /// Radius of the caustic density estimate, metres; unset = chosen from the scene.
    std::optional<double> caustic_radius_m;
    /// Set: the final gather reads Ward's irradiance cache at Lambertian camera hits.
    std::optional<IrradianceCacheSettings> irradiance_cache;
    /// Splitting at a camera path's first non-delta surface (issue #28): stratified light
    /// samples, and BSDF samples (gather rays; rounded up to a square) each carrying a path.
    /// Defaults measured on the Cornell box (docs/rendering.md): the gather's noise dominates.
    int light_samples = 4;
    int gather_rays = 16;
    /// Pixels whose camera samples see emitters (directly or through delta lobes) differ by R
    /// W/(sr·m²) are sampled again with about R / edge_tolerance rays; 0 = no refinement.
    double edge_tolerance = 0.004;
};

/// \brief Lightmap baking (scene key `lightmap`, issue #29).
struct LightmapSettings {
    int atlas_size = 1024;    ///< texels along each side of an atlas
    bool directional = false; ///< also the L1 SH atlases of incident radiance
    int gather = 0; ///< > 0: final-gather paths per texel sample instead of direct + indirect
};

/// \brief A box lattice of light probes (scene key `probes.grid`): along each axis
///        floor(extent / spacing) + 1 points spacing_m apart, centred in the box.
struct ProbeGrid {
    Vec3 min, max;                     ///< corners of the box, metres (min ≤ max per axis)
    double spacing_m = 1;              ///< > 0
    std::array<int, 3> counts() const; ///< points along x, y and z
    std::vector<Vec3> points() const;  ///< x fastest, then y, then z
};

/// \brief Light probes (scene key `probes`, issue #29): L2 SH irradiance at given points
///        and over a grid, written by `penumbra lightmap` and `bake`.
struct ProbeSettings {
    std::vector<Vec3> points; ///< metres
    std::optional<ProbeGrid> grid;
    int rays = 1024; ///< gather rays per probe over the sphere
    /// The points, then the grid's lattice points.
    std::vector<Vec3> positions() const;
};

/// \brief Settings of `penumbra annual` (scene key `annual`, issue #31).
struct AnnualSettings {
    /// `annual.blinds`: the shaded state of IES LM-83's blinds rule, `penumbra annual
    /// --blinds`: each a scene material of the same name with the entry's keys applied, which
    /// that material's polygons take while the blinds are closed.
    std::vector<Material> blinds;
};

/// \brief A camera of the scene's `cameras` list (issue #28), chosen by `--camera NAME`.
struct NamedCamera {
    std::string name;
    Camera camera;
};

struct Scene {
    std::string name;
    std::string file; ///< the scene file, for messages
    Vec3 up{0, 0, 1}; ///< unit: the scene's up direction (key `up`); exports turn it to +Y
    std::vector<Material> materials;
    std::vector<Polygon> polygons;
    std::vector<PointLight> point_lights;
    std::optional<Sun> sun;
    std::optional<Sky> sky; ///< sky and ground at infinity (issue #30)
    std::vector<Sensor> sensors;
    std::vector<SensorGrid> grids; ///< lattices of sensors of `sensors` (issue #30)
    std::optional<Camera> camera;
    std::vector<NamedCamera> cameras; ///< besides `camera`; names unique
    MesherSettings mesher;
    SolverSettings solver;
    RenderSettings render;
    std::optional<LightmapSettings> lightmap; ///< set: `bake` writes lightmaps
    AnnualSettings annual;
    std::optional<ProbeSettings> probes; ///< set: `lightmap` and `bake` write light probes
    /// Radiance W/(sr·m²) that the renderer's rays see where they leave the scene; it lights
    /// nothing (the solver does not see it: give a `sky` for light from all around).
    Rgb background;

    BBox bounds() const;
    /// Some polygon emits, or a point light, the sun or the sky has a non-zero intensity.
    bool has_emitter() const;
    /// \brief Makes the camera of `cameras` named \p camera_name the scene's `camera`.
    /// \throws InputError (one line, listing the names) when no camera has that name.
    void select_camera(const std::string& camera_name);
};

} // namespace penumbra
