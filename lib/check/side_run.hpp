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
//
// The command line of a side run is read whole by read_side_run (strictly, as every command line:
// input/arguments.hpp): one mode with its operands, --results DIR, --quiet, --help, and options of
// the study's own modes; an option of the study run (--full, --jobs, ...) beside a side run, two
// side runs at once or an unknown option is an input error naming it.
//
//   const check::SideRun side = check::read_side_run(argc, argv, "portal_frame_modes", usage, {"--screw-search"});
//   if (side.mode.empty()) return check::run_study(...);   // the study run reads its own options
//   ... side_run_folder("portal_frame_modes", "screw-search", side.results) ...
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace fem::input {
class Arguments;
}

namespace fem::check {

/// A side run's command line.
struct SideRun {
    std::string mode;                   // the mode's option (e.g. "--grasp"); empty: the study run
    std::vector<std::string> operands;  // its operands (the arguments after it up to the next option)
    std::filesystem::path results;      // --results DIR; empty: side_run_folder's default
    std::vector<std::string> options;   // the study's own side-run options given (e.g. "--resume")
    /// For a side run that only prints: InputError when --results was given (it would have no effect).
    void refuse_results() const;
    /// InputError when the mode has more than `most` operands; `names` says what they are (e.g.
    /// "case, end time").
    void at_most_operands(std::size_t most, std::string_view names = {}) const;
};

/// A side-run option of a study (beyond the modes) and the mode it belongs to.
struct SideRunOption {
    std::string_view name, mode;
};

/// Reads the command line of study program `study`. `modes`: its side runs; `options`: the options of
/// its side runs beyond them, each read by `read_option` (given the Arguments at that option, to take
/// its value); one given without its mode is an input error naming both. Throws InputError as above. --help
/// prints the study's usage and `usage` (its side runs) and exits 0 (an unknown option or a bad value
/// before it is still an error); --quiet with a side run turns its progress lines off (Progress).
SideRun read_side_run(int argc, char** argv, std::string_view study, std::string_view usage,
                      const std::vector<std::string_view>& modes, const std::vector<SideRunOption>& options = {},
                      const std::function<void(input::Arguments&)>& read_option = {});

/// The absolute folder of side run `run` of `study`: `results_option`, the DIR of the command line's
/// `--results DIR` (relative to the current directory, as a user types it), when it is not empty,
/// else <build>/results/<study>/<run> (the build's results folder, fixed when the program was built:
/// the same from any directory).
std::filesystem::path side_run_folder(std::string_view study, std::string_view run, const std::filesystem::path& results_option);

}  // namespace fem::check
