#pragma once
// Private to penumbra_core: Radiance scene files (`.rad`) as geometry files of a scene
// (issue #30; docs/scene-format.md lists the subset read). One RadianceImport reads all the
// `.rad` files of a scene in their `geometry` order, so that a modifier defined in one file
// serves the files after it, as Radiance's oconv reads them.

#include <memory>
#include <string>

#include "../geometry_import.h"

namespace penumbra {

namespace radiance {
class SceneBuilder;
struct Sources;
} // namespace radiance

/// \brief Whether \p path names a Radiance scene file (it ends in `.rad`).
bool is_radiance_file(const std::string& path);

class RadianceImport {
public:
    /// \brief Lengths in the files are multiplied by \p metres_per_unit.
    explicit RadianceImport(double metres_per_unit);
    ~RadianceImport();

    /// \brief Reads \p path with the files its `!xform` lines name (relative to the including
    ///        file's folder) and its `!gensky` and `!gendaylit` lines. Returns its polygons and the
    ///        materials they use. Throws InputError naming the file and line of anything
    ///        unsupported.
    ImportedGeometry read(const std::string& path);
    /// \brief The sun and the sky every file read so far gave (each optional), and where.
    radiance::Sources sources() const;

private:
    std::unique_ptr<radiance::SceneBuilder> builder_;
};

} // namespace penumbra
