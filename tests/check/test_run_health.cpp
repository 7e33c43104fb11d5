// Explicit-run health (check/run_health.hpp): balance error <= 1 %, hourglass <= 10 % of internal,
// unless the reference file exempts the run with a reason; stale exemptions are problems too.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "check/run_health.hpp"
#include "core/error.hpp"

using namespace fem;
using namespace fem::check;

namespace {

std::pair<std::string, nlohmann::json> run(const std::string& name, double balance, double hourglass) {
    return {name, {{"energy_balance_relative_error", balance}, {"hourglass_fraction_of_internal", hourglass}}};
}

bool mentions(const std::vector<std::string>& problems, const std::string& fragment) {
    for (const auto& p : problems)
        if (p.find(fragment) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST(RunHealth, LimitsAndExemptions) {
    const std::vector<std::pair<std::string, nlohmann::json>> runs = {
        run("healthy", 0.004, 0.02), run("leaky", 0.023, 0.01), run("hourglassy", 0.001, 0.2),
        run("exempt", 0.05, 0.3), run("broken", std::nan(""), 0.0),
        {"modal solve", {{"nodes", 10}}},  // not an explicit run: not judged
    };
    const std::vector<HealthExemption> exemptions = {
        {"exempt", "contact chatter books energy", "coarse mesh, stated in the README", 7},
        {"healthy", "no longer needed", "", 12},
        {"renamed", "a run that no longer exists", "", 15},
    };
    std::vector<std::string> problems;
    const auto h = judge_run_health(runs, exemptions, "reference/demo.toml", problems);
    ASSERT_EQ(h.size(), 5u);
    EXPECT_TRUE(h[0].passed());
    EXPECT_FALSE(h[1].passed());
    EXPECT_FALSE(h[1].balance_ok);
    EXPECT_FALSE(h[2].passed());
    EXPECT_FALSE(h[2].hourglass_ok);
    EXPECT_TRUE(h[3].passed());  // both limits exceeded, both exempt with a reason
    EXPECT_EQ(h[3].to_json()["hourglass_exemption"], "coarse mesh, stated in the README");
    EXPECT_FALSE(h[4].passed());  // nan balance error
    // runs.json records a verdict per limit (the report shows them).
    EXPECT_EQ(h[0].to_json()["balance_verdict"], "ok");
    EXPECT_EQ(h[1].to_json()["balance_verdict"], "failed");
    EXPECT_EQ(h[1].to_json()["hourglass_verdict"], "ok");
    EXPECT_EQ(h[2].to_json()["hourglass_verdict"], "failed");
    EXPECT_EQ(h[3].to_json()["balance_verdict"], "exempt");
    EXPECT_EQ(h[3].to_json()["hourglass_verdict"], "exempt");
    EXPECT_EQ(h[4].to_json()["balance_verdict"], "failed");
    EXPECT_TRUE(mentions(problems, "FAIL   run health leaky: energy balance error 2.3 %"));
    EXPECT_TRUE(mentions(problems, "run health hourglassy"));
    EXPECT_TRUE(mentions(problems, "reference/demo.toml:12: run 'healthy' is exempt from the balance limit but meets it"));
    EXPECT_TRUE(mentions(problems, "reference/demo.toml:15: the health exemption names run 'renamed'"));
    EXPECT_EQ(problems.size(), 5u);
}

TEST(RunHealth, ExemptionsAreReadStrictly) {
    const auto dir = std::filesystem::temp_directory_path() / "fem_test_run_health";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "ok.toml") << "study = \"demo\"\n[[health_exemption]]\nrun = \"Case D\"\nbalance = \"why\"\n";
    const auto e = load_health_exemptions(dir / "ok.toml");
    ASSERT_EQ(e.size(), 1u);
    EXPECT_EQ(e[0].run, "Case D");
    EXPECT_EQ(e[0].line, 2);
    std::ofstream(dir / "typo.toml") << "study = \"demo\"\n[[health_exemption]]\nrun = \"Case D\"\nbalanse = \"why\"\n";
    EXPECT_THROW(load_health_exemptions(dir / "typo.toml"), InputError);
    std::ofstream(dir / "bare.toml") << "study = \"demo\"\n[[health_exemption]]\nrun = \"Case D\"\n";
    EXPECT_THROW(load_health_exemptions(dir / "bare.toml"), InputError);
}

TEST(RunHealth, PatternsCoverTheRunsOfASearch) {
    const std::vector<std::pair<std::string, nlohmann::json>> runs = {
        run("search alpha=30", 0.001, 0.3), run("search alpha=35", 0.001, 0.05), run("other", 0.001, 0.3)};
    std::vector<std::string> problems;
    const auto h = judge_run_health(runs, {{"search *", "", "coarse search mesh", 3}}, "ref.toml", problems);
    EXPECT_TRUE(h[0].passed());
    EXPECT_TRUE(h[1].passed());  // healthy anyway: fine, since another run of the pattern needs it
    EXPECT_FALSE(h[2].passed());
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_TRUE(mentions(problems, "run health other"));
    problems.clear();
    judge_run_health({run("search alpha=35", 0.001, 0.05)}, {{"search *", "", "coarse search mesh", 3}}, "ref.toml", problems);
    EXPECT_TRUE(mentions(problems, "ref.toml:3: run 'search *' is exempt from the hourglass limit but meets it"));
}
