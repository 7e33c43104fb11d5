#pragma once
// Where this build tree's project sources, programs and results are: the project folder (reference
// files, meshes, case files, test corpora), build/bin and build/results. All are absolute paths
// fixed when the build is configured (lib/check/CMakeLists.txt). They are compiled into build_paths.cpp alone, so that no other
// translation unit carries a clone's own path: ccache then reuses every other object in a clone
// made under another path (CMakeLists.txt, fem_unity).
#include <filesystem>

namespace fem::check {

/// The project folder of this build (CMake's source directory).
std::filesystem::path source_dir();
/// build/bin of this build tree: the studies and the fem-* programs (tests run them from there).
std::filesystem::path bin_dir();
/// build/results of this build tree: each study writes into results_dir() / <study>.
std::filesystem::path results_dir();

}  // namespace fem::check
