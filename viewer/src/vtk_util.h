#pragma once
// Helpers shared by the VTK writers and the viewer: error capture (VTK reports errors through
// events, not exceptions), array builders and an XML writer call that throws ExternalError.

#include "core/rgb.h"

#include <vtkCommand.h>
#include <vtkDataSetAttributes.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

class vtkAlgorithm;
class vtkDataObject;
class vtkXMLWriter;

namespace penumbra::viewer {

/// Collects the first error a VTK object reports. While an observer is registered, VTK sends
/// the object's errors to it instead of printing them.
class ErrorCapture final : public vtkCommand {
public:
    static ErrorCapture* New() { return new ErrorCapture; }
    void Execute(vtkObject*, unsigned long, void* call_data) override;
    /// Observes the errors of \p algorithm and of its executive (which repeats them).
    void watch(vtkAlgorithm* algorithm);
    std::string message;
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

/// Adds the field array "units": one "name=unit" string per array name, so that readers (the
/// viewer, ParaView users) know each array's unit without a table of names.
void add_units(vtkDataObject* data, const std::vector<std::pair<std::string, std::string>>& units);

/// Writes \p data with \p writer (binary appended, zlib) to \p temp; errors name \p path.
void write_xml(vtkXMLWriter* writer, vtkDataObject* data, const std::string& temp,
               const std::string& path);

} // namespace penumbra::viewer
