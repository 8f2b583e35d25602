#pragma once
// VTK XML output of the radiosity mesh, its solution, sensors, discontinuity segments and the
// passes of a progressive solve, for ParaView and `penumbra view`. Every file is written
// atomically (temporary name, then rename). Each file's field data holds an array "units" of
// "name=unit" strings for the arrays that have a unit.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "core/scene.h"

namespace penumbra::viewer {

/// \brief Writes \p path (.vtu, VTK XML unstructured grid, binary appended, zlib) atomically.
///        Cell data: radiosity, irradiance_direct, irradiance_indirect, irradiance_total (RGB,
///        W/m²), illuminance_lx, luminance_cd_m2, reflectance, emission (RGB, W/m²), level,
///        surface_id, patch_id, material_id, polygon_id, back_side. Point data: the
///        radiometric and photometric values of the vertex solution, and surface_id. Field
///        data: scene_name, units and, when the scene has a camera, camera_eye,
///        camera_look_at, camera_up (metres), camera_fov_deg, camera_fov_axis_x and
///        camera_image_size (the preset `penumbra view` starts from).
/// \throws ExternalError if VTK cannot write the file; InternalError if the arrays of
///         \p mesh and \p solution disagree.
void write_vtu(const std::string& path, const Scene& scene, const RadiosityMesh& mesh,
               const Solution& solution);

/// \brief One array of cell data on a mesh: a value per element, and its unit ("" for none).
struct CellArray {
    std::string name;
    std::string unit;
    std::vector<double> values;
};

/// \brief Writes \p mesh as write_vtu() does, with the cell data \p arrays (as floats) first,
///        then the element arrays (level, surface_id, patch_id, material_id, polygon_id,
///        back_side, reflectance, emission); no solution arrays.
/// \throws ExternalError if VTK cannot write the file; InternalError for an array whose size
///         is not the mesh's element count.
void write_cell_arrays_vtu(const std::string& path, const Scene& scene, const RadiosityMesh& mesh,
                           const std::vector<CellArray>& arrays);

/// \brief Writes the sensors as a VTK XML poly data file (.vtp) of vertices: points, normals
///        and point data irradiance_direct, irradiance_total (RGB, W/m²),
///        illuminance_direct_lx, illuminance_total_lx and name. \p readings[i] belongs to
///        scene.sensors[i].
void write_sensors_vtp(const std::string& path, const Scene& scene,
                       const std::vector<SensorReading>& readings);

/// \brief Writes one sensor grid of \p scene as a .vtp: its present lattice points as
///        vertices and the quads between four present neighbours (a surface in ParaView), with
///        point data illuminance_direct_lx, illuminance_total_lx, row, column and, when
///        \p daylight_reference_lx is given, daylight_factor_pct = 100 × E_total / it.
///        \p readings[i] belongs to scene.sensors[i].
void write_grid_vtp(const std::string& path, const Scene& scene, const SensorGrid& grid,
                    const std::vector<SensorReading>& readings,
                    std::optional<double> daylight_reference_lx);

/// \brief One array of point data of a grid's .vtp: a value per present lattice point, in
///        lattice order (row-major), and its unit ("" for none).
struct GridPointArray {
    std::string name;
    std::string unit;
    std::vector<double> values;
};

/// \brief Writes one sensor grid of \p scene as a .vtp, as write_grid_vtp() does, with the
///        point data \p arrays (doubles) and row, column.
/// \throws InternalError for an array whose size is not the grid's count of present points.
void write_grid_arrays_vtp(const std::string& path, const Scene& scene, const SensorGrid& grid,
                           const std::vector<GridPointArray>& arrays);

/// \brief An array of point data with \p components values per point (point-major), and
///        its unit ("" for none).
struct PointArray {
    std::string name;
    std::string unit;
    int components = 1;
    std::vector<double> values;
};

/// \brief Writes \p points as a .vtp of vertices with the point data \p arrays (light
///        probes, issue #29). \throws InternalError for an array of the wrong size.
void write_points_vtp(const std::string& path, const std::vector<Vec3>& points,
                      const std::vector<PointArray>& arrays);

/// \brief Writes the discontinuity segments of \p mesh as a .vtp of lines with cell data
///        order, source and surface (see DiscontinuitySegment). source is the emitting
///        polygon's index for an area source, −1 for the sun and −2 − i for point light i.
void write_discontinuities_vtp(const std::string& path, const RadiosityMesh& mesh);

/// \brief One step of a .pvd collection: a time value and a file relative to the .pvd.
struct PvdStep {
    double timestep = 0;
    std::string file;
};

/// \brief Writes a ParaView data collection (.pvd) listing \p steps in order.
void write_pvd(const std::string& path, const std::vector<PvdStep>& steps);

/// \brief Writes the passes of a solve as `DIR/series/mesh_<shots>.vtu` plus `DIR/series.pvd`
///        (timestep = shots, or sweeps for gathering solvers). Each add() writes its file at
///        once and rewrites the .pvd, so an interrupted solve leaves a readable series;
///        snapshots are not kept in memory. Construction removes the files of an earlier
///        series in DIR. Keeps a reference to \p scene, which must outlive it. Not thread-safe.
class SeriesWriter {
public:
    SeriesWriter(std::string dir, const Scene& scene);
    /// \brief Writes \p snapshot on \p mesh as the step at \p shots. A step at the same shot
    ///        count as the previous one (the final solution right after a snapshot, or on a
    ///        refined mesh) replaces it.
    void add(const RadiosityMesh& mesh, const Solution& snapshot, std::int64_t shots);
    std::size_t step_count() const { return steps_.size(); }
    /// The shot count of the last step, -1 before the first.
    std::int64_t last_shots() const;

private:
    std::string dir_;
    const Scene& scene_;
    std::vector<PvdStep> steps_;
};

/// \brief Removes `DIR/series.pvd` and the `DIR/series/mesh_*.vtu` files (and the folder if
///        then empty), so that a folder's outputs never mix two bakes. Returns true if
///        anything was removed.
bool remove_series(const std::string& dir);

} // namespace penumbra::viewer
