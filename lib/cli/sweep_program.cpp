// fem-sweep: a design study over a fem-explicit case file (lib/explicit_case/sweep.hpp; the format:
// lib/explicit_case/CASE_FILE.md, "Sweeps").
//
//   fem-sweep sweep.toml [--output DIR] [--jobs N] [--resume] [--list] [--quiet]
//   mpirun -n 4 build/bin/mpi/fem-sweep sweep.toml      # the cases across machines (README.md)
//
// Runs every case of the sweep (the case file with the [[parameter]] values set) into DIR/case-<k>/,
// up to N at once (default: FEM_JOBS, else the cores; each case gets its share of the cores'
// OpenMP threads), and writes DIR/sweep.csv, sweep.dat, sweep.json and summary.txt: one row per case
// with its values, status, the solver's numbers and the [[result]]s; and a figure per result,
// DIR/sweep-<result>.svg (gnuplot, from DIR/sweep.gp). --resume keeps the cases a
// killed or earlier run of the same sweep completed (same settings) and runs the others; with
// every case completed it only tabulates again (a changed [[result]] list). --list reads every case
// and lists them (values, folders) without running anything.
// Exit status: 0 every case ran healthy; 1 some case was unhealthy, unstable or could not be built
// (the table says which and why); 2 bad input (a parameter's key or value the case refuses: nothing
// runs); 4 other errors; 130 Ctrl-C (the completed cases are kept for --resume).
#include <iostream>
#include <string>

#include "check/cases.hpp"
#include "cli/programs.hpp"
#include "core/error.hpp"
#include "core/program.hpp"
#include "explicit_case/sweep.hpp"
#include "input/arguments.hpp"

namespace fem::cli {

int sweep_program(int argc, char** argv) {
    return fem::run_program("fem-sweep", [&]() {
        constexpr const char* usage = "fem-sweep SWEEP.toml [--output DIR] [--jobs N] [--resume] [--list] [--quiet]";
        std::string file, output;
        explicit_case::SweepOptions options;
        input::Arguments args(argc, argv, {"--help", "--output", "--jobs", "--resume", "--list", "--quiet"});
        while (args.next()) {
            if (args.is("--help") || args.is("-h")) {
                std::cout << "usage: " << usage << "\n"
                          << "A design sweep of a fem-explicit case file: the case run once per combination of the\n"
                             "[[parameter]] values of SWEEP.toml (lib/explicit_case/CASE_FILE.md, \"Sweeps\"), each into\n"
                             "DIR/case-<k>/, and one table of every case's values, status, solver numbers and\n"
                             "[[result]]s: DIR/sweep.csv, sweep.dat, sweep.json, summary.txt; a figure per result,\n"
                             "DIR/sweep-<result>.svg (gnuplot, from DIR/sweep.gp).\n"
                             "--output DIR: instead of the sweep file's folder key (default <stem>_results beside it).\n"
                             "--jobs N: cases at once (default FEM_JOBS, else the cores).\n"
                             "--resume: keep the cases an earlier run of the same sweep completed; run the others.\n"
                             "--list: read every case and list the cases (values, folders); run nothing.\n"
                             "Under mpirun (build/bin/mpi/fem-sweep) the cases are dealt to the ranks.\n";
                return 0;
            } else if (args.is("--output")) {
                output = args.value();
            } else if (args.is("--jobs")) {
                options.jobs = args.integer<int>({.min = 1});
            } else if (args.is("--resume")) {
                options.resume = true;
            } else if (args.is("--list")) {
                options.list = true;
            } else if (args.is("--quiet")) {
                options.quiet = true;
            } else {
                args.positional(file);
            }
        }
        if (file.empty()) throw InputError(std::string("no sweep file given (usage: ") + usage + ")");
        check::detail::share_cores_among_local_ranks();
        explicit_case::Sweep sweep = explicit_case::read_sweep(file);
        if (!output.empty()) sweep.folder = output;
        const explicit_case::SweepOutcome outcome = explicit_case::run_sweep(sweep, options);
        if (check::ranks().rank() == 0) std::cout << outcome.table << std::flush;
        return options.list || outcome.all_ok() ? 0 : 1;
    });
}

}  // namespace fem::cli
