#pragma once
// Runs a study's gnuplot script. Scripts receive their folders as string variables, so the same
// .gp file draws into figures/ for `make all` and into build/figures for CTest:
//   gnuplot -e "results='build/results/<study>'; figures='figures'; term='svg'; ext='svg'" studies/<study>/<study>.gp
#include <filesystem>
#include <map>
#include <string>
#include <string_view>

namespace fem::io {

/// `s` as a gnuplot string constant between single quotes ('' stands for a quote inside).
std::string gnuplot_string(std::string_view s);

/// Runs gnuplot on `script` with the given string variables (any text: quoted for gnuplot and the
/// shell); throws SolverError with gnuplot's
/// output when gnuplot fails, InputError when the script does not exist.
void run_gnuplot(const std::filesystem::path& script, const std::map<std::string, std::string>& variables);

}  // namespace fem::io
