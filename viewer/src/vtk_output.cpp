// VTK XML unstructured grid (.vtu) of the radiosity mesh and its solution, for ParaView.
// Cells are the mesh elements (one VTK_TRIANGLE each), points the mesh vertices. Photometric
// arrays go through the project's one conversion, to_photometric (core/rgb.h). A solution
// whose arrays are all empty (a mesh written before solving) gives the geometry arrays only.

#include "viewer/vtk_output.h"

#include "core/error.h"
#include "core/files.h"

#include "vtk_util.h"

#include <fmt/format.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace penumbra::viewer {

namespace {

float illuminance_lx(const Rgb& irradiance) {
    return float(to_photometric(irradiance));
}
float luminance_cd_m2(const Rgb& radiosity) {
    return float(to_photometric(radiosity) / k_pi);
}

void check_mesh(const RadiosityMesh& mesh) {
    bool ok = mesh.vertex_patch.size() == mesh.vertex_count() &&
              mesh.element_patch.size() == mesh.element_count();
    for (std::uint32_t p : mesh.vertex_patch)
        ok = ok && p < mesh.patches.size();
    for (std::uint32_t p : mesh.element_patch)
        ok = ok && p < mesh.patches.size();
    for (const auto& t : mesh.triangles)
        ok = ok && t[0] < mesh.vertex_count() && t[1] < mesh.vertex_count() &&
             t[2] < mesh.vertex_count();
    ok = ok && (mesh.element_level.empty() || mesh.element_level.size() == mesh.element_count());
    if (!ok)
        throw InternalError("write_vtu: the mesh's vertex, element and patch arrays disagree");
}

/// True if the solution has values to write; throws if they do not match the mesh.
bool check_solution(const RadiosityMesh& mesh, const Solution& s) {
    const std::vector<Rgb>* cell[] = {&s.radiosity, &s.irradiance_direct, &s.irradiance_indirect};
    const std::vector<Rgb>* point[] = {&s.vertex_radiosity, &s.vertex_irradiance_direct,
                                       &s.vertex_irradiance_indirect};
    bool all_empty = true, all_match = true;
    for (const auto* a : cell) {
        all_empty = all_empty && a->empty();
        all_match = all_match && a->size() == mesh.element_count();
    }
    for (const auto* a : point) {
        all_empty = all_empty && a->empty();
        all_match = all_match && a->size() == mesh.vertex_count();
    }
    if (!all_empty && !all_match)
        throw InternalError(fmt::format("write_vtu: solution arrays do not match the mesh of {} "
                                        "elements and {} vertices",
                                        mesh.element_count(), mesh.vertex_count()));
    return !all_empty;
}

void add_cell_patch_arrays(vtkCellData* data, const RadiosityMesh& mesh) {
    const std::size_t n = mesh.element_count();
    add_rgb(data, "emission", n, [&](std::size_t e) { return mesh.patch_of(e).emission; });
    add_rgb(data, "reflectance", n, [&](std::size_t e) { return mesh.patch_of(e).reflectance; });
    // An empty element_level means a flat mesh: every element is a level-0 mesh triangle.
    add_scalar<vtkIntArray>(data, "level", n, [&](std::size_t e) {
        return mesh.element_level.empty() ? 0 : int(mesh.element_level[e]);
    });
    add_scalar<vtkIntArray>(data, "surface_id", n,
                            [&](std::size_t e) { return int(mesh.patch_of(e).surface); });
    add_scalar<vtkIntArray>(data, "patch_id", n,
                            [&](std::size_t e) { return int(mesh.element_patch[e]); });
    add_scalar<vtkIntArray>(data, "material_id", n,
                            [&](std::size_t e) { return int(mesh.patch_of(e).material); });
    add_scalar<vtkIntArray>(data, "polygon_id", n,
                            [&](std::size_t e) { return int(mesh.patch_of(e).polygon); });
    add_scalar<vtkIntArray>(data, "back_side", n,
                            [&](std::size_t e) { return mesh.patch_of(e).back ? 1 : 0; });
}

void add_cell_solution_arrays(vtkCellData* data, const Solution& s, std::size_t n) {
    auto total = [&](std::size_t e) { return s.irradiance_direct[e] + s.irradiance_indirect[e]; };
    add_rgb(data, "radiosity", n, [&](std::size_t e) { return s.radiosity[e]; });
    add_rgb(data, "irradiance_direct", n, [&](std::size_t e) { return s.irradiance_direct[e]; });
    add_rgb(data, "irradiance_indirect", n,
            [&](std::size_t e) { return s.irradiance_indirect[e]; });
    add_rgb(data, "irradiance_total", n, total);
    add_scalar<vtkFloatArray>(data, "illuminance_lx", n,
                              [&](std::size_t e) { return illuminance_lx(total(e)); });
    add_scalar<vtkFloatArray>(data, "luminance_cd_m2", n,
                              [&](std::size_t e) { return luminance_cd_m2(s.radiosity[e]); });
}

void add_point_solution_arrays(vtkPointData* data, const Solution& s, std::size_t n) {
    add_rgb(data, "radiosity", n, [&](std::size_t v) { return s.vertex_radiosity[v]; });
    add_rgb(data, "irradiance_direct", n,
            [&](std::size_t v) { return s.vertex_irradiance_direct[v]; });
    add_rgb(data, "irradiance_indirect", n,
            [&](std::size_t v) { return s.vertex_irradiance_indirect[v]; });
    add_scalar<vtkFloatArray>(data, "illuminance_lx", n, [&](std::size_t v) {
        return illuminance_lx(s.vertex_irradiance_direct[v] + s.vertex_irradiance_indirect[v]);
    });
    add_scalar<vtkFloatArray>(data, "luminance_cd_m2", n, [&](std::size_t v) {
        return luminance_cd_m2(s.vertex_radiosity[v]);
    });
}

void set_geometry(vtkUnstructuredGrid* grid, const RadiosityMesh& mesh) {
    vtkNew<vtkPoints> points;
    points->SetDataTypeToFloat();
    points->SetNumberOfPoints(vtkIdType(mesh.vertex_count()));
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        const Vec3f& p = mesh.positions[v];
        points->SetPoint(vtkIdType(v), p.x, p.y, p.z);
    }
    vtkNew<vtkIdTypeArray> connectivity;
    connectivity->SetNumberOfValues(vtkIdType(3 * mesh.element_count()));
    for (std::size_t e = 0; e < mesh.element_count(); ++e)
        for (std::size_t k = 0; k < 3; ++k)
            connectivity->SetValue(vtkIdType(3 * e + k), vtkIdType(mesh.triangles[e][k]));
    vtkNew<vtkCellArray> cells;
    cells->SetData(3, connectivity);
    grid->SetPoints(points);
    grid->SetCells(VTK_TRIANGLE, cells);
}

