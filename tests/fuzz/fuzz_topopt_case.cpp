// Fuzz target: the fem-topopt case-file reader (topopt/case_file.hpp), which also builds the mesh,
// the model and checks the filter. Any text must end in a Case or an InputError. A memory budget of
// 256 MB keeps a fuzzed `elements = [2000, 2000]` from building a 4-million-element model (it is
// refused as it would be on a small machine).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "core/error.hpp"
#include "core/memory.hpp"
#include "topopt/case_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const bool limited = (fem::set_memory_limit(256u << 20), true);
    (void)limited;
    try {
        fem::topopt::parse_case(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.toml", FEM_FUZZ_BASE);
    } catch (const fem::InputError& e) {
        if (std::getenv("FEM_FUZZ_VERBOSE")) std::fprintf(stderr, "refused: %s\n", e.what());  // for triage
    }
    return 0;
}
