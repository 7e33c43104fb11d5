#include "cli/case_command_line.hpp"

#include <iostream>

#include "core/error.hpp"
#include "input/arguments.hpp"

namespace fem::cli {

std::optional<CaseCommandLine> read_case_command_line(int argc, char** argv, std::string_view usage, std::string_view help,
                                                      bool explicit_run) {
    CaseCommandLine c;
    input::Arguments args(argc, argv,
                          explicit_run ? std::initializer_list<std::string_view>{"--help", "--output", "--quiet", "--end-time", "--resume", "--set"}
                                       : std::initializer_list<std::string_view>{"--help", "--output", "--quiet"});
    while (args.next()) {
        if (args.is("--help") || args.is("-h")) {
            std::cout << "usage: " << usage << "\n" << help;
            return std::nullopt;
        } else if (args.is("--output")) {
            c.output = args.value();
        } else if (explicit_run && args.is("--end-time")) {
            c.end_time = args.real(input::Range::positive());
        } else if (explicit_run && args.is("--set")) {
            const std::string assignment = args.value();
            c.settings.push_back(input::Setting::parse(assignment, "--set " + assignment));
        } else if (explicit_run && args.is("--resume")) {
            c.resume = true;
        } else if (args.is("--quiet")) {
            c.quiet = true;
        } else {
            args.positional(c.case_path);
        }
    }
    if (c.case_path.empty()) throw InputError("no case file given (usage: " + std::string(usage) + ")");
    return c;
}

}  // namespace fem::cli
