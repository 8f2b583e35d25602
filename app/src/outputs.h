#pragma once
// The files a bake writes, as a list of writers: each names the files it owns in the output
// folder, says whether this bake produces them and writes them. write_outputs() walks the
// list, so a new output (renders, lightmaps, daylight results) is one writer, and files an
// earlier bake left that this one does not write are removed in one place.

#include <functional>
#include <string>
#include <vector>

#include "app/pipeline.h"
#include "core/scene.h"

namespace penumbra::app {

/// What every writer reads: the scene, the bake's result and the output folder.
struct OutputTarget {
    const Scene& scene;
    const BakeResult& result;
    std::string dir;
    bool save_state = true;

    /// \brief The path of \p name inside the output folder.
    std::string path(const std::string& name) const;
};

/// \brief One output of a bake. \p files are the names it owns inside the output folder, and
///        \p scene_files, when set, the names that depend on the scene (one per grid); when
///        \p wanted is false they are removed instead of written (by \p remove when set, else
///        file by file).
struct OutputWriter {
    std::string name;
    std::vector<std::string> files;
    std::function<bool(const OutputTarget&)> wanted;
    std::function<void(const OutputTarget&)> write;
    std::function<void(const OutputTarget&)> remove = {};
    std::function<std::vector<std::string>(const OutputTarget&)> scene_files = {};
};

/// \brief The writers of `penumbra bake`, in the order they write.
const std::vector<OutputWriter>& bake_writers();

/// \brief Removes \p writer's files from the output folder (those that exist).
void remove_output(const OutputWriter& writer, const OutputTarget& target);

} // namespace penumbra::app
