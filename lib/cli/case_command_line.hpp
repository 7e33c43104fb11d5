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
};

/// Reads the arguments; prints `help` and returns nullopt for --help / -h; InputError "no case file
/// given (usage: <usage>)" when there is none. with_end_time: --end-time T (> 0) is an option too.
std::optional<CaseCommandLine> read_case_command_line(int argc, char** argv, std::string_view usage, std::string_view help,
                                                      bool with_end_time = false);

}  // namespace fem::cli
