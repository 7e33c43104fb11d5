// check::side_run_folder: a study's side run (e.g. chicken_shackling --grasp 4) writes under the
// build's results folder whatever directory it is started from (the bug it guards against: --grasp
// run from the project root left grasp-case-4.pvd, its VTU and surface files in the project root).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "check/side_run.hpp"
#include "core/error.hpp"

namespace fs = std::filesystem;
using fem::check::side_run_folder;

namespace {

/// Runs the test body in a scratch directory and goes back afterwards.
struct InScratchDirectory {
    fs::path before = fs::current_path(), scratch;
    InScratchDirectory() {
        scratch = fs::temp_directory_path() / ("fem_side_run_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                                               "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(scratch);
        fs::current_path(scratch);
    }
    ~InScratchDirectory() {
        fs::current_path(before);
        fs::remove_all(scratch);
    }
};

std::vector<char*> arguments(std::vector<std::string>& words) {
    std::vector<char*> args;
    for (auto& w : words) args.push_back(w.data());
    return args;
}

}  // namespace

TEST(SideRunFolder, IsUnderTheStudysResultsFolderWhateverTheCurrentDirectory) {
    std::vector<std::string> words = {"chicken_shackling", "--grasp", "4", "0.12"};
    const auto args = arguments(words);
    const fs::path from_here = side_run_folder("chicken_shackling", "grasp-case-4", args);
    InScratchDirectory in;
    const fs::path from_scratch = side_run_folder("chicken_shackling", "grasp-case-4", args);
    EXPECT_TRUE(from_scratch.is_absolute());
    EXPECT_EQ(from_scratch, from_here);  // not relative to the current directory
    EXPECT_EQ(from_scratch.filename(), "grasp-case-4");
    EXPECT_EQ(from_scratch.parent_path().filename(), "chicken_shackling");
    EXPECT_EQ(from_scratch.parent_path().parent_path().filename(), "results");
    // Not the current directory, nor anything in it.
    const fs::path rel = fs::relative(from_scratch, fs::current_path());
    EXPECT_TRUE(rel.empty() || *rel.begin() == "..") << from_scratch << " lies in the current directory " << fs::current_path();
}

TEST(SideRunFolder, ResultsOptionChoosesTheFolderRelativeToTheCurrentDirectory) {
    InScratchDirectory in;
    std::vector<std::string> words = {"chicken_shackling", "--shackle", "rotating", "--results", "out/rot"};
    EXPECT_EQ(side_run_folder("chicken_shackling", "shackle-rotating", arguments(words)), fs::current_path() / "out" / "rot");
    std::vector<std::string> absolute = {"chicken_shackling", "--results", "/tmp/somewhere", "--grasp", "2"};
    EXPECT_EQ(side_run_folder("chicken_shackling", "grasp-case-2", arguments(absolute)), fs::path("/tmp/somewhere"));
    std::vector<std::string> missing = {"chicken_shackling", "--grasp", "4", "--results"};
    EXPECT_THROW(side_run_folder("chicken_shackling", "grasp-case-4", arguments(missing)), fem::InputError);
}
