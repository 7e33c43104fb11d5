// fem-topopt: minimum-compliance topology optimization (thesis Sec 2.6); see topopt_program.cpp.
#include "cli/programs.hpp"

int main(int argc, char** argv) { return fem::cli::topopt_program(argc, argv); }
