// Determinism: the same inputs give the same results whatever the thread count and run after run.
// finger_twist (two explicit hexahedral finger runs, the shortest explicit study) runs with
// OMP_NUM_THREADS = 1 and 2; checks.json and the HDF5 histories must be byte-identical and runs.json
// identical apart from its timings (wall time, element-cycles per second, threads). Two runs are also
// run after run; a third (2 threads again, 1/3 of this test's ~100 s) was dropped to pay for the fuzz
// runs in CTest: run-after-run identity is tested besides by outputs_killed_run (fem-modal, HDF5
// included) and outputs_killed_explicit_resumes (an explicit case run twice, byte for byte).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "check/build_paths.hpp"
#include "explicit/solver.hpp"

namespace fs = std::filesystem;

namespace {

fs::path g_work;

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Runs the study with `threads` OpenMP threads into `dir`; returns the exit status.
int run_study(int threads, const fs::path& dir) {
    const std::string cmd = "OMP_NUM_THREADS=" + std::to_string(threads) + " '" + (fem::check::bin_dir() / "finger_twist").string() +
                            "' --results '" + dir.string() + "' > '" + dir.string() + ".log' 2>&1";
    return std::system(cmd.c_str());
}

nlohmann::json runs_without_timings(const fs::path& file) {
    auto runs = nlohmann::json::parse(slurp(file));
    for (auto& run : runs)
        fem::RunSummary::erase_machine_facts(run["values"]);
    return runs;
}

}  // namespace

TEST(Determinism, OneAndTwoThreadsGiveTheSameBytes) {
    fs::remove_all(g_work);
    fs::create_directories(g_work);
    const fs::path one = g_work / "threads-1", two = g_work / "threads-2";
    // The study's verdicts are its own test (CTest finger_twist); here it only has to run to its end.
    for (const auto& [threads, dir] : {std::pair{1, one}, {2, two}}) {
        run_study(threads, dir);
        ASSERT_TRUE(fs::exists(dir / "checks.json")) << slurp(dir.string() + ".log");
    }

    std::vector<std::string> h5;
    for (const auto& e : fs::directory_iterator(one))
        if (e.path().extension() == ".h5") h5.push_back(e.path().filename().string());
    ASSERT_EQ(h5.size(), 2u) << "finger_twist writes case-a.h5 and refined.h5";
    for (const fs::path& other : {two}) {
        EXPECT_EQ(slurp(one / "checks.json"), slurp(other / "checks.json")) << other;
        EXPECT_EQ(runs_without_timings(one / "runs.json"), runs_without_timings(other / "runs.json")) << other;
        for (const auto& f : h5) EXPECT_EQ(slurp(one / f), slurp(other / f)) << other / f << " differs byte for byte";
    }
    // The runs did run on the threads asked for (else the comparison proves nothing).
    const auto threads = [](const fs::path& d) { return nlohmann::json::parse(slurp(d / "runs.json"))[0]["values"]["threads"]; };
    EXPECT_EQ(threads(one), 1);
    EXPECT_EQ(threads(two), 2);
    if (!::testing::Test::HasFailure()) fs::remove_all(g_work);
}

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
    g_work = argc > 1 ? fs::path(argv[1]) : fs::temp_directory_path() / "fem_test_determinism";
    return RUN_ALL_TESTS();
}
