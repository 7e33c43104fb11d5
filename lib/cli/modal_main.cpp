// fem-modal: natural frequencies and mode shapes of a Gmsh mesh (thesis Sec 2.4); see modal_program.cpp.
#include "cli/programs.hpp"

int main(int argc, char** argv) { return fem::cli::modal_program(argc, argv); }
