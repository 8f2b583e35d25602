// write_vtu: a hand-made mesh and solution written, read back with VTK's own reader.

#include "viewer/vtk_output.h"

#include "common/test_util.h"
#include "core/error.h"
#include "core/files.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace penumbra::viewer {
namespace {

namespace fs = std::filesystem;

/// A two-sided unit square (2 front + 2 back elements) and a one-sided triangle.
RadiosityMesh test_mesh() {
    RadiosityMesh m;
    auto add_patch = [&](std::uint32_t polygon, std::uint32_t material, bool back, Vec3 normal) {
        Patch p;
        p.polygon = polygon;
        p.surface = polygon + 10;
        p.material = material;
        p.back = back;
        p.normal = normal;
        p.reflectance = Rgb(0.1f * float(polygon + 1), 0.5f, 0.7f);
        p.emission = back ? Rgb() : Rgb(float(polygon) * 3.0f, 1.5f, 0.25f);
        m.patches.push_back(p);
    };
    add_patch(0, 0, false, Vec3(0, 0, 1));
    add_patch(0, 0, true, Vec3(0, 0, -1));
    add_patch(1, 2, false, Vec3(1, 0, 0));
    const Vec3f square[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    for (std::uint32_t side = 0; side < 2; ++side)
        for (const Vec3f& p : square) {
            m.positions.push_back(p);
            m.vertex_patch.push_back(side);
        }
    for (const Vec3f& p : {Vec3f(2, 0, 0), Vec3f(2, 1, 0), Vec3f(2, 0, 1)}) {
        m.positions.push_back(p);
        m.vertex_patch.push_back(2);
    }
    m.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 6, 5}, {4, 7, 6}, {8, 9, 10}};
    m.element_patch = {0, 0, 1, 1, 2};
    m.element_twin = {2, 3, 0, 1, -1};
    m.element_area = {0.5, 0.5, 0.5, 0.5, 0.5};
    m.geometry_elements = {0, 1, 4};
    return m;
}

Solution test_solution(const RadiosityMesh& m) {
    Solution s;
    auto value = [](std::size_t i, float scale) {
        return Rgb(scale * float(i + 1), scale * float(i) + 0.5f, scale / float(i + 1));
    };
    for (std::size_t e = 0; e < m.element_count(); ++e) {
        s.radiosity.push_back(value(e, 1.0f));
        s.irradiance_direct.push_back(value(e, 2.0f));
        s.irradiance_indirect.push_back(value(e, 0.25f));
    }
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
        s.vertex_radiosity.push_back(value(v, 1.5f));
        s.vertex_irradiance_direct.push_back(value(v, 3.0f));
        s.vertex_irradiance_indirect.push_back(value(v, 0.125f));
    }
    return s;
}

vtkSmartPointer<vtkUnstructuredGrid> read_vtu(const std::string& path) {
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    return vtkSmartPointer<vtkUnstructuredGrid>(reader->GetOutput());
}

