// Fuzz target: the fem-explicit case-file reader (explicit_case/case_file.hpp over
// input/toml_input.hpp). Any text must end in an ExplicitCase or an InputError.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "core/error.hpp"
#include "core/memory.hpp"
#include "explicit_case/case_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const bool limited = (fem::set_memory_limit(256u << 20), true);  // mesh requests above 256 MB are refused
    (void)limited;
    try {
        fem::explicit_case::parse_case(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.toml");
    } catch (const fem::InputError& e) {
        if (std::getenv("FEM_FUZZ_VERBOSE")) std::fprintf(stderr, "refused: %s\n", e.what());  // for triage
    }
    return 0;
}
