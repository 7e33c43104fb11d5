// fem-explicit: the explicit solver (thesis Sec 2.3, Ch 4) on a TOML case file
// (lib/explicit_case/case_file.hpp; every key: lib/explicit_case/CASE_FILE.md).
//
//   fem-explicit case.toml [--output DIR] [--end-time T] [--quiet]
//
// --end-time T ends the run at T seconds instead of [control] end_time (a short look at a long case,
// e.g. the CTest smoke runs of the Ch 4 studies' case files; phases starting at or after T are left out).
// Writes DIR/summary.txt (run summary: element-cycles/s, timing table, energy balance, health),
// run.json, histories.h5 and histories.dat / energies.dat, VTU/PVD when asked, restart dumps when
// asked, as one io::RunFolder set. Progress on stderr (--quiet: none); Ctrl-C stops after the
// current cycle, writes the state reached marked partial and exits 130.
#include <iostream>
#include <string>

#include "cli/case_command_line.hpp"
#include "cli/programs.hpp"
#include "core/error.hpp"
#include "core/program.hpp"
#include "core/progress.hpp"
#include "explicit_case/case_file.hpp"

namespace fem::cli {

int explicit_program(int argc, char** argv) {
    return fem::run_program("fem-explicit", [&]() {
        const auto line = read_case_command_line(
            argc, argv, "fem-explicit CASE.toml [--output DIR] [--end-time T] [--quiet]",
            "Explicit dynamics (central differences, penalty contact, rigid parts) of a TOML case\n"
            "file; every key: lib/explicit_case/CASE_FILE.md. Writes summary.txt, run.json,\n"
            "histories.h5, histories.dat, energies.dat (and VTU/PVD, restart dumps) to DIR.\n"
            "--end-time T: end the run at T seconds instead of [control] end_time.\n", true);
        if (!line) return 0;  // --help
        auto c = fem::explicit_case::read_case(line->case_path);
        if (!line->output.empty()) c.output.folder = line->output;
        if (line->end_time) fem::explicit_case::cut_at(c, *line->end_time);
        std::cout << fem::explicit_case::run_case(c, line->quiet) << std::flush;
        return 0;
    });
}

}  // namespace fem::cli
