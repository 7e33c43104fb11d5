// Fuzz target: the fem-modal case-file reader (modal/case.hpp over input/toml_input.hpp). Any text
// must end in a ModalCase or an InputError.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "core/error.hpp"
#include "modal/case.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        fem::modal::parse_modal_case(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.toml");
    } catch (const fem::InputError& e) {
        if (std::getenv("FEM_FUZZ_VERBOSE")) std::fprintf(stderr, "refused: %s\n", e.what());  // for triage
    }
    return 0;
}
