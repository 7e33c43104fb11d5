// fem-explicit: the explicit solver (thesis Sec 2.3, Ch 4) on a TOML case file
// (lib/explicit_case/case_file.hpp; every key: lib/explicit_case/CASE_FILE.md).
//
//   fem-explicit case.toml [--set KEY=VALUE ...] [--output DIR] [--end-time T] [--resume] [--quiet]
//
// --set KEY=VALUE replaces a value of the case file before it is read (repeatable; input::Setting):
// `--set part[finger].alpha=20 --set control.end_time=0.5`. A design study of many such runs is
// fem-sweep's (lib/explicit_case/sweep.hpp).
// --end-time T ends the run at T seconds instead of [control] end_time (a short look at a long case,
// e.g. the CTest smoke runs of the Ch 4 studies' case files; phases starting at or after T are left out).
// --resume continues a run that was killed (SIGKILL, a crash) in DIR from the last restart dump it
// wrote (restart_interval / restart_times), as LS-DYNA's `r=d3dump01`: the same command plus --resume.
// Writes DIR/summary.txt (run summary: element-cycles/s, timing table, energy balance, health),
// run.json, histories.h5 and histories.dat / energies.dat, VTU/PVD when asked, restart dumps when
// asked, as one io::RunFolder set. Progress on stderr (--quiet: none); Ctrl-C stops after the
// current cycle, writes the state reached marked partial and exits 130.
// Exit status: 0 a healthy run; 1 a run that finished but failed its health check (energy balance
// error > 1 % or hourglass energy > 10 % of internal, check/run_health.hpp: the limits a study fails
// a run for, with the same status 1), its files written for inspection, or whose case file holds a
// stale [[health_exemption]] (one no run needed, or naming no run); 2 bad input; 3 a run that
// went unstable (nothing written); 4 any other error; 130 Ctrl-C.
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
            argc, argv, "fem-explicit CASE.toml [--set KEY=VALUE ...] [--output DIR] [--end-time T] [--resume] [--quiet]",
            "Explicit dynamics (central differences, penalty contact, rigid parts) of a TOML case\n"
            "file; every key: lib/explicit_case/CASE_FILE.md. Writes summary.txt, run.json,\n"
            "histories.h5, histories.dat, energies.dat (and VTU/PVD, restart dumps) to DIR.\n"
            "--set KEY=VALUE: replace a value of the case file before it is read, e.g.\n"
            "  --set part[finger].alpha=20 (an [[part]] entry by name or index), --set control.end_time=0.5.\n"
            "--end-time T: end the run at T seconds instead of [control] end_time.\n"
            "--resume: continue the run killed in DIR from the last restart dump it wrote.\n", true);
        if (!line) return 0;  // --help
        auto c = fem::explicit_case::read_case(line->case_path, line->settings);
        if (!line->output.empty()) c.output.folder = line->output;
        if (line->end_time) fem::explicit_case::cut_at(c, *line->end_time);
        const auto outcome = fem::explicit_case::run_case(c, line->quiet, line->resume);
        std::cout << outcome.summary << std::flush;
        if (outcome.healthy()) return 0;
        for (const std::string& verdict : outcome.unhealthy) {  // "FAIL   run health <run>: ..."
            const auto at = verdict.find("run health ");
            std::cerr << "fem-explicit: run health failed: " << (at == std::string::npos ? verdict : verdict.substr(at + 11))
                      << '\n';
        }
        for (const std::string& problem : outcome.stale_exemptions) std::cerr << "fem-explicit: " << problem << '\n';
        if (!outcome.unhealthy.empty())
            std::cerr << "fem-explicit: the results are in " << c.output.folder.string()
                      << " for inspection, but are not to be relied on: energy that does not balance, or hourglass modes "
                         "carrying the deformation, say the discretization does not resolve the loading\n";
        return 1;
    });
}

}  // namespace fem::cli
