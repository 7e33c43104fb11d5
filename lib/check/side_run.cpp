#include "check/side_run.hpp"

#include "check/build_paths.hpp"

namespace fem::check {

std::filesystem::path side_run_folder(std::string_view study, std::string_view run, const std::filesystem::path& results_option) {
    if (!results_option.empty()) return std::filesystem::absolute(results_option);
    return std::filesystem::absolute(results_dir() / study / run);
}

}  // namespace fem::check
