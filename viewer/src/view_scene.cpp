// The scene of `penumbra view`. Colour ranges come from ViewData (over all steps of a series),
// so stepping through the passes of a progressive solve shows the light building up rather
// than a picture rescaled at each step. Surfaces are unlit (the colours are the solution) and
// back faces are culled: the two sides of a surface are coincident elements.

#include "view_scene.h"

#include "core/error.h"
#include "core/files.h"
#include "viewer/view.h"

#include <fmt/format.h>
#include <vtkCamera.h>
#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkCellPicker.h>
#include <vtkColorTransferFunction.h>
#include <vtkDataArray.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkProperty.h>
#include <vtkStringArray.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cmath>
#include <string_view>
#include <vector>

namespace penumbra::viewer {

namespace {

/// The log scale spans at most three decades below the maximum: darker values say little
/// (and a single almost-black element would squeeze everything else into the top colours).
constexpr double k_log_decades = 1e-3;

/// False-colour ramp: dark blue → blue → green → yellow → red, a lighting engineer's
/// low-to-high, with roughly increasing lightness up to yellow.
void fill_ramp(vtkLookupTable* lut) {
    vtkNew<vtkColorTransferFunction> ramp;
    ramp->SetColorSpaceToLab();
    ramp->AddRGBPoint(0.00, 0.08, 0.05, 0.35);
    ramp->AddRGBPoint(0.25, 0.05, 0.40, 0.85);
    ramp->AddRGBPoint(0.50, 0.15, 0.75, 0.40);
    ramp->AddRGBPoint(0.75, 0.98, 0.85, 0.15);
    ramp->AddRGBPoint(1.00, 0.85, 0.10, 0.05);
    const int n = 256;
    lut->SetNumberOfTableValues(n);
    for (int i = 0; i < n; ++i) {
        double rgb[3];
        ramp->GetColor(double(i) / (n - 1), rgb);
        lut->SetTableValue(i, rgb[0], rgb[1], rgb[2], 1.0);
    }
    lut->SetNanColor(0.5, 0.5, 0.5, 1.0);
}

vtkDataArray* array_of(vtkDataSet* data, const std::string& name, bool point) {
    return point ? data->GetPointData()->GetArray(name.c_str())
                 : data->GetCellData()->GetArray(name.c_str());
}

std::string format_value(const std::vector<double>& v, const std::string& unit) {
    std::string text;
    if (v.size() == 1)
        text = fmt::format("{:.4g}", v[0]);
    else {
        for (double x : v)
            text += fmt::format("{}{:.4g}", text.empty() ? "(" : ", ", x);
        text += ")";
    }
    return unit.empty() || unit == "1" ? text : text + " " + unit;
}

std::vector<double> tuple_of(vtkDataArray* a, vtkIdType i) {
    std::vector<double> v(std::size_t(a->GetNumberOfComponents()));
    for (std::size_t c = 0; c < v.size(); ++c)
        v[c] = a->GetComponent(i, int(c));
    return v;
}

void style_text(vtkTextActor* text, int size, bool top) {
    text->GetTextProperty()->SetFontSize(size);
    text->GetTextProperty()->SetColor(1, 1, 1);
    text->GetTextProperty()->ShadowOn();
    text->GetTextProperty()->SetVerticalJustification(top ? VTK_TEXT_TOP : VTK_TEXT_BOTTOM);
    text->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
    text->GetPositionCoordinate()->SetValue(0.01, top ? 0.99 : 0.01);
}

vtkSmartPointer<vtkDataSetMapper> overlay_mapper(const std::string& file) {
    auto mapper = vtkSmartPointer<vtkDataSetMapper>::New();
    mapper->SetInputData(read_dataset(file));
    mapper->ScalarVisibilityOff();
    return mapper;
}

} // namespace

ViewScene::ViewScene(const ViewData& data, const ViewState& state, int width, int height,
                     bool offscreen, const Context& ctx)
    : data_(data), state_(state), ctx_(ctx) {
    window_->AddObserver(vtkCommand::ErrorEvent, errors_);
    renderer_->AddObserver(vtkCommand::ErrorEvent, errors_);
    window_->SetOffScreenRendering(offscreen ? 1 : 0);
    window_->SetSize(width, height);
    window_->SetWindowName(("penumbra view: " + data.source()).c_str());
    window_->AddRenderer(renderer_);
    renderer_->SetBackground(0.12, 0.12, 0.14);

    fill_ramp(lut_);
    actor_->SetMapper(mapper_);
    // Unlit: the colours are the solution.
    actor_->GetProperty()->SetAmbient(1.0);
    actor_->GetProperty()->SetDiffuse(0.0);
    actor_->GetProperty()->SetSpecular(0.0);
    actor_->GetProperty()->BackfaceCullingOn();
    actor_->GetProperty()->SetEdgeColor(0.1, 0.1, 0.1);
    actor_->GetProperty()->SetEdgeVisibility(state_.edges);
    mapper_->SetLookupTable(lut_);
    mapper_->SetUseLookupTableScalarRange(true);
    renderer_->AddActor(actor_);

    scalar_bar_->SetLookupTable(lut_);
    scalar_bar_->SetNumberOfLabels(5);
    scalar_bar_->SetLabelFormat("%.3g");
    scalar_bar_->UnconstrainedFontSizeOn();
    const int font = std::clamp(std::min(width, height) / 28, 9, 16);
    scalar_bar_->GetLabelTextProperty()->SetFontSize(font);
    scalar_bar_->GetLabelTextProperty()->SetColor(1, 1, 1);
    scalar_bar_->GetLabelTextProperty()->ShadowOn();
    scalar_bar_->GetLabelTextProperty()->ItalicOff();
    scalar_bar_->GetLabelTextProperty()->BoldOff();
    scalar_bar_->SetBarRatio(0.25);
    scalar_bar_->SetPosition(0.80, 0.05);
    scalar_bar_->SetWidth(0.19);
    scalar_bar_->SetHeight(0.83);
    renderer_->AddActor2D(scalar_bar_);
    style_text(bar_title_, font + 1, true);
    bar_title_->GetTextProperty()->SetJustificationToRight();
    bar_title_->GetPositionCoordinate()->SetValue(0.99, 0.99);
    renderer_->AddActor2D(bar_title_);

    style_text(status_, 14, true);
    style_text(help_, 12, false);
    help_->SetInput("a/A array  l log  e edges  n/p step  c/r camera  s sensors  "
                    "d discontinuities  click pick  q quit");
    renderer_->AddActor2D(status_);
    renderer_->AddActor2D(help_);
    show_text(false);

    add_overlays();
    load_step();
    apply_array();
    scene_camera();
}

void ViewScene::add_overlays() {
    if (!data_.sensors_file().empty()) {
        sensors_->SetMapper(overlay_mapper(data_.sensors_file()));
        sensors_->GetProperty()->SetColor(1, 1, 1);
        sensors_->GetProperty()->SetPointSize(10);
        sensors_->GetProperty()->RenderPointsAsSpheresOn();
        sensors_->GetProperty()->LightingOff();
        renderer_->AddActor(sensors_);
    }
    if (!data_.discontinuities_file().empty()) {
        discontinuities_->SetMapper(overlay_mapper(data_.discontinuities_file()));
        discontinuities_->GetProperty()->SetColor(1.0, 0.2, 0.9);
        discontinuities_->GetProperty()->SetLineWidth(2);
        discontinuities_->GetProperty()->LightingOff();
        renderer_->AddActor(discontinuities_);
    }
    sensors_->SetVisibility(state_.sensors);
    discontinuities_->SetVisibility(state_.discontinuities);
}

void ViewScene::load_step() {
    current_ = data_.load(state_.step);
    if (const ArrayInfo* colour = data_.find(k_true_colour))
        add_true_colour(current_, colour->point, data_.exposure());
    mapper_->SetInputData(current_);
}

void ViewScene::apply_array() {
    const ArrayInfo& info = data_.arrays()[state_.array];
    const bool true_colour = info.name == k_true_colour;
    mapper_->ScalarVisibilityOn();
    if (info.point)
        mapper_->SetScalarModeToUsePointFieldData();
    else
        mapper_->SetScalarModeToUseCellFieldData();
    mapper_->SelectColorArray(info.name.c_str());
    mapper_->SetColorMode(true_colour ? VTK_COLOR_MODE_DIRECT_SCALARS : VTK_COLOR_MODE_MAP_SCALARS);
    mapper_->SetInterpolateScalarsBeforeMapping(!true_colour && info.point);
    scalar_bar_->SetVisibility(!true_colour);
    bar_title_->SetVisibility(!true_colour);
    if (!true_colour) {
        double lo = info.min <= info.max ? info.min : 0, hi = info.min <= info.max ? info.max : 1;
        const bool log = state_.log_scale && hi > 0 && info.min_positive > 0;
        if (log)
            lo = std::max(info.min_positive, hi * k_log_decades);
        if (hi <= lo)
            hi = lo + (lo != 0 ? std::abs(lo) * 1e-3 : 1.0);
        lut_->SetScale(log ? VTK_SCALE_LOG10 : VTK_SCALE_LINEAR);
        lut_->SetVectorModeToMagnitude();
        lut_->SetRange(lo, hi);
        lut_->Build();
        const std::string what = info.components > 1 ? "|" + info.name + "|" : info.name;
        const std::string title =
            info.unit.empty() || info.unit == "1" ? what : fmt::format("{} [{}]", what, info.unit);
        bar_title_->SetInput(title.c_str());
    }
    update_status();
}

void ViewScene::update_status() {
    const ArrayInfo& info = data_.arrays()[state_.array];
    std::string text = info.name;
    if (info.name != k_true_colour)
        text += state_.log_scale ? "  (log)" : "  (linear)";
    if (data_.is_series())
        text += fmt::format("   step {}/{}  ({:g} shots)", state_.step + 1, data_.steps().size(),
                            data_.steps()[state_.step].time);
    if (!picked_.empty())
        text += "\n" + picked_;
    status_->SetInput(text.c_str());
}

void ViewScene::cycle_array(int delta) {
    const auto n = std::ptrdiff_t(data_.arrays().size());
    state_.array = std::size_t(((std::ptrdiff_t(state_.array) + delta) % n + n) % n);
    picked_.clear();
    apply_array();
}

void ViewScene::toggle_log() {
    state_.log_scale = !state_.log_scale;
    apply_array();
}

void ViewScene::toggle_edges() {
    state_.edges = !state_.edges;
    actor_->GetProperty()->SetEdgeVisibility(state_.edges);
}

void ViewScene::toggle_sensors() {
    state_.sensors = !state_.sensors;
    sensors_->SetVisibility(state_.sensors);
}

void ViewScene::toggle_discontinuities() {
    state_.discontinuities = !state_.discontinuities;
    discontinuities_->SetVisibility(state_.discontinuities);
}

void ViewScene::change_step(int delta) {
    const auto n = data_.steps().size();
    const auto next =
        std::clamp(std::ptrdiff_t(state_.step) + delta, std::ptrdiff_t(0), std::ptrdiff_t(n) - 1);
    if (std::size_t(next) == state_.step)
        return;
    state_.step = std::size_t(next);
    picked_.clear();
    load_step();
    apply_array();
}

void ViewScene::scene_camera() {
    const auto& preset = data_.camera();
    if (!preset) {
        fit_camera();
        return;
    }
    vtkCamera* camera = renderer_->GetActiveCamera();
    camera->SetPosition(preset->eye);
    camera->SetFocalPoint(preset->look_at);
    camera->SetViewUp(preset->up);
    camera->SetUseHorizontalViewAngle(preset->fov_axis_x);
    camera->SetViewAngle(preset->fov_deg);
    renderer_->ResetCameraClippingRange();
}

void ViewScene::fit_camera() {
    renderer_->ResetCamera();
}

void ViewScene::show_text(bool on) {
    status_->SetVisibility(on);
    help_->SetVisibility(on);
}

void ViewScene::render() {
    window_->Render();
    if (!errors_->message.empty())
        throw ExternalError("penumbra view: VTK could not render: " + errors_->message);
}

void ViewScene::write_png(const std::string& path) {
    render();
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(window_);
    grab->SetInputBufferTypeToRGB();
    grab->ReadFrontBufferOff();
    // Encoded in memory, then written by write_text_file: VTK's own file output does not say
    // why a write failed.
    vtkNew<vtkPNGWriter> writer;
    vtkNew<ErrorCapture> errors;
    errors->watch(writer);
    errors->watch(grab);
    writer->SetInputConnection(grab->GetOutputPort());
    writer->WriteToMemoryOn();
    writer->Write();
    vtkUnsignedCharArray* encoded = writer->GetResult();
    if (!errors->message.empty() || !encoded)
        throw ExternalError(fmt::format("cannot write PNG file '{}': {}", path,
                                        errors->message.empty() ? "no image" : errors->message));
    write_text_file(path, std::string_view(reinterpret_cast<const char*>(encoded->GetPointer(0)),
                                           std::size_t(encoded->GetNumberOfValues())));
}

void ViewScene::pick(int x, int y) {
    vtkNew<vtkCellPicker> picker;
    picker->SetTolerance(0.002);
    if (!picker->Pick(x, y, 0, renderer_) || picker->GetCellId() < 0) {
        picked_ = fmt::format("pick ({}, {}): nothing there", x, y);
    } else if (picker->GetActor() == sensors_.GetPointer()) {
        vtkDataSet* sensors = sensors_->GetMapper()->GetInput();
        auto* names =
            vtkStringArray::SafeDownCast(sensors->GetPointData()->GetAbstractArray("name"));
        vtkDataArray* lx = sensors->GetPointData()->GetArray("illuminance_total_lx");
        const vtkIdType id = picker->GetPointId() >= 0 ? picker->GetPointId() : 0;
        picked_ = fmt::format("sensor '{}': illuminance_total_lx = {}",
                              names ? names->GetValue(id) : std::to_string(id),
                              lx ? format_value(tuple_of(lx, id), "lx") : "?");
    } else {
        picked_ =
            describe_surface_pick(picker->GetCellId(), picker->GetPCoords(), picker->GetSubId());
        const double* p = picker->GetPickPosition();
        picked_ += fmt::format(" at ({:.3f}, {:.3f}, {:.3f}) m", p[0], p[1], p[2]);
    }
    ctx_.info("{}", picked_);
    update_status();
}

std::string ViewScene::describe_surface_pick(vtkIdType cell, const double pcoords[3], int sub_id) {
    const ArrayInfo& info = data_.arrays()[state_.array];
    // True colour is a display encoding: report the radiosity it shows.
    const std::string name = info.name == k_true_colour ? "radiosity" : info.name;
    const ArrayInfo* shown = data_.find(name);
    std::string where = fmt::format("element {}", cell);
    if (vtkDataArray* surface = current_->GetCellData()->GetArray("surface_id"))
        where += fmt::format(" (surface {})", surface->GetComponent(cell, 0));
    if (!shown)
        return where;
    if (vtkDataArray* a = array_of(current_, name, false))
        return fmt::format("{}: {} = {}", where, name,
                           format_value(tuple_of(a, cell), shown->unit));
    vtkDataArray* a = array_of(current_, name, true);
    if (!a)
        return where;
    // A point-only array: interpolate the vertex values at the picked point.
    vtkCell* c = current_->GetCell(cell);
    std::vector<double> weights(std::size_t(c->GetNumberOfPoints()));
    double x[3];
    double pc[3] = {pcoords[0], pcoords[1], pcoords[2]};
    c->EvaluateLocation(sub_id, pc, x, weights.data());
    std::vector<double> value(std::size_t(a->GetNumberOfComponents()), 0.0);
    for (vtkIdType k = 0; k < c->GetNumberOfPoints(); ++k)
        for (std::size_t comp = 0; comp < value.size(); ++comp)
            value[comp] += weights[std::size_t(k)] * a->GetComponent(c->GetPointId(k), int(comp));
    return fmt::format("{}: {} = {} (interpolated)", where, name, format_value(value, shown->unit));
}

} // namespace penumbra::viewer
