// fem-modal: natural frequencies and mode shapes of a Gmsh mesh (thesis Sec 2.4).
//   fem-modal case.toml [--output DIR] [--modes N]
// The case file (see lib/modal/case.hpp) names the mesh, materials per part, supports and couplings
// by physical group. Writes DIR/frequencies.csv, DIR/modes.h5 and DIR/modes.pvd (one VTU per mode).
#include <iostream>
#include <string>

#include "cli/programs.hpp"
#include "core/error.hpp"
#include "core/program.hpp"
#include "input/arguments.hpp"
#include "modal/case.hpp"

namespace fem::cli {

int modal_program(int argc, char** argv) {
    return fem::run_program("fem-modal", [&]() {
        const char* usage = "usage: fem-modal case.toml [--output DIR] [--modes N]";
        std::string case_file, output;
        int modes = 0;
        fem::input::Arguments args(argc, argv, {"--help", "--output", "--modes"});
        while (args.next()) {
            if (args.is("--help") || args.is("-h")) {
                std::cout << usage << "\n";
                return 0;
            }
            if (args.is("--output")) output = args.value();
            else if (args.is("--modes")) modes = args.integer<int>({.min = 1});
            else args.positional(case_file);
        }
        if (case_file.empty()) throw fem::InputError(std::string("no case file given (") + usage + ")");
        fem::modal::ModalCase c = fem::modal::read_modal_case(case_file);
        if (!output.empty()) c.output = output;
        if (modes > 0) c.options.modes = modes;
        std::cout << fem::modal::run_modal_case(c);
        return 0;
    });
}

}  // namespace fem::cli
