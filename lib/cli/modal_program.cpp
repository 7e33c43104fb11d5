// fem-modal: natural frequencies and mode shapes of a Gmsh mesh or a CalculiX/Abaqus deck (thesis
// Sec 2.4).
//   fem-modal case.toml [--output DIR] [--modes N] [--shapes N] [--export-deck model.inp]
//   fem-modal model.inp [--output DIR] [--modes N] [--shapes N]
// The case file (see lib/modal/case.hpp) names the mesh, materials per part, supports and couplings
// by physical group; a deck (lib/deck/deck.hpp) is run as ccx runs its *FREQUENCY step and the
// eigenvalue table is printed in the layout of ccx's .dat. Writes DIR/frequencies.csv, DIR/modes.h5
// and, for the first N modes (--shapes; all by default, 0 = frequencies only), DIR/modes.pvd with
// one VTU per mode. --export-deck writes the case's model as a deck for ccx instead of solving.
#include <cctype>
#include <filesystem>
#include <iostream>
#include <string>

#include "cli/programs.hpp"
#include "core/error.hpp"
#include "core/program.hpp"
#include "input/arguments.hpp"
#include "modal/case.hpp"
#include "modal/deck_run.hpp"

namespace fem::cli {

int modal_program(int argc, char** argv) {
    return fem::run_program("fem-modal", [&]() {
        const char* usage =
            "usage: fem-modal case.toml|model.inp [--output DIR] [--modes N] [--shapes N] [--export-deck model.inp]";
        std::string input_file, output, export_deck;
        int modes = 0, shapes = -1;
        fem::input::Arguments args(argc, argv, {"--help", "--output", "--modes", "--shapes", "--export-deck"});
        while (args.next()) {
            if (args.is("--help") || args.is("-h")) {
                std::cout << usage << "\n";
                return 0;
            }
            if (args.is("--output")) output = args.value();
            else if (args.is("--modes")) modes = args.integer<int>({.min = 1});
            else if (args.is("--shapes")) shapes = args.integer<int>({.min = 0});
            else if (args.is("--export-deck")) export_deck = args.value();
            else args.positional(input_file);
        }
        if (input_file.empty()) throw fem::InputError(std::string("no case file or deck given (") + usage + ")");
        std::string ext = std::filesystem::path(input_file).extension().string();
        for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        if (ext == ".inp") {
            if (!export_deck.empty()) throw fem::InputError("command line: --export-deck: the input is a deck already");
            std::cout << fem::modal::run_deck(input_file, {.output = output, .modes = modes, .shapes = shapes});
            return 0;
        }
        fem::modal::ModalCase c = fem::modal::read_modal_case(input_file);
        if (!output.empty()) c.output = output;
        if (modes > 0) c.options.modes = modes;
        if (shapes >= 0) c.shapes = shapes;
        if (!export_deck.empty()) {
            if (!output.empty() || shapes >= 0)
                throw fem::InputError("command line: --export-deck writes the deck only; --output and --shapes have no effect with it");
            std::cout << fem::modal::export_case_deck(c, export_deck);
            return 0;
        }
        std::cout << fem::modal::run_modal_case(c);
        return 0;
    });
}

}  // namespace fem::cli
