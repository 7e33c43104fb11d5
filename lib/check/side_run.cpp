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

void SideRun::at_most_operands(std::size_t most, std::string_view names) const {
    if (operands.size() <= most) return;
    if (most == 0) throw InputError(fmt::format("command line: {} takes no operand, got '{}'", mode, operands.front()));
    throw InputError(fmt::format("command line: {} takes at most {} operand{}{}, got {}: '{}'", mode, most, most > 1 ? "s" : "",
                                 names.empty() ? "" : fmt::format(" ({})", names), operands.size(), operands[most]));
}

SideRun read_side_run(int argc, char** argv, std::string_view study, std::string_view usage,
                      const std::vector<std::string_view>& modes, const std::vector<SideRunOption>& options,
                      const std::function<void(input::Arguments&)>& read_option) {
    std::vector<std::string_view> known(modes);
    for (const SideRunOption& o : options) known.push_back(o.name);
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
        } else if (std::ranges::find(options, option, &SideRunOption::name) != options.end()) {
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
    for (const std::string& given : side.options) {
        const std::string_view belongs = std::ranges::find(options, given, &SideRunOption::name)->mode;
        if (side.mode != belongs)
            throw InputError(fmt::format("command line: {} is an option of the {} side run{} (see --help)", given, belongs,
                                         side.mode.empty() ? "" : ", not of " + side.mode));
    }
    if (!side.mode.empty() && quiet) Progress::set_quiet(true);
    return side;
}

}  // namespace fem::check
