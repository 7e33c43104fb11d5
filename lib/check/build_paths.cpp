#include "check/build_paths.hpp"

namespace fem::check {

std::filesystem::path source_dir() { return FEM_SOURCE_DIR; }
std::filesystem::path bin_dir() { return FEM_BIN_DIR; }
std::filesystem::path results_dir() { return FEM_RESULTS_DIR; }

}  // namespace fem::check
