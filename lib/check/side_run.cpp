#include "check/side_run.hpp"

#include <string>

#include "check/build_paths.hpp"
#include "core/error.hpp"

namespace fem::check {

std::filesystem::path side_run_folder(std::string_view study, std::string_view run, std::span<char* const> args) {
    for (std::size_t i = 1; i < args.size(); ++i)
        if (std::string_view(args[i]) == "--results") {
            if (i + 1 >= args.size()) throw InputError("option --results needs a value");
            return std::filesystem::absolute(args[i + 1]);
        }
    return std::filesystem::absolute(results_dir() / study / run);
}

}  // namespace fem::check