void add_vector_field(vtkFieldData* data, const char* name, const Vec3& v) {
    vtkNew<vtkDoubleArray> array;
    array->SetName(name);
    array->SetNumberOfComponents(3);
    array->InsertNextTuple3(v.x, v.y, v.z);
    data->AddArray(array);
}

template <typename Array, typename... Values>
void add_field(vtkFieldData* data, const char* name, Values... values) {
    vtkNew<Array> array;
    array->SetName(name);
    (array->InsertNextValue(values), ...);
    data->AddArray(array);
}

/// The scene camera as field data, the preset `penumbra view` starts from.
void add_camera(vtkFieldData* data, const Camera& camera) {
    add_vector_field(data, "camera_eye", camera.eye);
    add_vector_field(data, "camera_look_at", camera.look_at);
    add_vector_field(data, "camera_up", camera.up);
    add_field<vtkDoubleArray>(data, "camera_fov_deg", camera.fov_deg);
    add_field<vtkIntArray>(data, "camera_fov_axis_x", camera.fov_axis_x ? 1 : 0);
    add_field<vtkIntArray>(data, "camera_image_size", camera.width, camera.height);
}

} // namespace

void write_vtu(const std::string& path, const Scene& scene, const RadiosityMesh& mesh,
               const Solution& solution) {
    check_mesh(mesh);
    const bool has_solution = check_solution(mesh, solution);
    vtkNew<vtkUnstructuredGrid> grid;
    set_geometry(grid, mesh);
    // Solution arrays first: viewers list arrays in file order.
    if (has_solution) {
        add_cell_solution_arrays(grid->GetCellData(), solution, mesh.element_count());
        add_point_solution_arrays(grid->GetPointData(), solution, mesh.vertex_count());
    }
    add_cell_patch_arrays(grid->GetCellData(), mesh);
    add_scalar<vtkIntArray>(
        grid->GetPointData(), "surface_id", mesh.vertex_count(),
        [&](std::size_t v) { return int(mesh.patches[mesh.vertex_patch[v]].surface); });
    add_field<vtkStringArray>(grid->GetFieldData(), "scene_name", scene.name);
    if (scene.camera)
        add_camera(grid->GetFieldData(), *scene.camera);
    add_units(grid, {{"radiosity", "W/m²"},
                     {"irradiance_direct", "W/m²"},
                     {"irradiance_indirect", "W/m²"},
                     {"irradiance_total", "W/m²"},
                     {"emission", "W/m²"},
                     {"reflectance", "1"},
                     {"illuminance_lx", "lx"},
                     {"luminance_cd_m2", "cd/m²"}});

    write_xml_file<vtkXMLUnstructuredGridWriter>(grid, path);
}

void write_cell_arrays_vtu(const std::string& path, const Scene& scene, const RadiosityMesh& mesh,
                           const std::vector<CellArray>& arrays) {
    check_mesh(mesh);
    vtkNew<vtkUnstructuredGrid> grid;
    set_geometry(grid, mesh);
    std::vector<std::pair<std::string, std::string>> units{{"reflectance", "1"},
                                                           {"emission", "W/m²"}};
    for (const CellArray& a : arrays) {
        if (a.values.size() != mesh.element_count())
            throw InternalError(fmt::format("write_cell_arrays_vtu: '{}' has {} values for {} "
                                            "elements",
                                            a.name, a.values.size(), mesh.element_count()));
        add_scalar<vtkFloatArray>(grid->GetCellData(), a.name.c_str(), a.values.size(),
                                  [&](std::size_t e) { return float(a.values[e]); });
        if (!a.unit.empty())
            units.emplace_back(a.name, a.unit);
    }
    add_cell_patch_arrays(grid->GetCellData(), mesh);
    add_field<vtkStringArray>(grid->GetFieldData(), "scene_name", scene.name);
    add_units(grid, units);
    write_xml_file<vtkXMLUnstructuredGridWriter>(grid, path);
}

} // namespace penumbra::viewer
