// fem-report: writes figures/REPORT.md and figures/REPORT.html from every study's checks.json.
//   fem-report --reference reference --results build/results --figures figures
#include <iostream>
#include <string>

#include "check/report.hpp"
#include "core/error.hpp"
#include "core/program.hpp"

int main(int argc, char** argv) {
    return fem::run_program("fem-report", [&]() {
        fem::check::ReportInputs in{"reference", "build/results", "figures"};
        for (int i = 1; i < argc; ++i) {
            const std::string arg = argv[i];
            if (i + 1 >= argc) throw fem::InputError("option '" + arg + "' needs a value (see --help)");
            if (arg == "--reference") in.reference_dir = argv[++i];
            else if (arg == "--results") in.results_dir = argv[++i];
            else if (arg == "--figures") in.figures_dir = argv[++i];
            else throw fem::InputError("unknown option '" + arg + "'; use --reference DIR --results DIR --figures DIR");
        }
        const int failed = fem::check::write_report(in);
        std::cout << "report: " << (in.figures_dir / "REPORT.md").string() << " and REPORT.html ("
                  << failed << " failed checks)\n";
        return 0;  // the report is written whatever the verdicts; studies carry the exit status
    });
}
