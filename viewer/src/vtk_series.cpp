// The passes of a progressive solve as a ParaView data collection (.pvd): one .vtu per pass,
// listed with the shot count as its time value.

#include "viewer/vtk_output.h"

#include "core/error.h"
#include "core/files.h"

#include <fmt/format.h>

#include <filesystem>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace penumbra::viewer {

namespace {

namespace fs = std::filesystem;

std::string xml_escape(const std::string& text) {
    std::string out;
    for (char c : text) {
        switch (c) {
        case '&':
            out += "&amp;";
            break;
        case '<':
            out += "&lt;";
            break;
        case '>':
            out += "&gt;";
            break;
        case '"':
            out += "&quot;";
            break;
        default:
            out += c;
        }
    }
    return out;
}

bool is_series_file(const fs::path& p) {
    const std::string name = p.filename().string();
    return name.rfind("mesh_", 0) == 0 && p.extension() == ".vtu";
}

} // namespace

void write_pvd(const std::string& path, const std::vector<PvdStep>& steps) {
    std::string text = "<?xml version=\"1.0\"?>\n"
                       "<VTKFile type=\"Collection\" version=\"0.1\" "
                       "byte_order=\"LittleEndian\">\n  <Collection>\n";
    for (const PvdStep& s : steps)
        text += fmt::format("    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n",
                            s.timestep, xml_escape(s.file));
    text += "  </Collection>\n</VTKFile>\n";
    write_text_file(path, text);
}

bool remove_series(const std::string& dir) {
    std::error_code ec;
    bool removed = fs::remove(fs::path(dir) / "series.pvd", ec);
    const fs::path folder = fs::path(dir) / "series";
    if (!fs::is_directory(folder, ec))
        return removed;
    for (const auto& entry : fs::directory_iterator(folder, ec))
        if (entry.is_regular_file(ec) && is_series_file(entry.path()))
            removed = fs::remove(entry.path(), ec) || removed;
    if (fs::is_empty(folder, ec))
        fs::remove(folder, ec);
    return removed;
}

SeriesWriter::SeriesWriter(std::string dir, const Scene& scene)
    : dir_(std::move(dir)), scene_(scene) {
    remove_series(dir_);
    std::error_code ec;
    fs::create_directories(fs::path(dir_) / "series", ec);
    if (ec)
        throw ConfigError(fmt::format("cannot create folder '{}': {}",
                                      (fs::path(dir_) / "series").string(), ec.message()));
}

std::int64_t SeriesWriter::last_shots() const {
    return steps_.empty() ? -1 : std::int64_t(steps_.back().timestep);
}

void SeriesWriter::add(const RadiosityMesh& mesh, const Solution& snapshot, std::int64_t shots) {
    const std::string file = fmt::format("series/mesh_{:08d}.vtu", shots);
    write_vtu((fs::path(dir_) / file).string(), scene_, mesh, snapshot);
    const double timestep = double(shots);
    if (!steps_.empty() && steps_.back().timestep == timestep)
        steps_.back().file = file;
    else
        steps_.push_back({timestep, file});
    write_pvd((fs::path(dir_) / "series.pvd").string(), steps_);
}

} // namespace penumbra::viewer
