// fem-modal: natural frequencies and mode shapes of a Gmsh mesh (thesis Sec 2.4).
//   fem-modal case.toml [--output DIR] [--modes N]
// The case file (see lib/modal/case.hpp) names the mesh, materials per part, supports and couplings
// by physical group. Writes DIR/frequencies.csv, DIR/modes.h5 and DIR/modes.pvd (one VTU per mode).
#include <iostream>
#include <string>

#include "core/error.hpp"
#include "core/program.hpp"
#include "modal/case.hpp"

int main(int argc, char** argv) {
    return fem::run_program("fem-modal", [&]() {
        std::string case_file, output;
        int modes = 0;
        for (int i = 1; i < argc; ++i) {
            const std::string arg = argv[i];
            if (arg == "--help" || arg == "-h") {
                std::cout << "usage: fem-modal case.toml [--output DIR] [--modes N]\n";
                return 0;
            }
            if (arg == "--output" || arg == "--modes") {
                if (i + 1 >= argc) throw fem::InputError("option '" + arg + "' needs a value");
                if (arg == "--output") output = argv[++i];
                else {
                    try {
                        modes = std::stoi(argv[++i]);
                    } catch (const std::exception&) {
                        throw fem::InputError(std::string("--modes needs a number, got '") + argv[i] + "'");
                    }
                }
            } else if (case_file.empty()) {
                case_file = arg;
            } else {
                throw fem::InputError("unexpected argument '" + arg + "' (usage: fem-modal case.toml [--output DIR] [--modes N])");
            }
        }
        if (case_file.empty()) throw fem::InputError("no case file given (usage: fem-modal case.toml [--output DIR] [--modes N])");
        fem::modal::ModalCase c = fem::modal::read_modal_case(case_file);
        if (!output.empty()) c.output = output;
        if (modes > 0) c.options.modes = modes;
        std::cout << fem::modal::run_modal_case(c);
        return 0;
    });
}
