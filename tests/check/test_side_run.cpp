// check::side_run_folder: a study's side run (e.g. chicken_shackling --grasp 4) writes under the
// build's results folder whatever directory it is started from (the bug it guards against: --grasp
// run from the project root left grasp-case-4.pvd, its VTU and surface files in the project root).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "check/side_run.hpp"
#include "core/error.hpp"
#include "input/arguments.hpp"

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

namespace {

fem::check::SideRun read(std::vector<std::string> words, double* dump_every = nullptr) {
    words.insert(words.begin(), "study");
    std::vector<char*> argv;
    for (auto& w : words) argv.push_back(w.data());
    return fem::check::read_side_run(static_cast<int>(argv.size()), argv.data(), "study", "", {"--grasp", "--shackle"}, {{"--dump-every", "--grasp"}, {"--resume", "--grasp"}},
                                     [&](fem::input::Arguments& args) {
                                         if (args.is("--dump-every")) *dump_every = args.real(fem::input::Range::positive());
                                     });
}

std::string error_of(std::vector<std::string> words) {
    double d = 0;
    try {
        read(std::move(words), &d);
    } catch (const fem::InputError& e) {
        return e.what();
    }
    return "(accepted)";
}

}  // namespace

TEST(SideRunCommandLine, ReadsTheModeItsOperandsAndOptionsStrictly) {
    double dump_every = 0;
    const auto side = read({"--grasp", "4", "-0.5", "--dump-every", "0.01", "--results", "out", "--resume"}, &dump_every);
    EXPECT_EQ(side.mode, "--grasp");
    EXPECT_EQ(side.operands, (std::vector<std::string>{"4", "-0.5"}));
    EXPECT_EQ(side.options, (std::vector<std::string>{"--dump-every", "--resume"}));
    EXPECT_EQ(side.results, fs::path("out"));
    EXPECT_EQ(dump_every, 0.01);
    // The study run: no mode; its own options pass through (Study reads them).
    const auto study = read({"--full", "--jobs", "2", "--figures", "f"});
    EXPECT_TRUE(study.mode.empty());
    // --help prints the usage and ends the program with status 0, whatever else is given.
    EXPECT_EXIT(read({"--grasp", "--full", "--help"}), ::testing::ExitedWithCode(0), "");
    EXPECT_NE(error_of({"--grasp", "4", "--dump-evry", "1"}).find("unknown option '--dump-evry' (did you mean '--dump-every'?)"),
              std::string::npos);
    EXPECT_NE(error_of({"--grasp", "--shackle"}).find("one side run at a time, got --grasp and --shackle"), std::string::npos);
    EXPECT_NE(error_of({"--shackle", "--jobs", "2"}).find("--jobs is an option of the study run, not of the --shackle side run"),
              std::string::npos);
    EXPECT_NE(error_of({"--grasp", "--dump-every", "0"}).find("--dump-every: must be a finite number > 0, got 0"), std::string::npos);
    EXPECT_NE(error_of({"--grasp", "--results"}).find("option '--results' needs a value"), std::string::npos);
    // An option of one side run beside another, or alone.
    EXPECT_NE(error_of({"--shackle", "--resume"}).find("--resume is an option of the --grasp side run, not of --shackle"), std::string::npos);
    EXPECT_NE(error_of({"--resume"}).find("--resume is an option of the --grasp side run (see --help)"), std::string::npos);
    // Surplus operands.
    EXPECT_THROW(read({"--shackle", "a"}).at_most_operands(0), fem::InputError);
    try {
        read({"--grasp", "4", "1", "x"}).at_most_operands(2, "case, end time");
        ADD_FAILURE() << "a third operand was accepted";
    } catch (const fem::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("--grasp takes at most 2 operands (case, end time), got 3: 'x'"), std::string::npos) << e.what();
    }
    // A side run that only prints refuses --results rather than ignore it.
    EXPECT_THROW(read({"--shackle", "--results", "out"}).refuse_results(), fem::InputError);
    EXPECT_NO_THROW(read({"--shackle"}).refuse_results());
}
