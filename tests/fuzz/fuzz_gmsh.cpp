// Fuzz target: the Gmsh .msh reader (mesh/gmsh.hpp: Gmsh's own parser, then our conversion and
// validation). Any input must end in a Mesh or an InputError: no crash, no sanitizer report, no leak.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "core/error.hpp"
#include "mesh/gmsh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    // One Gmsh session for the whole run (initializing Gmsh per input would dominate the time).
    static fem::GmshSession session;
    static const std::filesystem::path file =
        std::filesystem::temp_directory_path() / ("fem_fuzz_gmsh_" + std::to_string(::getpid()) + ".msh");
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    try {
        fem::read_gmsh(file);
    } catch (const fem::InputError& e) {
        if (std::getenv("FEM_FUZZ_VERBOSE")) std::fprintf(stderr, "refused: %s\n", e.what());  // for triage
    }
    return 0;
}
