// The file level of the Radiance importer: reading files, following `!xform` into the files it
// names, and running `!gensky` and `!gendaylit`. Radiance runs `!` lines as shell commands;
// Penumbra interprets these three and refuses any other, naming the line.

#include "radiance_import.h"

#include <filesystem>

#include <fmt/format.h>

#include "core/error.h"
#include "core/files.h"

#include "gendaylit.h"
#include "gensky.h"
#include "scene_builder.h"
#include "syntax.h"
#include "transform.h"

namespace penumbra {

namespace fs = std::filesystem;

namespace {

using namespace radiance;

/// Files one `.rad` file may nest through `!xform`: deeper is a file that includes itself.
constexpr int k_max_nesting = 32;

class FileReader {
public:
    explicit FileReader(SceneBuilder& builder) : builder_(builder) {}

    void read(const std::string& path, const Affine& xf, bool invert, int depth) {
        std::error_code ec;
        if (!fs::is_regular_file(path, ec))
            throw InputError(path, "geometry", "Radiance file not found");
        const std::string dir = fs::path(path).parent_path().string();
        for (const Statement& s : parse_statements(read_text_file(path), path)) {
            if (const auto* p = std::get_if<Primitive>(&s))
                builder_.add(*p, xf, invert);
            else
                run(std::get<Command>(s), dir, xf, invert, depth);
        }
    }

private:
    void run(const Command& c, const std::string& dir, const Affine& xf, bool invert, int depth) {
        const std::string name = c.words.empty() ? "" : fs::path(c.words[0]).filename().string();
        if (name == "xform")
            return run_xform(c, dir, xf, invert, depth);
        if (name == "gensky") {
            for (const Primitive& p : gensky_primitives(run_gensky(c), c.where))
                builder_.add(p, xf, invert);
            return;
        }
        if (name == "gendaylit") {
            for (const Primitive& p : gendaylit_primitives(c))
                builder_.add(p, xf, invert);
            return;
        }
        fail(c.where, fmt::format("command '!{}' is not supported (supported: !xform, !gensky, "
                                  "!gendaylit)",
                                  name));
    }

    void run_xform(const Command& c, const std::string& dir, const Affine& xf, bool invert,
                   int depth) {
        if (depth >= k_max_nesting)
            fail(c.where, fmt::format("!xform nests more than {} files deep (does a file "
                                      "include itself?)",
                                      k_max_nesting));
        const Xform x = parse_xform(c);
        for (const std::string& file : x.files) {
            const std::string path = (fs::path(dir) / file).string();
            std::error_code ec;
            if (!fs::is_regular_file(path, ec))
                fail(c.where, fmt::format("!xform: file '{}' not found", path));
            for (const Affine& copy : x.copies)
                read(path, then(copy, xf), invert != x.invert, depth + 1);
        }
    }

    SceneBuilder& builder_;
};

} // namespace

bool is_radiance_file(const std::string& path) {
    return fs::path(path).extension() == ".rad";
}

RadianceImport::RadianceImport(double metres_per_unit)
    : builder_(std::make_unique<SceneBuilder>(metres_per_unit)) {}

RadianceImport::~RadianceImport() = default;

ImportedGeometry RadianceImport::read(const std::string& path) {
    FileReader(*builder_).read(path, Affine{}, false, 0);
    return builder_->take_geometry();
}

Sources RadianceImport::sources() const {
    return builder_->sources();
}

} // namespace penumbra
