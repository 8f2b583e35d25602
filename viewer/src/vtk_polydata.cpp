// VTK XML poly data (.vtp) of the sensors (vertices with normals) and of the discontinuity
// segments (lines), the point and line companions of mesh.vtu.

#include "viewer/vtk_output.h"

#include "core/error.h"
#include "core/files.h"

#include "vtk_util.h"

#include <fmt/format.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cstddef>
#include <string>
#include <variant>
#include <vector>

namespace penumbra::viewer {

namespace {

void write_polydata(const std::string& path, vtkPolyData* data) {
    write_xml_file<vtkXMLPolyDataWriter>(data, path);
}

// The `source` value of a discontinuity segment: the polygon's index for an area source, −1
// for the sun, −2 − i for point light i (the documented values of discontinuities.vtp).
void add_sensor_arrays(vtkPointData* data, const Scene& scene,
                       const std::vector<SensorReading>& readings) {
    const std::size_t n = readings.size();
    add_rgb(data, "irradiance_direct", n,
            [&](std::size_t i) { return readings[i].irradiance_direct; });
    add_rgb(data, "irradiance_total", n,
            [&](std::size_t i) { return readings[i].irradiance_total; });
    add_scalar<vtkDoubleArray>(data, "illuminance_direct_lx", n,
                               [&](std::size_t i) { return readings[i].illuminance_direct_lx; });
    add_scalar<vtkDoubleArray>(data, "illuminance_total_lx", n,
                               [&](std::size_t i) { return readings[i].illuminance_total_lx; });
    vtkNew<vtkStringArray> names;
    names->SetName("name");
    for (const Sensor& s : scene.sensors)
        names->InsertNextValue(s.name);
    data->AddArray(names);
}

} // namespace

void write_sensors_vtp(const std::string& path, const Scene& scene,
                       const std::vector<SensorReading>& readings) {
    if (readings.size() != scene.sensors.size())
        throw InternalError(fmt::format("write_sensors_vtp: {} readings for {} sensors",
                                        readings.size(), scene.sensors.size()));
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    vtkNew<vtkCellArray> vertices;
    vtkNew<vtkDoubleArray> normals;
    normals->SetName("normal");
    normals->SetNumberOfComponents(3);
    for (const Sensor& s : scene.sensors) {
        const vtkIdType id = points->InsertNextPoint(s.position.x, s.position.y, s.position.z);
        vertices->InsertNextCell(1, &id);
        normals->InsertNextTuple3(s.normal.x, s.normal.y, s.normal.z);
    }
    vtkNew<vtkPolyData> data;
    data->SetPoints(points);
    data->SetVerts(vertices);
    data->GetPointData()->SetNormals(normals);
    add_sensor_arrays(data->GetPointData(), scene, readings);
    add_units(data, {{"irradiance_direct", "W/m²"},
                     {"irradiance_total", "W/m²"},
                     {"illuminance_direct_lx", "lx"},
                     {"illuminance_total_lx", "lx"}});
    write_polydata(path, data);
}

void write_points_vtp(const std::string& path, const std::vector<Vec3>& points,
                      const std::vector<PointArray>& arrays) {
    vtkNew<vtkPoints> vtk_points;
    vtk_points->SetDataTypeToDouble();
    vtkNew<vtkCellArray> vertices;
    for (const Vec3& p : points) {
        const vtkIdType id = vtk_points->InsertNextPoint(p.x, p.y, p.z);
        vertices->InsertNextCell(1, &id);
    }
    vtkNew<vtkPolyData> data;
    data->SetPoints(vtk_points);
    data->SetVerts(vertices);
    std::vector<std::pair<std::string, std::string>> units;
    for (const PointArray& a : arrays) {
        if (a.values.size() != points.size() * std::size_t(a.components))
            throw InternalError(fmt::format("write_points_vtp: array '{}' has {} values for {} "
                                            "points of {} components",
                                            a.name, a.values.size(), points.size(), a.components));
        vtkNew<vtkDoubleArray> array;
        array->SetName(a.name.c_str());
        array->SetNumberOfComponents(a.components);
        array->SetNumberOfTuples(vtkIdType(points.size()));
        std::copy(a.values.begin(), a.values.end(), array->GetPointer(0));
        data->GetPointData()->AddArray(array);
        if (!a.unit.empty())
            units.emplace_back(a.name, a.unit);
    }
    add_units(data, units);
    write_polydata(path, data);
}

void write_discontinuities_vtp(const std::string& path, const RadiosityMesh& mesh) {
    const auto& segments = mesh.discontinuities;
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    vtkNew<vtkCellArray> lines;
    for (const DiscontinuitySegment& s : segments) {
        const vtkIdType ids[2] = {points->InsertNextPoint(s.a.x, s.a.y, s.a.z),
                                  points->InsertNextPoint(s.b.x, s.b.y, s.b.z)};
        lines->InsertNextCell(2, ids);
    }
    vtkNew<vtkPolyData> data;
    data->SetPoints(points);
    data->SetLines(lines);
    const std::size_t n = segments.size();
    add_scalar<vtkIntArray>(data->GetCellData(), "order", n,
                            [&](std::size_t i) { return segments[i].order; });
    add_scalar<vtkIntArray>(data->GetCellData(), "source", n,
                            [&](std::size_t i) { return source_code(segments[i].source); });
    add_scalar<vtkIntArray>(data->GetCellData(), "surface", n,
                            [&](std::size_t i) { return int(segments[i].surface); });
    write_polydata(path, data);
}

} // namespace penumbra::viewer
