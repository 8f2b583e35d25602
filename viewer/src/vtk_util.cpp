#include "vtk_util.h"

#include "core/error.h"

#include <fmt/format.h>
#include <vtkAlgorithm.h>
#include <vtkDataObject.h>
#include <vtkErrorCode.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkStringArray.h>
#include <vtkXMLWriter.h>

namespace penumbra::viewer {

namespace {
/// VTK's text is "ERROR: In file, line n\nClass (address): message\n\n": keep the message.
std::string plain_message(std::string text) {
    if (auto line_end = text.find('\n');
        text.rfind("ERROR: In ", 0) == 0 && line_end != std::string::npos)
        text.erase(0, line_end + 1);
    if (auto colon = text.find("): "); colon != std::string::npos)
        text.erase(0, colon + 3);
    while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
        text.pop_back();
    for (char& c : text)
        if (c == '\n')
            c = ' ';
    return text;
}
} // namespace

void ErrorCapture::Execute(vtkObject*, unsigned long, void* call_data) {
    if (message.empty())
        message =
            call_data ? plain_message(static_cast<const char*>(call_data)) : "unknown VTK error";
}

void ErrorCapture::watch(vtkAlgorithm* algorithm) {
    algorithm->AddObserver(vtkCommand::ErrorEvent, this);
    algorithm->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, this);
}

void add_units(vtkDataObject* data, const std::vector<std::pair<std::string, std::string>>& units) {
    vtkNew<vtkStringArray> array;
    array->SetName("units");
    for (const auto& [name, unit] : units)
        array->InsertNextValue(name + "=" + unit);
    data->GetFieldData()->AddArray(array);
}

FileStream::Buffer::int_type FileStream::Buffer::overflow(int_type c) {
    if (traits_type::eq_int_type(c, traits_type::eof()))
        return traits_type::not_eof(c);
    const char byte = traits_type::to_char_type(c);
    return xsputn(&byte, 1) == 1 ? c : traits_type::eof();
}

std::streamsize FileStream::Buffer::xsputn(const char* s, std::streamsize n) {
    try {
        file_.write(s, std::size_t(n));
        return n;
    } catch (const ExternalError&) {
        return 0; // the stream fails; file_ keeps the reason
    }
}

FileStream::Buffer::pos_type
FileStream::Buffer::seekoff(off_type offset, std::ios_base::seekdir dir, std::ios_base::openmode) {
    const off_type base = dir == std::ios_base::beg   ? 0
                          : dir == std::ios_base::cur ? off_type(file_.position())
                                                      : off_type(-1);
    if (base < 0 || base + offset < 0)
        return pos_type(off_type(-1));
    if (offset == 0 && dir == std::ios_base::cur) // tellp()
        return pos_type(base);
    try {
        file_.seek(std::uint64_t(base + offset));
        return pos_type(base + offset);
    } catch (const ExternalError&) {
        return pos_type(off_type(-1));
    }
}

void write_xml(vtkXMLWriter* writer, vtkDataObject* data, FileWriter& file,
               const std::string& path) {
    vtkNew<ErrorCapture> errors;
    errors->watch(writer);
    writer->SetInputDataObject(data);
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff(); // raw binary, not base64
    writer->SetCompressorTypeToZLib();
    writer->SetHeaderTypeToUInt64();
    const bool ok = writer->Write() == 1;
    const unsigned long code = writer->GetErrorCode();
    if (file.error())
        file.rethrow();
    if (!ok || code != vtkErrorCode::NoError || !errors->message.empty()) {
        const std::string reason =
            !errors->message.empty() ? errors->message : vtkErrorCode::GetStringFromErrorCode(code);
        throw ExternalError(fmt::format("cannot write VTK file '{}': {}", path, reason));
    }
    file.close();
}

} // namespace penumbra::viewer
