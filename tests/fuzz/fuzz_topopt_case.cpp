// Fuzz target: the fem-topopt case-file reader (topopt/case_file.hpp), which also builds the mesh,
// the model and checks the filter (no optimization is run). Any text must end in a Case or an
// InputError.
// A memory budget of 8 MB (require_memory: 5 kB per quad4, 17 kB per quad8 element) keeps the
// design domain at most ~1600 quad4 or ~470 quad8 elements: a larger grid is refused as it would be
// on a small machine, through the same check. The reader's paths (every key, every check, the
// refusal of a grid too large) are the same for a small grid as for a large one; only the loops over
// elements and nodes grow, and under AddressSanitizer they dominated: with 256 MB the fuzzer spent
// its time building grids of up to 50,000 elements (32 executions/s; README "make fuzz").
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string_view>

#include "check/build_paths.hpp"
#include "core/error.hpp"
#include "core/memory.hpp"
#include "topopt/case_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    // Relative paths in the input resolve under the corpus folder (check/build_paths.hpp: no
    // clone's own path is compiled into this file, so ccache reuses it in another clone).
    static const std::filesystem::path corpus_dir = fem::check::source_dir() / "tests/fuzz/corpus/topopt_case";
    static const bool limited = (fem::set_memory_limit(8u << 20), true);
    (void)limited;
    try {
        fem::topopt::parse_case(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.toml", corpus_dir);
    } catch (const fem::InputError& e) {
        if (std::getenv("FEM_FUZZ_VERBOSE")) std::fprintf(stderr, "refused: %s\n", e.what());  // for triage
    }
    return 0;
}
