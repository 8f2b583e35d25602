// write_vtu: a hand-made mesh and solution written, read back with VTK's own reader.

#include "viewer/vtk_output.h"

#include "common/test_util.h"
#include "core/error.h"
#include "core/files.h"

#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

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
    EXPECT_EQ(cells->GetNumberOfArrays(), 13);
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

} // namespace
} // namespace penumbra::viewer