void expect_rgb_array(vtkDataSetAttributes* data, const char* name,
                      const std::vector<Rgb>& values) {
    vtkDataArray* array = data->GetArray(name);
    ASSERT_NE(array, nullptr) << name;
    EXPECT_EQ(array->GetDataType(), VTK_FLOAT) << name;
    ASSERT_EQ(array->GetNumberOfComponents(), 3) << name;
    ASSERT_EQ(array->GetNumberOfTuples(), vtkIdType(values.size())) << name;
    for (std::size_t i = 0; i < values.size(); ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(float(array->GetComponent(vtkIdType(i), c)), values[i][c]) << name << i;
}

template <typename T>
void expect_scalar_array(vtkDataSetAttributes* data, const char* name, int type,
                         const std::vector<T>& values) {
    vtkDataArray* array = data->GetArray(name);
    ASSERT_NE(array, nullptr) << name;
    EXPECT_EQ(array->GetDataType(), type) << name;
    ASSERT_EQ(array->GetNumberOfComponents(), 1) << name;
    ASSERT_EQ(array->GetNumberOfTuples(), vtkIdType(values.size())) << name;
    for (std::size_t i = 0; i < values.size(); ++i)
        EXPECT_EQ(T(array->GetComponent(vtkIdType(i), 0)), values[i]) << name << i;
}

template <typename Fn> auto per_index(std::size_t n, Fn&& fn) {
    std::vector<decltype(fn(std::size_t(0)))> out;
    for (std::size_t i = 0; i < n; ++i)
        out.push_back(fn(i));
    return out;
}

TEST(WriteVtu, GeometryRoundTrips) {
    const RadiosityMesh mesh = test_mesh();
    const std::string dir = test::temp_dir("vtu");
    const std::string path = dir + "/mesh.vtu";
    Scene scene;
    scene.name = "two patches";
    write_vtu(path, scene, mesh, test_solution(mesh));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);

    auto grid = read_vtu(path);
    ASSERT_EQ(grid->GetNumberOfPoints(), vtkIdType(mesh.vertex_count()));
    ASSERT_EQ(grid->GetNumberOfCells(), vtkIdType(mesh.element_count()));
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        double p[3];
        grid->GetPoint(vtkIdType(v), p);
        EXPECT_EQ(Vec3f(float(p[0]), float(p[1]), float(p[2])), mesh.positions[v]);
    }
    vtkNew<vtkIdList> ids;
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
        EXPECT_EQ(grid->GetCellType(vtkIdType(e)), VTK_TRIANGLE);
        grid->GetCellPoints(vtkIdType(e), ids);
        ASSERT_EQ(ids->GetNumberOfIds(), 3);
        for (int k = 0; k < 3; ++k)
            EXPECT_EQ(ids->GetId(k), vtkIdType(mesh.triangles[e][std::size_t(k)]));
    }
    auto* name = vtkStringArray::SafeDownCast(grid->GetFieldData()->GetAbstractArray("scene_name"));
    ASSERT_NE(name, nullptr);
    ASSERT_EQ(name->GetNumberOfValues(), 1);
    EXPECT_EQ(name->GetValue(0), "two patches");

    const std::string text = read_text_file(path);
    EXPECT_NE(text.find("format=\"appended\""), std::string::npos);
    EXPECT_NE(text.find("encoding=\"raw\""), std::string::npos);
    EXPECT_NE(text.find("vtkZLibDataCompressor"), std::string::npos);
}

TEST(WriteVtu, CellArraysRoundTrip) {
    const RadiosityMesh mesh = test_mesh();
    const Solution s = test_solution(mesh);
    const std::string path = test::temp_dir("vtu") + "/mesh.vtu";
    write_vtu(path, Scene(), mesh, s);
    auto grid = read_vtu(path);
    vtkCellData* cells = grid->GetCellData();
    const std::size_t n = mesh.element_count();
    auto total =
        per_index(n, [&](auto e) { return s.irradiance_direct[e] + s.irradiance_indirect[e]; });

    expect_rgb_array(cells, "radiosity", s.radiosity);
    expect_rgb_array(cells, "irradiance_direct", s.irradiance_direct);
    expect_rgb_array(cells, "irradiance_indirect", s.irradiance_indirect);
    expect_rgb_array(cells, "irradiance_total", total);
    expect_rgb_array(cells, "emission",
                     per_index(n, [&](auto e) { return mesh.patch_of(e).emission; }));
    expect_rgb_array(cells, "reflectance",
                     per_index(n, [&](auto e) { return mesh.patch_of(e).reflectance; }));
    expect_scalar_array(cells, "illuminance_lx", VTK_FLOAT,
                        per_index(n, [&](auto e) { return float(to_photometric(total[e])); }));
    expect_scalar_array(cells, "luminance_cd_m2", VTK_FLOAT, per_index(n, [&](auto e) {
                            return float(to_photometric(s.radiosity[e]) / k_pi);
                        }));
    expect_scalar_array(cells, "surface_id", VTK_INT, std::vector<int>{10, 10, 10, 10, 11});
    expect_scalar_array(cells, "patch_id", VTK_INT, std::vector<int>{0, 0, 1, 1, 2});
    expect_scalar_array(cells, "material_id", VTK_INT, std::vector<int>{0, 0, 0, 0, 2});
    expect_scalar_array(cells, "polygon_id", VTK_INT, std::vector<int>{0, 0, 0, 0, 1});
    expect_scalar_array(cells, "back_side", VTK_INT, std::vector<int>{0, 0, 1, 1, 0});
    expect_scalar_array(cells, "level", VTK_INT, std::vector<int>{0, 0, 0, 0, 0});
    EXPECT_EQ(cells->GetNumberOfArrays(), 14);
}

