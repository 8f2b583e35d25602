#pragma once
// Private to penumbra_core: Radiance's `!xform` command (issue #30): rigid motions, uniform
// scaling and mirrors, and arrays of copies.

#include <array>
#include <string>
#include <vector>

#include "core/vec.h"

#include "syntax.h"

namespace penumbra::radiance {

/// \brief p ↦ M p + t.
struct Affine {
    std::array<Vec3, 3> rows{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}}; ///< of M
    Vec3 translation;

    Vec3 point(const Vec3& p) const;
    /// \brief M d, normalised: a direction (a source's, the sun's) after the motion.
    Vec3 direction(const Vec3& d) const;
    /// \brief True when M reverses orientation: a polygon's vertex order must then be
    ///        reversed to keep its front side.
    bool mirrors() const;
};

/// \brief \p first, then \p second.
Affine then(const Affine& first, const Affine& second);

/// \brief What an `!xform` line asks for.
struct Xform {
    /// One transform per copy (one without `-a`; the product of the counts with it).
    std::vector<Affine> copies;
    bool invert = false;            ///< `-I`: every surface turned over
    std::vector<std::string> files; ///< as written, relative to the including file's folder
};

/// \brief Reads `!xform` options as xform(1) does: -t x y z, -rx/-ry/-rz degrees, -s factor,
///        -mx/-my/-mz, -a count and -i count, -I, and -c (ignored: commands are always
///        interpreted here). -n, -m and -f, reading the standard input, and any other option
///        are InputErrors at \p command's line.
Xform parse_xform(const Command& command);

} // namespace penumbra::radiance
