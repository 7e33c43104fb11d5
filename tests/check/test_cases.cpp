// Independent cases of a study (check/cases.hpp): results in case order on any number of threads,
// the first failure rethrown after every case ended, --jobs and FEM_JOBS, and the dealing of cases
// to MPI ranks with the gathering of their JSON results (on a stand-in for two ranks; the real
// mpirun run is the CTest test mpi_<study>).
#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "check/cases.hpp"
#include "check/study.hpp"
#include "core/error.hpp"

namespace fs = std::filesystem;
using fem::check::Study;

namespace {

// A study "cases" with an empty reference file in a temporary folder; extra command-line options.
struct CaseStudy {
    fs::path dir = fs::temp_directory_path() / ("fem-test-cases-" + std::to_string(::getpid()));
    std::unique_ptr<Study> study;
    explicit CaseStudy(std::vector<std::string> extra = {}) {
        fs::create_directories(dir);
        std::ofstream(dir / "cases.toml") << "study = \"cases\"\ntitle = \"cases\"\nsection = \"-\"\n";
        std::vector<std::string> a = {"cases", "--results", (dir / "results").string(), "--reference",
                                      (dir / "cases.toml").string()};
        a.insert(a.end(), extra.begin(), extra.end());
        std::vector<char*> argv;
        for (auto& s : a) argv.push_back(s.data());
        study = std::make_unique<Study>("cases", static_cast<int>(argv.size()), argv.data());
    }
    ~CaseStudy() { fs::remove_all(dir); }
};

}  // namespace

TEST(Cases, ResultsInCaseOrderOnAnyNumberOfThreads) {
    for (const char* jobs : {"1", "2", "5"}) {
        CaseStudy s({"--jobs", jobs});
        std::atomic<int> running{0}, most{0};
        const auto r = fem::check::run_cases<long>(*s.study, 11, [&](int k) {
            const int now = ++running;
            for (int m = most; now > m && !most.compare_exchange_weak(m, now);) {
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(5 * ((k * 7) % 4)));  // finish out of order
            --running;
            return static_cast<long>(k) * k;
        });
        ASSERT_EQ(r.size(), 11u);
        for (int k = 0; k < 11; ++k) EXPECT_EQ(r[k], static_cast<long>(k) * k) << jobs;
        EXPECT_LE(most.load(), std::stoi(jobs)) << jobs;
    }
}

TEST(Cases, FirstFailureIsRethrownAfterEveryCaseEnded) {
    CaseStudy s({"--jobs", "3"});
    std::atomic<int> done{0};
    try {
        fem::check::run_cases<int>(*s.study, 9, [&](int k) {
            if (k == 7) throw std::runtime_error("case 7");
            if (k == 3) {
                std::this_thread::sleep_for(std::chrono::milliseconds(20));  // fails after case 7 did
                throw std::runtime_error("case 3");
            }
            ++done;
            return k;
        });
        ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "case 3");
    }
    EXPECT_EQ(done.load(), 7);
}

TEST(Cases, JobsFromTheCommandLineOrTheEnvironment) {
    {
        CaseStudy s({"--jobs", "3"});
        EXPECT_EQ(s.study->jobs(), 3);
        EXPECT_EQ(fem::check::case_jobs(*s.study), 3);
    }
    EXPECT_THROW(CaseStudy({"--jobs", "0"}), fem::InputError);
    EXPECT_THROW(CaseStudy({"--jobs", "two"}), fem::InputError);
    CaseStudy s;
    EXPECT_EQ(s.study->jobs(), 0);
    ::setenv("FEM_JOBS", "4", 1);
    EXPECT_EQ(fem::check::case_jobs(*s.study), 4);
    ::setenv("FEM_JOBS", "many", 1);
    EXPECT_THROW(fem::check::case_jobs(*s.study), fem::InputError);
    ::unsetenv("FEM_JOBS");
    EXPECT_GE(fem::check::case_jobs(*s.study), 1);
}

namespace {
// Rank 0 of two: "rank 1" computes the odd cases (here: the test computes them) and all_gather hands
// back both ranks' JSON in rank order, as MPI_Allgatherv does.
struct Result {
    int k = 0;
    double value = 0;
    std::vector<double> series;
};
void to_json(nlohmann::json& j, const Result& r) { j = {{"k", r.k}, {"value", r.value}, {"series", r.series}}; }
void from_json(const nlohmann::json& j, Result& r) {
    r.k = j.at("k").get<int>();
    r.value = j.at("value").get<double>();
    r.series = j.at("series").get<std::vector<double>>();
}
Result compute(int k) { return {k, 1.0 / (k + 3), {0.1 * k, std::sqrt(k + 0.5)}}; }

class TwoRanks final : public fem::check::Ranks {
public:
    int rank() const override { return 0; }
    int size() const override { return 2; }
    std::vector<std::string> all_gather(const std::string& mine) const override {
        nlohmann::json other = nlohmann::json::array();
        for (int k = 1; k < 7; k += 2) other.push_back(nlohmann::json::array({k, nlohmann::json(compute(k))}));
        ++calls;
        return {mine, other.dump()};
    }
    mutable int calls = 0;
};
}  // namespace

TEST(Cases, CasesAreDealtToRanksAndEveryResultGathered) {
    auto backend = std::make_unique<TwoRanks>();
    const TwoRanks* two = backend.get();
    fem::check::set_ranks(std::move(backend));
    std::vector<int> ran;
    std::vector<Result> r;
    {
        CaseStudy s({"--jobs", "1"});
        r = fem::check::run_cases<Result>(*s.study, 7, [&](int k) {
            ran.push_back(k);
            return compute(k);
        });
        EXPECT_EQ(two->calls, 1);
    }
    fem::check::set_ranks(nullptr);  // back to serial
    EXPECT_EQ(fem::check::detail::deal_cases(7, 2, {.writes_files = {1, 4}}),
              (std::vector<int>{0, 0, 1, 0, 0, 1, 0}));  // cases 1, 4 write files: rank 0
    EXPECT_EQ(fem::check::ranks().size(), 1);
    EXPECT_EQ(ran, (std::vector<int>{0, 2, 4, 6}));  // rank 0's share: k mod 2 = 0
    ASSERT_EQ(r.size(), 7u);
    for (int k = 0; k < 7; ++k) {  // every result, bit for bit (JSON keeps doubles exactly)
        const Result c = compute(k);
        EXPECT_EQ(r[k].k, k);
        EXPECT_EQ(r[k].value, c.value);
        EXPECT_EQ(r[k].series, c.series);
    }
}
