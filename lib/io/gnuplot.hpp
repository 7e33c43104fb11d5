#pragma once
// Runs a study's gnuplot script. Scripts receive their folders as string variables, so the same
// .gp file draws into figures/ for `make all` and into build/figures for CTest:
//   gnuplot -e "results='build/results/<study>'; figures='figures'; term='svg'; ext='svg'" studies/<study>/<study>.gp
#include <filesystem>
#include <map>
#include <string>

namespace fem::io {

/// Runs gnuplot on `script` with the given string variables; throws SolverError with gnuplot's
/// output when gnuplot fails, InputError when the script does not exist.
void run_gnuplot(const std::filesystem::path& script, const std::map<std::string, std::string>& variables);

}  // namespace fem::io
