// Fuzz target: the solver state reader (`--reuse`, solver/src/state/solver_state.cpp). The
// input's last 8 bytes are replaced by the checksum of the rest: a random change would
// otherwise only ever reach the checksum test, never the checks of sizes and indices behind it.

#include <cstdint>
#include <cstring>
#include <string>

#include "solver/solver.h"
#include "state/solver_state.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace penumbra;
    std::string bytes(reinterpret_cast<const char*>(data), size);
    if (bytes.size() >= sizeof(std::uint64_t)) {
        const std::size_t payload = bytes.size() - sizeof(std::uint64_t);
        const std::uint64_t sum = solver::state_checksum({bytes.data(), payload});
        std::memcpy(bytes.data() + payload, &sum, sizeof(sum));
    }
    const std::string path = fuzz::write_scratch_file("solver_state.bin", bytes);
    fuzz::accept_input_errors([&] { solver::read_hierarchical_state(path); });
    return 0;
}
