// Fuzz target: the Abaqus/CalculiX deck reader (deck/deck.hpp over input/numbers.hpp). Any text must
// end in a Deck or an InputError (*INCLUDE paths resolve under the corpus folder).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string_view>

#include "check/build_paths.hpp"
#include "core/error.hpp"
#include "deck/deck.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    // Relative paths in the input resolve under the corpus folder (check/build_paths.hpp: no
    // clone's own path is compiled into this file, so ccache reuses it in another clone).
    static const std::filesystem::path corpus_dir = fem::check::source_dir() / "tests/fuzz/corpus/deck";
    try {
        fem::deck::parse_deck(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.inp", corpus_dir);
    } catch (const fem::InputError& e) {
        if (std::getenv("FEM_FUZZ_VERBOSE")) std::fprintf(stderr, "refused: %s\n", e.what());  // for triage
    }
    return 0;
}