TEST(WriteVtu, PointArraysRoundTrip) {
    const RadiosityMesh mesh = test_mesh();
    const Solution s = test_solution(mesh);
    const std::string path = test::temp_dir("vtu") + "/mesh.vtu";
    write_vtu(path, Scene(), mesh, s);
    auto grid = read_vtu(path);
    vtkPointData* points = grid->GetPointData();
    const std::size_t n = mesh.vertex_count();

    expect_rgb_array(points, "radiosity", s.vertex_radiosity);
    expect_rgb_array(points, "irradiance_direct", s.vertex_irradiance_direct);
    expect_rgb_array(points, "irradiance_indirect", s.vertex_irradiance_indirect);
    expect_scalar_array(points, "illuminance_lx", VTK_FLOAT, per_index(n, [&](auto v) {
                            return float(to_photometric(s.vertex_irradiance_direct[v] +
                                                        s.vertex_irradiance_indirect[v]));
                        }));
    expect_scalar_array(points, "luminance_cd_m2", VTK_FLOAT, per_index(n, [&](auto v) {
                            return float(to_photometric(s.vertex_radiosity[v]) / k_pi);
                        }));
    expect_scalar_array(points, "surface_id", VTK_INT,
                        std::vector<int>{10, 10, 10, 10, 10, 10, 10, 10, 11, 11, 11});
    EXPECT_EQ(points->GetNumberOfArrays(), 6);
}

TEST(WriteVtu, IlluminanceMatchesPhotometricDefinition) {
    // 1 W/m² of white light is 179 lx under the project's photometric convention.
    RadiosityMesh mesh = test_mesh();
    Solution s = test_solution(mesh);
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
        s.irradiance_direct[e] = Rgb(0.75f);
        s.irradiance_indirect[e] = Rgb(0.25f);
    }
    const std::string path = test::temp_dir("vtu") + "/mesh.vtu";
    write_vtu(path, Scene(), mesh, s);
    auto grid = read_vtu(path);
    vtkDataArray* lx = grid->GetCellData()->GetArray("illuminance_lx");
    ASSERT_NE(lx, nullptr);
    for (vtkIdType e = 0; e < lx->GetNumberOfTuples(); ++e)
        EXPECT_NEAR(lx->GetComponent(e, 0), k_luminous_efficacy_lm_per_w, 1e-3);
}

TEST(WriteVtu, MeshWithoutSolutionHasGeometryArraysOnly) {
    const RadiosityMesh mesh = test_mesh();
    const std::string path = test::temp_dir("vtu") + "/mesh.vtu";
    write_vtu(path, Scene(), mesh, Solution());
    auto grid = read_vtu(path);
    EXPECT_EQ(grid->GetNumberOfCells(), vtkIdType(mesh.element_count()));
    EXPECT_NE(grid->GetCellData()->GetArray("patch_id"), nullptr);
    EXPECT_EQ(grid->GetCellData()->GetArray("radiosity"), nullptr);
    EXPECT_NE(grid->GetPointData()->GetArray("surface_id"), nullptr);
}

TEST(WriteVtu, EmptyMesh) {
    const std::string path = test::temp_dir("vtu") + "/mesh.vtu";
    write_vtu(path, Scene(), RadiosityMesh(), Solution());
    auto grid = read_vtu(path);
    EXPECT_EQ(grid->GetNumberOfPoints(), 0);
    EXPECT_EQ(grid->GetNumberOfCells(), 0);
}

TEST(WriteVtu, Errors) {
    const RadiosityMesh mesh = test_mesh();
    Solution s = test_solution(mesh);
    const std::string dir = test::temp_dir("vtu");
    try {
        write_vtu(dir + "/no/such/folder/mesh.vtu", Scene(), mesh, s);
        FAIL() << "no exception";
    } catch (const ExternalError& e) {
        EXPECT_NE(std::string(e.what()).find("mesh.vtu"), std::string::npos) << e.what();
    }
    s.radiosity.pop_back();
    EXPECT_THROW(write_vtu(dir + "/mesh.vtu", Scene(), mesh, s), InternalError);
    EXPECT_FALSE(fs::exists(dir + "/mesh.vtu"));
}

