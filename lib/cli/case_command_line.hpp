#pragma once
// The command line shared by the case-file programs: `fem-<name> CASE.toml [--output DIR] [--quiet]`
// (fem-topopt, fem-explicit), read through input/arguments.hpp (unknown options with "did you mean",
// a second case file refused).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "input/toml_input.hpp"

namespace fem::cli {

struct CaseCommandLine {
    std::string case_path, output;  // output empty: the case file's own folder
    bool quiet = false;
    std::optional<double> end_time;  // --end-time T (programs that take it): end the run at T [s]
    bool resume = false;             // --resume (fem-explicit): continue the run killed in the output folder
    /// --set KEY=VALUE (fem-explicit, repeatable): values of the case file replaced before it is read.
    std::vector<input::Setting> settings;
};

/// Reads the arguments; prints `help` and returns nullopt for --help / -h; InputError "no case file
/// given (usage: <usage>)" when there is none. explicit_run: --end-time T (> 0), --resume and
/// --set KEY=VALUE are options too (fem-explicit).
std::optional<CaseCommandLine> read_case_command_line(int argc, char** argv, std::string_view usage, std::string_view help,
                                                      bool explicit_run = false);

}  // namespace fem::cli
