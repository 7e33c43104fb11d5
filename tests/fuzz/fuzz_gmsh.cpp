// Fuzz target: the Gmsh .msh reader (mesh/gmsh.hpp: Gmsh's own parser in the reader process, then
// our conversion and validation here). Any input must end in a Mesh or an InputError: no crash, no
// sanitizer report, no leak. (A crash inside libgmsh is the reader process's, which read_gmsh turns
// into an InputError; libgmsh is not instrumented, so coverage is that of our code.)
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
    // One Gmsh session for the whole run: read_gmsh's reader process is a fork of this one and
    // starts with Gmsh initialized (a new reader, after a crash or an exception in Gmsh, would
    // otherwise initialize it again).
    static fem::GmshSession session;
    // A read Gmsh spends more than 0.25 s on (at most 8 kB: `make fuzz` -max_len) is refused: a longer
    // limit costs the run its time on the many inputs with a huge count that Gmsh loops over (121 of
    // 4958 inputs in 180 s, each costing the whole limit). Measured under the fuzz build at load 12:
    // accepted reads took 8 ms on average, the slowest 120 ms; a slower one is refused, never
    // reported as a crash.
    static const bool limited = (fem::set_gmsh_read_time_limit(0.25, 10), true);
    (void)limited;
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
