// Fuzz target: the scene loader end to end on arbitrary JSON text (scene_json.cpp, then the
// merging and validation of scene_io.cpp). Relative geometry and sensor paths resolve in an
// empty scratch folder, so that the target reads no repository files.

#include <cstdint>
#include <filesystem>
#include <string>

#include "core/scene_io.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace penumbra;
    const std::string text(reinterpret_cast<const char*>(data), size);
    const std::string scene_path = fuzz::write_scratch_file("scene.json", text);
    const std::string base_dir = std::filesystem::path(scene_path).parent_path().string();
    fuzz::accept_input_errors([&] { parse_scene(text, scene_path, base_dir); });
    return 0;
}
