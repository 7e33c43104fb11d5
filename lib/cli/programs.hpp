#pragma once
// The command-line programs as functions: each fem-<name> program's main() calls <name>_program,
// and tests call them in-process (tests/bad_input runs its whole corpus of malformed inputs this
// way, in one process, instead of paying a program start per case). They return the exit status
// (fem::run_program: 0 done, 2 input error, 3 solver error, 4 other) and print what the program
// prints.
namespace fem::cli {

/// fem-modal case.toml|model.inp [--output DIR] [--modes N] [--shapes N] [--export-deck F]  (lib/cli/modal_program.cpp)
int modal_program(int argc, char** argv);
/// fem-explicit case.toml [--set KEY=VALUE ...] [--output DIR] [--quiet]  (lib/cli/explicit_program.cpp)
int explicit_program(int argc, char** argv);
/// fem-sweep sweep.toml [--output DIR] [--jobs N] [--resume] [--quiet]  (lib/cli/sweep_program.cpp)
int sweep_program(int argc, char** argv);
/// fem-topopt case.toml [--output DIR] [--quiet]  (lib/cli/topopt_program.cpp)
int topopt_program(int argc, char** argv);

}  // namespace fem::cli
