// The viewer's input: steps, arrays with their ranges over all steps, camera and exposure,
// all read from the files the pipeline writes (viewer/vtk_output.h).

#include "view_data.h"

#include "core/error.h"
#include "core/rgb.h"
#include "core/vec.h"
#include "viewer/view.h"

#include "vtk_util.h"

#include <fmt/format.h>
#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkStringArray.h>
#include <vtkTriangle.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLGenericDataObjectReader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>

namespace penumbra::viewer {

namespace {

namespace fs = std::filesystem;

std::string unit_from_suffix(const std::string& name) {
    auto ends_with = [&](const char* suffix) {
        const std::string s = suffix;
        return name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
    };
    if (ends_with("_lx"))
        return "lx";
    if (ends_with("_cd_m2"))
        return "cd/m²";
    if (ends_with("_w_m2"))
        return "W/m²";
    return {};
}

std::map<std::string, std::string> units_of(vtkDataSet* data) {
    std::map<std::string, std::string> units;
    auto* array = vtkStringArray::SafeDownCast(data->GetFieldData()->GetAbstractArray("units"));
    for (vtkIdType i = 0; array && i < array->GetNumberOfValues(); ++i) {
        const std::string entry = array->GetValue(i);
        if (auto eq = entry.find('='); eq != std::string::npos)
            units[entry.substr(0, eq)] = entry.substr(eq + 1);
    }
    return units;
}

bool field_vector(vtkFieldData* field, const char* name, double out[3]) {
    vtkDataArray* a = field->GetArray(name);
    if (!a || a->GetNumberOfComponents() != 3 || a->GetNumberOfTuples() < 1)
        return false;
    a->GetTuple(0, out);
    return true;
}

std::optional<CameraPreset> camera_of(vtkDataSet* data) {
    vtkFieldData* field = data->GetFieldData();
    CameraPreset c;
    vtkDataArray* fov = field->GetArray("camera_fov_deg");
    if (!field_vector(field, "camera_eye", c.eye) ||
        !field_vector(field, "camera_look_at", c.look_at) ||
        !field_vector(field, "camera_up", c.up) || !fov || fov->GetNumberOfTuples() < 1)
        return std::nullopt;
    c.fov_deg = fov->GetComponent(0, 0);
    if (vtkDataArray* axis = field->GetArray("camera_fov_axis_x"))
        c.fov_axis_x = axis->GetNumberOfTuples() > 0 && axis->GetComponent(0, 0) != 0;
    if (vtkDataArray* size = field->GetArray("camera_image_size");
        size && size->GetNumberOfValues() >= 2) {
        c.width = int(size->GetComponent(0, 0));
        c.height = int(size->GetComponent(1, 0));
        if (size->GetNumberOfComponents() == 2) {
            c.width = int(size->GetComponent(0, 0));
            c.height = int(size->GetComponent(0, 1));
        }
    }
    return c;
}

double value_of(vtkDataArray* a, vtkIdType i) {
    const int n = a->GetNumberOfComponents();
    if (n == 1)
        return a->GetComponent(i, 0);
    double sum = 0;
    for (int c = 0; c < n; ++c)
        sum += a->GetComponent(i, c) * a->GetComponent(i, c);
    return std::sqrt(sum);
}

double luminance_of(vtkDataArray* radiosity, vtkIdType i) {
    return (k_lum_weight_r * radiosity->GetComponent(i, 0) +
            k_lum_weight_g * radiosity->GetComponent(i, 1) +
            k_lum_weight_b * radiosity->GetComponent(i, 2)) /
           k_pi;
}

double cell_area(vtkDataSet* data, vtkIdType cell_id) {
    vtkCell* cell = data->GetCell(cell_id);
    if (cell->GetNumberOfPoints() != 3)
        return 1.0;
    double p[3][3];
    for (int k = 0; k < 3; ++k)
        cell->GetPoints()->GetPoint(k, p[k]);
    return vtkTriangle::TriangleArea(p[0], p[1], p[2]);
}

/// Reinhard et al. 2002's key value, as core's auto_exposure for images: the (area-weighted)
/// log-average luminance of the radiance B/π maps to middle grey 0.18.
double auto_exposure_of(vtkDataSet* data) {
    vtkDataArray* radiosity = data->GetCellData()->GetArray("radiosity");
    const bool cells = radiosity != nullptr;
    if (!radiosity)
        radiosity = data->GetPointData()->GetArray("radiosity");
    if (!radiosity || radiosity->GetNumberOfComponents() != 3)
        return 1.0;
    // Cells darker than 1e-4 of the brightest (unlit backs, round-off) would drag the
    // log-average down and wash the picture out: they do not set the exposure.
    double brightest = 0;
    for (vtkIdType i = 0; i < radiosity->GetNumberOfTuples(); ++i) {
        const double y = luminance_of(radiosity, i);
        if (std::isfinite(y))
            brightest = std::max(brightest, y);
    }
    double sum_log = 0, weight = 0;
    for (vtkIdType i = 0; i < radiosity->GetNumberOfTuples(); ++i) {
        const double y = luminance_of(radiosity, i);
        if (!(y > 1e-4 * brightest) || !std::isfinite(y))
            continue;
        const double w = cells ? cell_area(data, i) : 1.0;
        sum_log += w * std::log(y);
        weight += w;
    }
    return weight > 0 ? 0.18 / std::exp(sum_log / weight) : 1.0;
}

std::uint8_t encode_srgb(double linear) {
    if (!(linear > 0))
        return 0;
    if (linear >= 1)
        return 255;
    const double s =
        linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
    return std::uint8_t(std::lround(s * 255.0));
}

} // namespace

vtkSmartPointer<vtkDataSet> read_dataset(const std::string& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
        throw InputError(path, "", "no such file");
    vtkNew<vtkXMLGenericDataObjectReader> reader;
    vtkNew<ErrorCapture> errors;
    errors->watch(reader);
    reader->SetFileName(path.c_str());
    reader->Update();
    if (!errors->message.empty())
        throw ExternalError(fmt::format("cannot read VTK file '{}': {}", path, errors->message));
    auto* data = vtkDataSet::SafeDownCast(reader->GetOutputDataObject(0));
    if (!data)
        throw InputError(path, "", "not a VTK XML data set (.vtu, .vtp)");
    return vtkSmartPointer<vtkDataSet>(data);
}

void add_true_colour(vtkDataSet* data, bool point, double exposure) {
    vtkDataSetAttributes* attributes =
        point ? static_cast<vtkDataSetAttributes*>(data->GetPointData()) : data->GetCellData();
    vtkDataArray* radiosity = attributes->GetArray("radiosity");
    if (!radiosity || radiosity->GetNumberOfComponents() != 3)
        return;
    vtkNew<vtkUnsignedCharArray> colour;
    colour->SetName(k_true_colour);
    colour->SetNumberOfComponents(3);
    colour->SetNumberOfTuples(radiosity->GetNumberOfTuples());
    for (vtkIdType i = 0; i < radiosity->GetNumberOfTuples(); ++i)
        for (int c = 0; c < 3; ++c)
            colour->SetValue(3 * i + c,
                             encode_srgb(radiosity->GetComponent(i, c) / k_pi * exposure));
    attributes->AddArray(colour);
}

ViewData::ViewData(const std::string& input) {
    open_folder_or_file(input);
    vtkSmartPointer<vtkDataSet> last = load(steps_.size() - 1);
    catalogue(last);
    camera_ = camera_of(last);
    exposure_ = auto_exposure_of(last);
    update_ranges(last);
    for (std::size_t i = 0; i + 1 < steps_.size(); ++i)
        update_ranges(load(i));
}

void ViewData::open_folder_or_file(const std::string& input) {
    std::error_code ec;
    if (!fs::exists(input, ec))
        throw InputError(input, "", "no such file or folder");
    fs::path file = input, folder = fs::path(input).parent_path();
    if (fs::is_directory(input, ec)) {
        folder = input;
        file = fs::exists(folder / "series.pvd", ec) ? folder / "series.pvd" : folder / "mesh.vtu";
        if (!fs::exists(file, ec))
            throw InputError(input, "",
                             "no series.pvd or mesh.vtu in this folder; run "
                             "'penumbra bake' with '-o' this folder first");
    }
    source_ = file.string();
    const std::string ext = file.extension().string();
    if (ext != ".pvd" && ext != ".vtu" && ext != ".vtp")
        throw InputError(source_, "",
                         "not something penumbra view shows: give an output "
                         "folder, or a .vtu, .vtp or .pvd file");
    if (ext == ".pvd")
        read_pvd(source_);
    else
        steps_ = {{0.0, source_}};
    auto companion = [&](const char* name) {
        const fs::path p = folder / name;
        return fs::is_regular_file(p, ec) && !fs::equivalent(p, file, ec) ? p.string()
                                                                          : std::string();
    };
    sensors_file_ = companion("sensors.vtp");
    discontinuities_file_ = companion("discontinuities.vtp");
}

void ViewData::read_pvd(const std::string& path) {
    vtkNew<vtkXMLDataParser> parser;
    vtkNew<ErrorCapture> errors;
    parser->AddObserver(vtkCommand::ErrorEvent, errors);
    parser->SetFileName(path.c_str());
    if (!parser->Parse() || !errors->message.empty())
        throw InputError(path, "", "not a readable .pvd collection: " + errors->message);
    vtkXMLDataElement* root = parser->GetRootElement();
    vtkXMLDataElement* collection = root ? root->FindNestedElementWithName("Collection") : nullptr;
    if (!collection)
        throw InputError(path, "", "not a VTK collection (no <Collection> element)");
    const fs::path folder = fs::path(path).parent_path();
    for (int i = 0; i < collection->GetNumberOfNestedElements(); ++i) {
        vtkXMLDataElement* e = collection->GetNestedElement(i);
        const char* file = e->GetAttribute("file");
        if (std::string(e->GetName()) != "DataSet" || !file)
            continue;
        double time = double(steps_.size());
        e->GetScalarAttribute("timestep", time);
        steps_.push_back({time, (folder / file).string()});
    }
    if (steps_.empty())
        throw InputError(path, "", "the collection lists no data sets");
    series_ = true;
}

vtkSmartPointer<vtkDataSet> ViewData::load(std::size_t step) const {
    return read_dataset(steps_.at(step).file);
}

void ViewData::catalogue(vtkDataSet* last) {
    const auto units = units_of(last);
    auto add = [&](vtkDataArray* a, bool point) {
        if (!a || !a->GetName() || find(a->GetName()))
            return;
        ArrayInfo info;
        info.name = a->GetName();
        info.point = point || last->GetPointData()->GetArray(a->GetName()) != nullptr;
        info.has_cell = last->GetCellData()->GetArray(a->GetName()) != nullptr;
        info.components = a->GetNumberOfComponents();
        auto u = units.find(info.name);
        info.unit = u != units.end() ? u->second : unit_from_suffix(info.name);
        arrays_.push_back(info);
    };
    // Cell data first: it lists every array of mesh.vtu in the writer's order.
    for (int i = 0; i < last->GetCellData()->GetNumberOfArrays(); ++i)
        add(last->GetCellData()->GetArray(i), false);
    for (int i = 0; i < last->GetPointData()->GetNumberOfArrays(); ++i)
        add(last->GetPointData()->GetArray(i), true);
    if (const ArrayInfo* radiosity = find("radiosity"); radiosity && radiosity->components == 3) {
        ArrayInfo colour;
        colour.name = k_true_colour;
        colour.point = radiosity->point;
        colour.has_cell = radiosity->has_cell;
        colour.components = 3;
        arrays_.insert(arrays_.begin(), colour);
    }
    if (arrays_.empty())
        throw InputError(source_, "", "the data set has no point or cell arrays to show");
    for (ArrayInfo& a : arrays_) {
        a.min = std::numeric_limits<double>::infinity();
        a.max = -a.min;
    }
}

void ViewData::update_ranges(vtkDataSet* data) {
    for (ArrayInfo& info : arrays_) {
        vtkDataArray* a = info.point ? data->GetPointData()->GetArray(info.name.c_str())
                                     : data->GetCellData()->GetArray(info.name.c_str());
        for (vtkIdType i = 0; a && i < a->GetNumberOfTuples(); ++i) {
            const double v = value_of(a, i);
            if (!std::isfinite(v))
                continue;
            info.min = std::min(info.min, v);
            info.max = std::max(info.max, v);
            if (v > 0 && (info.min_positive == 0 || v < info.min_positive))
                info.min_positive = v;
        }
    }
}

const ArrayInfo* ViewData::find(const std::string& name) const {
    for (const ArrayInfo& a : arrays_)
        if (a.name == name)
            return &a;
    return nullptr;
}

std::string ViewData::array_names() const {
    std::string names;
    for (const ArrayInfo& a : arrays_)
        names += (names.empty() ? "" : ", ") + a.name;
    return names;
}

} // namespace penumbra::viewer
