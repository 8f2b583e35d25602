// Fuzz target: the Radiance scene importer (core/src/radiance/), reached through a scene whose
// `geometry` lists the fuzzed `.rad` file.

#include <cstdint>
#include <string>

#include "core/scene_io.h"

#include "fuzz_support.h"

namespace {

constexpr const char* k_scene = R"({"units": "m", "up": [0, 0, 1], "geometry": ["scene.rad"]})";

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace penumbra;
    fuzz::write_scratch_file("scene.rad", {reinterpret_cast<const char*>(data), size});
    const std::string scene = fuzz::write_scratch_file("scene.json", k_scene);
    fuzz::accept_input_errors([&] { load_scene(scene); });
    return 0;
}
