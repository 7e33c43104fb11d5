// check::side_run_folder: a study's side run (e.g. chicken_shackling --grasp 4) writes under the
// build's results folder whatever directory it is started from (the bug it guards against: --grasp
// run from the project root left grasp-case-4.pvd, its VTU and surface files in the project root).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "check/side_run.hpp"

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

}  // namespace

TEST(SideRunFolder, IsUnderTheStudysResultsFolderWhateverTheCurrentDirectory) {
    const fs::path from_here = side_run_folder("chicken_shackling", "grasp-case-4", {});
    InScratchDirectory in;
    const fs::path from_scratch = side_run_folder("chicken_shackling", "grasp-case-4", {});
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
    EXPECT_EQ(side_run_folder("chicken_shackling", "shackle-rotating", "out/rot"), fs::current_path() / "out" / "rot");
    EXPECT_EQ(side_run_folder("chicken_shackling", "grasp-case-2", "/tmp/somewhere"), fs::path("/tmp/somewhere"));
}