// Issue #32: a full disk gave VTK's pipeline errors; the message now names the file and the
// system's reason (here EFBIG from a file size limit), and nothing is left behind.
TEST(WriteVtu, FailedWriteSaysWhyAndLeavesNothing) {
    const RadiosityMesh mesh = test_mesh();
    const Solution s = test_solution(mesh);
    const std::string dir = test::temp_dir("vtu_efbig");
    const std::string path = dir + "/mesh.vtu";
    const std::string message =
        test::external_error_with_file_limit(300, [&] { write_vtu(path, Scene(), mesh, s); });
    EXPECT_EQ(message, fmt::format("cannot write '{}': {}", path, std::strerror(EFBIG)));
    EXPECT_TRUE(fs::is_empty(dir));
}

TEST(WriteVtu, HierarchyLevel) {
    RadiosityMesh mesh = test_mesh();
    mesh.element_level = {0, 1, 2, 2, 0};
    const std::string path = test::temp_dir("vtu") + "/mesh.vtu";
    write_vtu(path, Scene(), mesh, test_solution(mesh));
    expect_scalar_array(read_vtu(path)->GetCellData(), "level", VTK_INT,
                        std::vector<int>{0, 1, 2, 2, 0});
    mesh.element_level.pop_back();
    EXPECT_THROW(write_vtu(path, Scene(), mesh, test_solution(mesh)), InternalError);
}

std::vector<double> field_values(vtkFieldData* field, const char* name) {
    std::vector<double> out;
    if (vtkDataArray* a = field->GetArray(name))
        for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
            for (int c = 0; c < a->GetNumberOfComponents(); ++c)
                out.push_back(a->GetComponent(i, c));
    return out;
}

std::vector<std::string> string_values(vtkAbstractArray* array) {
    std::vector<std::string> out;
    auto* strings = vtkStringArray::SafeDownCast(array);
    for (vtkIdType i = 0; strings && i < strings->GetNumberOfValues(); ++i)
        out.push_back(strings->GetValue(i));
    return out;
}

TEST(WriteVtu, CameraAndUnitsInFieldData) {
    const RadiosityMesh mesh = test_mesh();
    Scene scene;
    Camera camera;
    camera.eye = Vec3(1, 2, 3);
    camera.look_at = Vec3(1, 2, 0);
    camera.up = Vec3(0, 1, 0);
    camera.fov_deg = 40;
    camera.fov_axis_x = false;
    camera.width = 320;
    camera.height = 200;
    scene.camera = camera;
    const std::string path = test::temp_dir("vtu") + "/mesh.vtu";
    write_vtu(path, scene, mesh, test_solution(mesh));
    auto grid = read_vtu(path);
    vtkFieldData* field = grid->GetFieldData();
    EXPECT_EQ(field_values(field, "camera_eye"), (std::vector<double>{1, 2, 3}));
    EXPECT_EQ(field_values(field, "camera_look_at"), (std::vector<double>{1, 2, 0}));
    EXPECT_EQ(field_values(field, "camera_up"), (std::vector<double>{0, 1, 0}));
    EXPECT_EQ(field_values(field, "camera_fov_deg"), (std::vector<double>{40}));
    EXPECT_EQ(field_values(field, "camera_fov_axis_x"), (std::vector<double>{0}));
    EXPECT_EQ(field_values(field, "camera_image_size"), (std::vector<double>{320, 200}));
    const auto units = string_values(field->GetAbstractArray("units"));
    for (const char* entry : {"illuminance_lx=lx", "luminance_cd_m2=cd/m²", "radiosity=W/m²",
                              "irradiance_total=W/m²", "emission=W/m²", "reflectance=1"})
        EXPECT_NE(std::find(units.begin(), units.end(), entry), units.end()) << entry;

    write_vtu(path, Scene(), mesh, test_solution(mesh)); // no camera: no camera arrays
    EXPECT_EQ(read_vtu(path)->GetFieldData()->GetArray("camera_eye"), nullptr);
}

vtkSmartPointer<vtkPolyData> read_vtp(const std::string& path) {
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    return vtkSmartPointer<vtkPolyData>(reader->GetOutput());
}

