#pragma once
// Helpers shared by the VTK writers and the viewer: error capture (VTK reports errors through
// events, not exceptions), array builders and an XML file writer that throws ExternalError.

#include "core/files.h"
#include "core/rgb.h"

#include <vtkCommand.h>
#include <vtkDataSetAttributes.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <cstddef>
#include <ostream>
#include <streambuf>
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

/// A std::ostream onto a FileWriter. VTK's writers see only a failed stream when the disk is
/// full; the FileWriter keeps the system's reason.
class FileStream final : public std::ostream {
public:
    explicit FileStream(FileWriter& file) : std::ostream(&buffer_), buffer_(file) {}

private:
    class Buffer final : public std::streambuf {
    public:
        explicit Buffer(FileWriter& file) : file_(file) {}

    protected:
        int_type overflow(int_type c) override;
        std::streamsize xsputn(const char* s, std::streamsize n) override;
        pos_type seekoff(off_type offset, std::ios_base::seekdir dir,
                         std::ios_base::openmode) override;
        pos_type seekpos(pos_type position, std::ios_base::openmode mode) override {
            return seekoff(off_type(position), std::ios_base::beg, mode);
        }

    private:
        FileWriter& file_;
    };
    Buffer buffer_;
};

/// \p Writer (a vtkXMLWriter) writing to a stream of ours instead of a file it opens itself.
template <typename Writer> class StreamedWriter final : public Writer {
public:
    static StreamedWriter* New() {
        auto* writer = new StreamedWriter;
        writer->InitializeObjectBase();
        return writer;
    }
    /// VTK writes to a stream it was given (its protected Stream) rather than opening FileName.
    void set_stream(std::ostream* stream) { this->Stream = stream; }
};

/// Writes \p data with \p writer (binary appended, zlib) to \p file; errors name \p path and
/// give the system's reason when a write failed.
void write_xml(vtkXMLWriter* writer, vtkDataObject* data, FileWriter& file,
               const std::string& path);

/// Writes \p data to the VTK XML file \p path atomically with a writer of type \p Writer
/// (vtkXMLPolyDataWriter, vtkXMLUnstructuredGridWriter).
template <typename Writer> void write_xml_file(vtkDataObject* data, const std::string& path) {
    write_atomically(path, [&](const std::string& temp) {
        FileWriter file(temp, path);
        FileStream stream(file);
        vtkNew<StreamedWriter<Writer>> writer;
        writer->set_stream(&stream);
        write_xml(writer, data, file, path);
    });
}

} // namespace penumbra::viewer
