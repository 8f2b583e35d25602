// A sensor grid as VTK XML poly data (.vtp) beside mesh.vtu: its points as vertices and the
// quads between four present neighbours, so that ParaView shows the grid's values as a surface.

#include "viewer/vtk_output.h"

#include "core/error.h"
#include "core/files.h"

#include "vtk_util.h"

#include <fmt/format.h>
#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace penumbra::viewer {

namespace {

/// The grid's present lattice points, row-major: their sensor indices and (row, column).
struct GridPoints {
    std::vector<std::uint32_t> sensor;
    std::vector<int> row, column;
    std::vector<std::optional<vtkIdType>> id_at; ///< rows × columns: the VTK point ids
};

GridPoints present_points(const SensorGrid& grid) {
    GridPoints points;
    for (int r = 0; r < grid.rows; ++r)
        for (int c = 0; c < grid.columns; ++c) {
            const auto sensor = grid.sensor_at(r, c);
            points.id_at.push_back(sensor ? std::optional(vtkIdType(points.sensor.size()))
                                          : std::nullopt);
            if (!sensor)
                continue;
            points.sensor.push_back(*sensor);
            points.row.push_back(r);
            points.column.push_back(c);
        }
    return points;
}

/// The quads (counter-clockwise seen from the sensors' side) whose four corners are present.
vtkNew<vtkCellArray> grid_quads(const SensorGrid& grid, const GridPoints& points) {
    vtkNew<vtkCellArray> quads;
    const auto id = [&](int r, int c) {
        return points.id_at[std::size_t(r) * std::size_t(grid.columns) + std::size_t(c)];
    };
    for (int r = 0; r + 1 < grid.rows; ++r)
        for (int c = 0; c + 1 < grid.columns; ++c) {
            const std::array corners{id(r, c), id(r, c + 1), id(r + 1, c + 1), id(r + 1, c)};
            if (corners[0] && corners[1] && corners[2] && corners[3]) {
                const std::array<vtkIdType, 4> ids{*corners[0], *corners[1], *corners[2],
                                                   *corners[3]};
                quads->InsertNextCell(4, ids.data());
            }
        }
    return quads;
}

} // namespace

void write_grid_arrays_vtp(const std::string& path, const Scene& scene, const SensorGrid& grid,
                           const std::vector<GridPointArray>& arrays) {
    const GridPoints points = present_points(grid);
    const std::size_t n = points.sensor.size();
    vtkNew<vtkPoints> xyz;
    xyz->SetDataTypeToDouble();
    vtkNew<vtkCellArray> vertices;
    for (std::uint32_t s : points.sensor) {
        const Vec3& p = scene.sensors[s].position;
        const vtkIdType id = xyz->InsertNextPoint(p.x, p.y, p.z);
        vertices->InsertNextCell(1, &id);
    }
    vtkNew<vtkPolyData> data;
    data->SetPoints(xyz);
    data->SetVerts(vertices);
    data->SetPolys(grid_quads(grid, points));
    vtkPointData* pd = data->GetPointData();
    std::vector<std::pair<std::string, std::string>> units;
    for (const GridPointArray& array : arrays) {
        if (array.values.size() != n)
            throw InternalError(fmt::format("write_grid_arrays_vtp: {} values of {} for {} points",
                                            array.values.size(), array.name, n));
        add_scalar<vtkDoubleArray>(pd, array.name.c_str(), n,
                                   [&](std::size_t i) { return array.values[i]; });
        if (!array.unit.empty())
            units.emplace_back(array.name, array.unit);
    }
    add_scalar<vtkIntArray>(pd, "row", n, [&](std::size_t i) { return points.row[i]; });
    add_scalar<vtkIntArray>(pd, "column", n, [&](std::size_t i) { return points.column[i]; });
    add_units(data, units);
    write_xml_file<vtkXMLPolyDataWriter>(data, path);
}

void write_grid_vtp(const std::string& path, const Scene& scene, const SensorGrid& grid,
                    const std::vector<SensorReading>& readings,
                    std::optional<double> daylight_reference_lx) {
    if (readings.size() != scene.sensors.size())
        throw InternalError(fmt::format("write_grid_vtp: {} readings for {} sensors",
                                        readings.size(), scene.sensors.size()));
    std::vector<GridPointArray> arrays{{"illuminance_direct_lx", "lx", {}},
                                       {"illuminance_total_lx", "lx", {}}};
    for (const auto& sensor : grid.sensors)
        if (sensor) {
            arrays[0].values.push_back(readings[*sensor].illuminance_direct_lx);
            arrays[1].values.push_back(readings[*sensor].illuminance_total_lx);
        }
    if (daylight_reference_lx) {
        GridPointArray df{"daylight_factor_pct", "%", arrays[1].values};
        for (double& value : df.values)
            value *= 100 / *daylight_reference_lx;
        arrays.push_back(std::move(df));
    }
    write_grid_arrays_vtp(path, scene, grid, arrays);
}

} // namespace penumbra::viewer