TEST(WriteVtp, Sensors) {
    Scene scene;
    scene.sensors = {{"desk", Vec3(1, 2, 0.8), Vec3(0, 0, 1)},
                     {"wall", Vec3(0, 1, 1), Vec3(1, 0, 0)}};
    std::vector<SensorReading> readings(2);
    readings[0] = {Rgb(1, 2, 3), Rgb(2, 3, 4), 100.5, 250.25};
    readings[1] = {Rgb(0.5f), Rgb(0.75f), 10, 20};
    const std::string path = test::temp_dir("vtp") + "/sensors.vtp";
    write_sensors_vtp(path, scene, readings);
    auto data = read_vtp(path);
    ASSERT_EQ(data->GetNumberOfPoints(), 2);
    EXPECT_EQ(data->GetNumberOfVerts(), 2);
    double p[3];
    data->GetPoint(0, p);
    EXPECT_EQ(Vec3(p[0], p[1], p[2]), scene.sensors[0].position);
    vtkPointData* points = data->GetPointData();
    ASSERT_NE(points->GetNormals(), nullptr);
    EXPECT_EQ(points->GetNormals()->GetComponent(1, 0), 1.0);
    expect_rgb_array(points, "irradiance_direct",
                     {readings[0].irradiance_direct, readings[1].irradiance_direct});
    expect_rgb_array(points, "irradiance_total",
                     {readings[0].irradiance_total, readings[1].irradiance_total});
    expect_scalar_array(points, "illuminance_direct_lx", VTK_DOUBLE,
                        std::vector<double>{100.5, 10});
    expect_scalar_array(points, "illuminance_total_lx", VTK_DOUBLE,
                        std::vector<double>{250.25, 20});
    EXPECT_EQ(string_values(points->GetAbstractArray("name")),
              (std::vector<std::string>{"desk", "wall"}));
    EXPECT_THROW(write_sensors_vtp(path, scene, {}), InternalError);
}

TEST(WriteVtp, Discontinuities) {
    RadiosityMesh mesh = test_mesh();
    mesh.discontinuities = {{Vec3(0, 0, 0), Vec3(1, 0, 0), 10, AreaSource{1}, 0},
                            {Vec3(0, 1, 0), Vec3(1, 1, 0), 11, PointSource{0}, 2},
                            {Vec3(0, 2, 0), Vec3(1, 2, 0), 12, PointSource{3}, 2},
                            {Vec3(0, 3, 0), Vec3(1, 3, 0), 13, SunSource{}, 1}};
    const std::string path = test::temp_dir("vtp") + "/discontinuities.vtp";
    write_discontinuities_vtp(path, mesh);
    auto data = read_vtp(path);
    EXPECT_EQ(data->GetNumberOfPoints(), 8);
    ASSERT_EQ(data->GetNumberOfLines(), 4);
    double p[3];
    data->GetPoint(3, p);
    EXPECT_EQ(Vec3(p[0], p[1], p[2]), Vec3(1, 1, 0));
    expect_scalar_array(data->GetCellData(), "order", VTK_INT, std::vector<int>{0, 2, 2, 1});
    // The documented values: the polygon's index, −2 − i for point light i, −1 for the sun.
    expect_scalar_array(data->GetCellData(), "source", VTK_INT, std::vector<int>{1, -2, -5, -1});
    expect_scalar_array(data->GetCellData(), "surface", VTK_INT, std::vector<int>{10, 11, 12, 13});
    mesh.discontinuities = {{Vec3(0, 0, 0), Vec3(1, 0, 0), 10, SkySource{}, 0}};
    EXPECT_THROW(write_discontinuities_vtp(path, mesh), InternalError); // the sky casts none
}

