#include "check/side_run.hpp"

#include <algorithm>
#include <cstdlib>
#include <iostream>

#include <fmt/format.h>

#include "check/build_paths.hpp"
#include "check/study.hpp"
#include "core/error.hpp"
#include "core/progress.hpp"
#include "input/arguments.hpp"

namespace fem::check {

std::filesystem::path side_run_folder(std::string_view study, std::string_view run, const std::filesystem::path& results_option) {
    if (!results_option.empty()) return std::filesystem::absolute(results_option);
    return std::filesystem::absolute(results_dir() / study / run);
}

void SideRun::refuse_results() const {
    if (!results.empty())
        throw InputError(fmt::format("command line: {} prints its findings and writes no files: --results has no effect", mode));
}

SideRun read_side_run(int argc, char** argv, std::string_view study, std::string_view usage,
                      const std::vector<std::string_view>& modes, const std::vector<std::string_view>& options,
                      const std::function<void(input::Arguments&)>& read_option) {
    std::vector<std::string_view> known(modes);
    known.insert(known.end(), options.begin(), options.end());
    known.insert(known.end(), study_options().begin(), study_options().end());
    input::Arguments args(argc, argv, known);
    SideRun side;
    bool help = false, quiet = false;
    std::vector<std::string> study_only;  // options of the study run given
    while (args.next()) {
        const std::string option = args.current();
        if (std::ranges::find(modes, option) != modes.end()) {
            if (!side.mode.empty())
                throw InputError(fmt::format("command line: one side run at a time, got {} and {} (see --help)", side.mode, option));
            side.mode = option;
            side.operands = args.operands();
        } else if (std::ranges::find(options, option) != options.end()) {
            if (read_option) read_option(args);
            side.options.push_back(option);
        } else if (option == "--results") {
            side.results = args.value();
        } else if (option == "--quiet") {
            quiet = true;
        } else if (option == "--help" || option == "-h") {
            help = true;
        } else if (option == "--figures" || option == "--reference" || option == "--jobs") {
            args.value();  // the study run reads it
            study_only.push_back(option);
        } else if (option == "--full") {
            study_only.push_back(option);
        } else {
            args.unknown();
        }
    }
    if (help) {
        print_study_usage(std::string(study));
        std::cout << usage;
        std::exit(0);
    }
    if (!side.mode.empty() && !study_only.empty())
        throw InputError(fmt::format("command line: {} is an option of the study run, not of the {} side run (see --help)",
                                     study_only.front(), side.mode));
    if (!side.mode.empty() && quiet) Progress::set_quiet(true);
    return side;
}

}  // namespace fem::check
