#pragma once
// Where a study's side run writes. A side run is a mode of a study program other than the study run
// itself, run by hand (e.g. `chicken_shackling --grasp 4`, `chicken_shackling --shackle rotating`):
// its files belong under build/results/<study>/ like the study's (DESIGN.md, "Outputs"), never in
// whatever directory the program was started from.
//
//   const auto dir = check::side_run_folder("chicken_shackling", "grasp-case-4", results_option);
//   io::RunFolder out(dir, "chicken_shackling --grasp");   // one run's set, locked (io/run_folder.hpp)
//   ... write into out.staging() ...
//   out.commit();
//
// The folder is a sub-folder of the study's results folder: the study run's io::RunFolder lists its
// own files in its manifest and leaves every other file and folder alone, so neither run removes
// the other's files, and a side run never overwrites a file the study run judged (e.g. the study's
// shackle-rotating.dat).
#include <filesystem>
#include <string_view>

namespace fem::check {

/// The absolute folder of side run `run` of `study`: `results_option`, the DIR of the command line's
/// `--results DIR` (relative to the current directory, as a user types it), when it is not empty,
/// else <build>/results/<study>/<run> (the build's results folder, fixed when the program was built:
/// the same from any directory).
std::filesystem::path side_run_folder(std::string_view study, std::string_view run, const std::filesystem::path& results_option);

}  // namespace fem::check