// A 2 × 3 grid missing point (1, 2): 5 vertices, one quad (the only four present
// neighbours), values by point and the daylight factor against a 2 000 lx reference.
TEST(WriteVtp, GridPointsAndQuads) {
    Scene scene;
    SensorGrid grid;
    grid.name = "g";
    grid.rows = 2;
    grid.columns = 3;
    grid.spacing_m = 0.5;
    std::vector<SensorReading> readings;
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 3; ++c) {
            if (r == 1 && c == 2) {
                grid.sensors.emplace_back();
                continue;
            }
            grid.sensors.emplace_back(std::uint32_t(scene.sensors.size()));
            scene.sensors.push_back({"", Vec3(0.5 * c, 0.5 * r, 0.8), Vec3(0, 0, 1)});
            const double lx = 100.0 * double(scene.sensors.size());
            readings.push_back({Rgb(), Rgb(), lx / 2, lx});
        }
    const std::string path = test::temp_dir("vtp") + "/grid_g.vtp";
    write_grid_vtp(path, scene, grid, readings, 2000.0);
    auto data = read_vtp(path);
    ASSERT_EQ(data->GetNumberOfPoints(), 5);
    EXPECT_EQ(data->GetNumberOfVerts(), 5);
    ASSERT_EQ(data->GetNumberOfPolys(), 1);
    double p[3];
    data->GetPoint(4, p);
    EXPECT_EQ(Vec3(p[0], p[1], p[2]), Vec3(0.5, 0.5, 0.8));
    vtkPointData* points = data->GetPointData();
    expect_scalar_array(points, "illuminance_total_lx", VTK_DOUBLE,
                        std::vector<double>{100, 200, 300, 400, 500});
    expect_scalar_array(points, "illuminance_direct_lx", VTK_DOUBLE,
                        std::vector<double>{50, 100, 150, 200, 250});
    expect_scalar_array(points, "daylight_factor_pct", VTK_DOUBLE,
                        std::vector<double>{5, 10, 15, 20, 25});
    expect_scalar_array(points, "row", VTK_INT, std::vector<int>{0, 0, 0, 1, 1});
    expect_scalar_array(points, "column", VTK_INT, std::vector<int>{0, 1, 2, 0, 1});
    write_grid_vtp(path, scene, grid, readings, std::nullopt);
    EXPECT_EQ(read_vtp(path)->GetPointData()->GetArray("daylight_factor_pct"), nullptr);
    EXPECT_THROW(write_grid_vtp(path, scene, grid, {}, std::nullopt), InternalError);
}

TEST(WritePvd, SeriesStepsAndReplacement) {
    const RadiosityMesh mesh = test_mesh();
    const std::string dir = test::temp_dir("series");
    write_text_file(dir + "/series.pvd", "stale");
    fs::create_directories(dir + "/series");
    write_text_file(dir + "/series/mesh_00000999.vtu", "stale");
    write_text_file(dir + "/series/notes.txt", "not ours");
    {
        const Scene scene;
        SeriesWriter series(dir, scene);
        EXPECT_FALSE(fs::exists(dir + "/series/mesh_00000999.vtu"));
        EXPECT_TRUE(fs::exists(dir + "/series/notes.txt"));
        Solution s = test_solution(mesh);
        series.add(mesh, s, 10);
        series.add(mesh, s, 20);
        s.radiosity[0] = Rgb(42.0f);
        series.add(mesh, s, 20); // the final solution at the same count replaces the step
        EXPECT_EQ(series.step_count(), 2u);
        EXPECT_EQ(series.last_shots(), 20);
    }
    const std::string pvd = read_text_file(dir + "/series.pvd");
    EXPECT_NE(pvd.find("type=\"Collection\""), std::string::npos) << pvd;
    EXPECT_NE(pvd.find("timestep=\"10\" group=\"\" part=\"0\" file=\"series/mesh_00000010.vtu\""),
              std::string::npos)
        << pvd;
    EXPECT_NE(pvd.find("timestep=\"20\" group=\"\" part=\"0\" file=\"series/mesh_00000020.vtu\""),
              std::string::npos)
        << pvd;
    EXPECT_EQ(read_vtu(dir + "/series/mesh_00000020.vtu")
                  ->GetCellData()
                  ->GetArray("radiosity")
                  ->GetComponent(0, 0),
              42.0);

    EXPECT_TRUE(remove_series(dir));
    EXPECT_FALSE(fs::exists(dir + "/series.pvd"));
    EXPECT_FALSE(fs::exists(dir + "/series/mesh_00000010.vtu"));
    EXPECT_TRUE(fs::exists(dir + "/series/notes.txt"));
    EXPECT_FALSE(remove_series(dir));
}

} // namespace
} // namespace penumbra::viewer
