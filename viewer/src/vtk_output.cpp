// VTK XML unstructured grid (.vtu) of the radiosity mesh and its solution, for ParaView.
// Cells are the mesh elements (one VTK_TRIANGLE each), points the mesh vertices. Photometric
// arrays go through the project's one conversion, to_photometric (core/rgb.h). A solution
// whose arrays are all empty (a mesh written before solving) gives the geometry arrays only.

#include "viewer/vtk_output.h"

#include "core/error.h"
#include "core/files.h"

#include <fmt/format.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkCommand.h>
#include <vtkErrorCode.h>
#include <vtkExecutive.h>
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
#include <vector>

namespace penumbra::viewer {

namespace {

/// Collects the first error a VTK object reports. While an observer is registered, VTK sends
/// the object's errors to it instead of printing them.
class ErrorCapture final : public vtkCommand {
public:
    static ErrorCapture* New() { return new ErrorCapture; }
    void Execute(vtkObject*, unsigned long, void* call_data) override {
        if (message.empty())
            message = call_data ? plain_message(static_cast<const char*>(call_data))
                                : "unknown VTK error";
    }
    std::string message;

private:
    /// VTK's text is "ERROR: In file, line n\nClass (address): message\n\n": keep the message.
    static std::string plain_message(std::string text) {
        if (auto line_end = text.find('\n');
            text.rfind("ERROR: In ", 0) == 0 && line_end != std::string::npos)
            text.erase(0, line_end + 1);
        if (auto colon = text.find("): "); colon != std::string::npos)
            text.erase(0, colon + 3);
        while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
            text.pop_back();
        return text;
    }
};

template <typename Fn>
void add_rgb(vtkDataSetAttributes* data, const char* name, std::size_t count, Fn&& value_of) {
    vtkNew<vtkFloatArray> array;
    array->SetName(name);
    array->SetNumberOfComponents(3);
    array->SetNumberOfTuples(vtkIdType(count));
    float* out = array->GetPointer(0);
    for (std::size_t i = 0; i < count; ++i) {
        const Rgb c = value_of(i);
        out[3 * i + 0] = c.r;
        out[3 * i + 1] = c.g;
        out[3 * i + 2] = c.b;
    }
    data->AddArray(array);
}

template <typename Array, typename Fn>
void add_scalar(vtkDataSetAttributes* data, const char* name, std::size_t count, Fn&& value_of) {
    vtkNew<Array> array;
    array->SetName(name);
    array->SetNumberOfComponents(1);
    array->SetNumberOfTuples(vtkIdType(count));
    for (std::size_t i = 0; i < count; ++i)
        array->SetValue(vtkIdType(i), value_of(i));
    data->AddArray(array);
}

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

void write_grid(vtkUnstructuredGrid* grid, const std::string& temp, const std::string& path) {
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    vtkNew<ErrorCapture> errors;
    // The executive reports the writer's failure again; observe both so nothing is printed.
    writer->AddObserver(vtkCommand::ErrorEvent, errors);
    writer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
    writer->SetFileName(temp.c_str());
    writer->SetInputData(grid);
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff(); // raw binary, not base64
    writer->SetCompressorTypeToZLib();
    writer->SetHeaderTypeToUInt64();
    const bool ok = writer->Write() == 1;
    const unsigned long code = writer->GetErrorCode();
    if (ok && code == vtkErrorCode::NoError && errors->message.empty())
        return;
    std::string reason =
        !errors->message.empty() ? errors->message : vtkErrorCode::GetStringFromErrorCode(code);
    throw ExternalError(fmt::format("cannot write VTK file '{}': {}", path, reason));
}

} // namespace

void write_vtu(const std::string& path, const Scene& scene, const RadiosityMesh& mesh,
               const Solution& solution) {
    check_mesh(mesh);
    const bool has_solution = check_solution(mesh, solution);
    vtkNew<vtkUnstructuredGrid> grid;
    set_geometry(grid, mesh);
    add_cell_patch_arrays(grid->GetCellData(), mesh);
    add_scalar<vtkIntArray>(
        grid->GetPointData(), "surface_id", mesh.vertex_count(),
        [&](std::size_t v) { return int(mesh.patches[mesh.vertex_patch[v]].surface); });
    if (has_solution) {
        add_cell_solution_arrays(grid->GetCellData(), solution, mesh.element_count());
        add_point_solution_arrays(grid->GetPointData(), solution, mesh.vertex_count());
    }
    vtkNew<vtkStringArray> name;
    name->SetName("scene_name");
    name->InsertNextValue(scene.name);
    grid->GetFieldData()->AddArray(name);

    write_atomically(path, [&](const std::string& temp) { write_grid(grid, temp, path); });
}

} // namespace penumbra::viewer
