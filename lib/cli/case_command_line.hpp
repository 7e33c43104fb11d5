#pragma once
// The command line shared by the case-file programs: `fem-<name> CASE.toml [--output DIR] [--quiet]`
// (fem-topopt, fem-explicit), read through input/arguments.hpp (unknown options with "did you mean",
// a second case file refused).
#include <optional>
#include <string>
#include <string_view>

namespace fem::cli {

struct CaseCommandLine {
    std::string case_path, output;  // output empty: the case file's own folder
    bool quiet = false;
    std::optional<double> end_time;  // --end-time T (programs that take it): end the run at T [s]
    bool resume = false;             // --resume (fem-explicit): continue the run killed in the output folder
};

/// Reads the arguments; prints `help` and returns nullopt for --help / -h; InputError "no case file
/// given (usage: <usage>)" when there is none. explicit_run: --end-time T (> 0) and --resume are
/// options too (fem-explicit).
std::optional<CaseCommandLine> read_case_command_line(int argc, char** argv, std::string_view usage, std::string_view help,
                                                      bool explicit_run = false);

}  // namespace fem::cli
