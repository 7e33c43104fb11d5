// fem-report: writes figures/REPORT.md and figures/REPORT.html from every study's checks.json.
//   fem-report --reference reference --results build/results --figures figures
#include <iostream>
#include <string>

#include "check/report.hpp"
#include "core/program.hpp"
#include "input/arguments.hpp"

int main(int argc, char** argv) {
    return fem::run_program("fem-report", [&]() {
        fem::check::ReportInputs in{"reference", "build/results", "figures"};
        fem::input::Arguments args(argc, argv, {"--reference", "--results", "--figures", "--help", "-h"});
        while (args.next()) {
            if (args.is("--reference")) in.reference_dir = args.value();
            else if (args.is("--results")) in.results_dir = args.value();
            else if (args.is("--figures")) in.figures_dir = args.value();
            else if (args.is("--help") || args.is("-h")) {
                std::cout << "usage: fem-report [--reference DIR] [--results DIR] [--figures DIR]\n"
                             "  Writes DIR/REPORT.md and REPORT.html (--figures, default figures) from every study's\n"
                             "  checks.json and runs.json under --results (default build/results) and the reference\n"
                             "  files under --reference (default reference).\n";
                return 0;
            } else args.unknown();
        }
        const int failed = fem::check::write_report(in);
        std::cout << "report: " << (in.figures_dir / "REPORT.md").string() << " and REPORT.html ("
                  << failed << " failed checks)\n";
        return 0;  // the report is written whatever the verdicts; studies carry the exit status
    });
}
