// Fuzz target: the EPW weather file reader (annual/epw.h), on the file's text as given.

#include <cstdint>
#include <string_view>

#include "annual/epw.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace penumbra;
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    fuzz::accept_input_errors([&] { annual::parse_epw(text, "fuzz.epw"); });
    return 0;
}
