// fem-sweep: a design sweep of a fem-explicit case file; see sweep_program.cpp.
#include "cli/programs.hpp"

int main(int argc, char** argv) { return fem::cli::sweep_program(argc, argv); }
