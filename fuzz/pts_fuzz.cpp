// Fuzz target: the `.pts` sensor file reader (scene key `sensors.file`), reached through a
// valid scene that names the fuzzed file.

#include <cstdint>
#include <string>

#include "core/scene_io.h"

#include "fuzz_support.h"

namespace {

// One emitting square over a floor: the smallest scene that passes validation.
constexpr const char* k_scene = R"({
  "units": "m",
  "materials": {"white": {"reflectance": 0.5}, "lamp": {"emission": 10}},
  "polygons": [
    {"material": "white", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]},
    {"material": "lamp", "vertices": [[0, 0, 1], [0, 1, 1], [1, 1, 1], [1, 0, 1]]}
  ],
  "sensors": {"file": "sensors.pts"}
})";

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace penumbra;
    fuzz::write_scratch_file("sensors.pts", {reinterpret_cast<const char*>(data), size});
    const std::string scene = fuzz::write_scratch_file("scene.json", k_scene);
    fuzz::accept_input_errors([&] { load_scene(scene); });
    return 0;
}
