// fem-explicit: explicit dynamics of a TOML case file; see explicit_program.cpp.
#include "cli/programs.hpp"

int main(int argc, char** argv) { return fem::cli::explicit_program(argc, argv); }
