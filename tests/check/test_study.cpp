// The check module: reference files, tolerances, check records, the report.
#include <gtest/gtest.h>

#include <algorithm>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>

#include <nlohmann/json.hpp>

#include "check/reference.hpp"
#include "check/report.hpp"
#include "check/study.hpp"
#include "core/error.hpp"
#include "io/table.hpp"

namespace fs = std::filesystem;
using namespace fem::check;

namespace {

struct TempDir {
    fs::path path;
    TempDir() {
        path = fs::temp_directory_path() / ("fem_check_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(path);
        fs::create_directories(path);
    }
    ~TempDir() { fs::remove_all(path); }
};

void write(const fs::path& p, const std::string& text) {
    std::ofstream(p) << text;
}

const char* kReference = R"toml(
study = "demo"
title = "Demo study"
section = "Sec 9.9"
[figures]
"Table 9-1" = ["table-9-1.md"]

[[check]]
id = "table-9-1/a"
source = "Table 9-1"
quantity = "a value"
unit = "us"
basis = "exact"
kind = "consistency"
thesis = 1.32
tolerance = { abs = 0.005 }
reason = "printed precision"

[[check]]
id = "table-9-1/steps"
source = "Table 9-1"
quantity = "steps"
basis = "exact"
kind = "consistency"
thesis = 1070
tolerance = { abs = 1.0 }
reason = "one step"
follows = 1071.06
discrepancy = "the printed value is twice another row"

[[check]]
id = "table-9-1/series"
source = "Table 9-1"
quantity = "three values"
basis = "model"
kind = "reproduction"
thesis = [1.0, 2.0, 3.0]
tolerance = { rel = 0.1 }
reason = "mesh"

[[check]]
id = "fig-9-2/order"
source = "Fig 9-2"
quantity = "ordering"
basis = "trend"
kind = "trend"
thesis = "A > B"

[[check]]
id = "fig-9-2/measured"
source = "Fig 9-2"
quantity = "experiment"
basis = "experiment"
kind = "shown"
thesis = 25.0
judged = false

[[check]]
id = "table-9-3/miss"
source = "Table 9-3"
quantity = "a value our model does not reach yet"
unit = "Hz"
basis = "model"
kind = "reproduction"
thesis = 10.0
tolerance = { rel = 0.05 }
reason = "mesh"
known_miss = "ours is 20 % low: the joint is too soft (tried: 6-DOF coupling)"
history = [ { date = "2026-12-01", change = "kind shown -> reproduction, known miss", was = "judged = false", why = "a miss is not hidden as shown" } ]

[[check]]
id = "table-9-3/modes"
source = "Table 9-3"
quantity = "three modes, the second a known miss"
basis = "model"
kind = "reproduction"
thesis = [1.0, 2.0, 3.0]
labels = ["m1", "m2", "m3"]
tolerance = { rel = 0.1 }
reason = "mesh"
known_miss = "mode 2 is a local mode of our bracket"
known_miss_labels = ["m2"]
)toml";

// A kReference study run with every check as expected: the known misses miss (unless the values
// given make them pass).
void run_demo_as_expected(Study& study, double miss = 8.0, double mode_2 = 2.5) {
    study.check("table-9-1/a", 1.32);
    study.check("table-9-1/steps", 1071.0);
    const std::vector<double> series = {1.0, 2.0, 3.0};
    study.check("table-9-1/series", series);
    study.trend("fig-9-2/order", "A > B");
    study.check("fig-9-2/measured", 25.5);
    study.check("table-9-3/miss", miss);
    const std::vector<double> modes = {1.0, mode_2, 3.0};
    study.check("table-9-3/modes", modes);
}

// Command line of the demo study: results under `results`, reference dir/demo.toml.
struct DemoArgs {
    std::vector<std::string> storage;
    std::vector<char*> argv;
    DemoArgs(const fs::path& reference, const fs::path& results)
        : storage{"demo", "--results", results.string(), "--reference", reference.string()} {
        for (auto& a : storage) argv.push_back(a.data());
    }
    int argc() const { return static_cast<int>(argv.size()); }
    char** data() { return argv.data(); }
};

// The demo study run as expected for the report tests: dir/reference/demo.toml and its results in
// dir/results/demo/; `more` (e.g. runs to record) is done before finish().
void run_demo_study(const fs::path& dir, const std::function<void(Study&)>& more = {}) {
    fs::create_directories(dir / "reference");
    write(dir / "reference" / "demo.toml", kReference);
    DemoArgs argv(dir / "reference" / "demo.toml", dir / "results" / "demo");
    Study study("demo", argv.argc(), argv.data());
    run_demo_as_expected(study);
    if (more) more(study);
    EXPECT_EQ(study.finish(), 0);
}


}  // namespace

TEST(Tolerance, AbsPlusRel) {
    Tolerance t{0.01, 0.5};
    EXPECT_TRUE(t.allows(101.4, 100.0));   // 1.4 <= 0.5 + 1.0
    EXPECT_FALSE(t.allows(101.6, 100.0));
    EXPECT_FALSE(t.allows(NAN, 100.0));
}

TEST(Reference, LoadsAllKinds) {
    TempDir dir;
    write(dir.path / "demo.toml", kReference);
    const auto ref = load_reference(dir.path / "demo.toml");
    EXPECT_EQ(ref.study, "demo");
    ASSERT_EQ(ref.entries.size(), 7u);
    EXPECT_TRUE(ref.entry("fig-9-2/order").is_trend());
    EXPECT_TRUE(ref.entry("table-9-1/series").is_series());
    EXPECT_EQ(*ref.entry("table-9-1/steps").follows, 1071.06);
    EXPECT_FALSE(ref.entry("fig-9-2/measured").judged());
    EXPECT_EQ(ref.entry("fig-9-2/measured").kind, Kind::Shown);
    EXPECT_EQ(ref.entry("table-9-1/a").kind, Kind::Consistency);
    EXPECT_TRUE(ref.entry("table-9-3/miss").is_known_miss());
    ASSERT_EQ(ref.entry("table-9-3/miss").history.size(), 1u);
    EXPECT_EQ(ref.entry("table-9-3/miss").history[0].was, "judged = false");
    EXPECT_TRUE(ref.entry("table-9-3/modes").member_is_known_miss("m2"));
    EXPECT_FALSE(ref.entry("table-9-3/modes").member_is_known_miss("m1"));
    EXPECT_THROW(ref.entry("nope"), std::out_of_range);
}

TEST(Reference, RefusesBadFilesNamingTheProblem) {
    TempDir dir;
    auto expect_error = [&](const std::string& text, const std::string& fragment) {
        write(dir.path / "bad.toml", text);
        try {
            load_reference(dir.path / "bad.toml");
            ADD_FAILURE() << "accepted: " << text;
        } catch (const fem::InputError& e) {
            EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
        }
    };
    const std::string entry = "study = \"x\"\n[[check]]\nid = \"a\"\nsource = \"T\"\nquantity = \"q\"\nbasis = \"exact\"\n";
    expect_error(entry + "kind = \"consistency\"\nthesis = 1\n", "needs a tolerance");
    expect_error(entry + "thesis = 1\ntolerance = { rel = 0.1 }\nreason = \"r\"\n", "lacks 'kind'");
    expect_error(entry + "kind = \"agreement\"\nthesis = 1\ntolerance = { rel = 0.1 }\nreason = \"r\"\n", "kind 'agreement'");
    expect_error(entry + "kind = \"reproduction\"\nthesis = 1\ntolerance = { rel = 0.1 }\nreason = \"r\"\njudged = false\n",
                 "judged = false is only for kind \"shown\"");
    expect_error(entry + "kind = \"shown\"\nthesis = 1\ntolerance = { rel = 0.1 }\nreason = \"r\"\n", "takes no tolerance");
    expect_error(entry + "kind = \"shown\"\nthesis = 1\nknown_miss = \"low\"\n", "known_miss is judged");
    expect_error(entry + "kind = \"reproduction\"\nthesis = 1\ntolerance = { rel = 0.1 }\nreason = \"r\"\nknown_miss = \"\"\n",
                 "non-empty");
    expect_error(entry + "kind = \"reproduction\"\nthesis = 1\ntolerance = { rel = 0.1 }\nreason = \"r\"\n"
                         "history = [ { date = \"2026-01-01\", change = \"c\", why = \"w\" } ]\n",
                 "lacks 'was'");
    expect_error(entry + "kind = \"reproduction\"\nthesis = [1, 2]\ntolerance = { rel = 0.1 }\nreason = \"r\"\n"
                         "known_miss = \"m\"\nknown_miss_labels = [\"3\"]\n",
                 "names '3'");
    expect_error(entry + "kind = \"reproduction\"\nthesis = 1\ntolerance = { rel = 0.1 }\nreason = \"r\"\nfull_only = \"\"\n",
                 "full_only must say why");
    expect_error("study = \"x\"\n[[check]]\nid = \"a\"\nsource = \"T\"\nquantity = \"q\"\nbasis = \"guess\"\nthesis = 1\n",
                 "basis 'guess'");
    expect_error(entry + "kind = \"consistency\"\nthesis = 1\ntolerance = { rel = 0.1 }\n", "reason");
    expect_error("study = \"x\"\n[[check]\n", "bad.toml:2");
    EXPECT_THROW(load_reference(dir.path / "missing.toml"), fem::InputError);
}

TEST(Study, WritesChecksAndFailsOnMissingOrWrongValues) {
    TempDir dir;
    write(dir.path / "demo.toml", kReference);
    DemoArgs argv(dir.path / "demo.toml", dir.path / "results");
    {
        Study study("demo", argv.argc(), argv.data());
        EXPECT_TRUE(*study.check("table-9-1/a", 1.3204).passed);
        // 1071.05 misses the printed 1070 by more than a step, but is checked against what follows.
        const auto& steps = study.check("table-9-1/steps", 1071.05);
        EXPECT_TRUE(*steps.passed);
        ASSERT_TRUE(steps.reference.has_value());
        const std::vector<double> series = {1.05, 2.5, 3.0};
        study.check("table-9-1/series", series);
        EXPECT_TRUE(*study.trend("fig-9-2/order", "A > B").passed);
        // fig-9-2/measured and the table-9-3 entries are left out on purpose: finish() must fail the
        // study, known misses included (a value the study did not produce is no known miss).
        EXPECT_EQ(study.finish(), 1);
    }
    std::ifstream in(dir.path / "results" / "checks.json");
    const auto j = nlohmann::json::parse(in);
    ASSERT_EQ(j.size(), 9u);  // a, steps, 3 series members, trend, 3 missing
    EXPECT_EQ(j[1]["reference"], 1071.06);
    EXPECT_EQ(j[3]["id"], "table-9-1/series/2");
    EXPECT_EQ(j[3]["passed"], false);  // 2.5 vs 2.0 with 10 %
    EXPECT_TRUE(j[5]["tolerance"].is_null());
    EXPECT_EQ(j[6]["id"], "fig-9-2/measured");
    EXPECT_EQ(j[6]["passed"], false);
    EXPECT_EQ(j[7]["id"], "table-9-3/miss");
    EXPECT_FALSE(j[7].contains("known_miss"));
    EXPECT_EQ(verdict(CheckRecord::from_json(j[7])), Verdict::Fail);
    EXPECT_EQ(j[0]["kind"], "consistency");
    // The results folder holds the run's set and its manifest, no temporary or staging folder.
    std::vector<std::string> files;
    for (const auto& e : fs::directory_iterator(dir.path / "results")) files.push_back(e.path().filename().string());
    std::sort(files.begin(), files.end());
    EXPECT_EQ(files, (std::vector<std::string>{"checks.json", "manifest.txt", "runs.json"}));
}

TEST(Study, ShownValuesAreNotJudgedAndAllPassingExitsZero) {
    TempDir dir;
    write(dir.path / "demo.toml", kReference);
    DemoArgs argv(dir.path / "demo.toml", dir.path / "results");
    Study study("demo", argv.argc(), argv.data());
    study.check("table-9-1/a", 1.32);
    study.check("table-9-1/steps", 1071.0);
    const std::vector<double> series = {1.0, 2.0, 3.0};
    study.check("table-9-1/series", series);
    EXPECT_FALSE(*study.trend_holds("fig-9-2/order", false, "B > A").passed);
    EXPECT_FALSE(study.check("fig-9-2/measured", 25.5).passed.has_value());
    EXPECT_EQ(verdict(study.check("table-9-3/miss", 8.0)), Verdict::KnownMiss);
    const std::vector<double> modes = {1.0, 2.5, 3.0};
    study.check("table-9-3/modes", modes);
    EXPECT_EQ(study.finish(), 1);  // the trend failed
}

TEST(Study, KnownMissesPassTheStudyWhileTheyMissAndFailItWhenTheyPass) {
    TempDir dir;
    write(dir.path / "demo.toml", kReference);
    DemoArgs argv(dir.path / "demo.toml", dir.path / "results");
    {
        Study study("demo", argv.argc(), argv.data());
        run_demo_as_expected(study);
        EXPECT_EQ(study.finish(), 0);
        std::map<std::string, Verdict> v;
        for (const auto& r : study.records()) v[r.id] = verdict(r);
        EXPECT_EQ(v["table-9-3/miss"], Verdict::KnownMiss);
        EXPECT_EQ(v["table-9-3/modes/m1"], Verdict::Pass);
        EXPECT_EQ(v["table-9-3/modes/m2"], Verdict::KnownMiss);
        EXPECT_EQ(v["fig-9-2/measured"], Verdict::Shown);
    }
    {
        std::ifstream in(dir.path / "results" / "checks.json");
        const auto j = nlohmann::json::parse(in);
        const auto r = CheckRecord::from_json(j[7]);
        EXPECT_EQ(r.id, "table-9-3/miss");
        EXPECT_EQ(r.kind, Kind::Reproduction);
        EXPECT_EQ(r.known_miss, "ours is 20 % low: the joint is too soft (tried: 6-DOF coupling)");
        ASSERT_EQ(r.history.size(), 1u);
        EXPECT_EQ(r.history[0].why, "a miss is not hidden as shown");
        EXPECT_EQ(j[8]["id"], "table-9-3/modes/m1");
        EXPECT_FALSE(j[8].contains("known_miss"));  // only the listed member is a known miss
        EXPECT_EQ(j[9]["known_miss"], "mode 2 is a local mode of our bracket");
    }
    for (int which = 0; which < 2; ++which) {  // the single value, then the series member, start to pass
        Study study("demo", argv.argc(), argv.data());
        run_demo_as_expected(study, which == 0 ? 10.1 : 8.0, which == 1 ? 2.0 : 2.5);
        std::map<std::string, Verdict> v;
        for (const auto& r : study.records()) v[r.id] = verdict(r);
        EXPECT_EQ(v["table-9-3/miss"], which == 0 ? Verdict::UnexpectedPass : Verdict::KnownMiss);
        EXPECT_EQ(v["table-9-3/modes/m2"], which == 1 ? Verdict::UnexpectedPass : Verdict::KnownMiss);
        EXPECT_EQ(study.finish(), 1);
    }
}

// A full_only entry: a run without --full lists it as not run (the study still exits 0) and refuses
// to judge it; a --full run judges it like any other, and fails when it is not produced.
TEST(Study, FullOnlyChecksAreListedAsNotRunWithoutFullAndJudgedWithIt) {
    TempDir dir;
    write(dir.path / "demo.toml", std::string(kReference) + R"toml(
[[check]]
id = "fig-9-4/long-run"
source = "Fig 9-4"
quantity = "a value of a run longer than CTest's budget"
basis = "model"
kind = "reproduction"
thesis = 5.0
tolerance = { rel = 0.1 }
reason = "mesh"
full_only = "five 20-minute runs"
)toml");
    DemoArgs argv(dir.path / "demo.toml", dir.path / "results");
    {
        Study study("demo", argv.argc(), argv.data());
        run_demo_as_expected(study);
        EXPECT_THROW(study.check("fig-9-4/long-run", 5.0), std::logic_error);
        EXPECT_EQ(study.finish(), 0);
        const CheckRecord& r = study.records().back();
        EXPECT_EQ(r.id, "fig-9-4/long-run");
        EXPECT_EQ(verdict(r), Verdict::NotRun);
        EXPECT_FALSE(fails_study(Verdict::NotRun));
        EXPECT_NE(r.note.find("five 20-minute runs"), std::string::npos) << r.note;
        std::ifstream in(dir.path / "results" / "checks.json");
        const auto back = CheckRecord::from_json(nlohmann::json::parse(in).back());
        EXPECT_EQ(verdict(back), Verdict::NotRun);
        EXPECT_EQ(back.full_only, "five 20-minute runs");
    }
    argv.storage.push_back("--full");
    argv.argv.clear();
    for (auto& a : argv.storage) argv.argv.push_back(a.data());
    for (const double value : {5.2, 7.0}) {
        Study study("demo", argv.argc(), argv.data());
        run_demo_as_expected(study);
        EXPECT_EQ(verdict(study.check("fig-9-4/long-run", value)), value == 5.2 ? Verdict::Pass : Verdict::Fail);
        EXPECT_EQ(study.finish(), value == 5.2 ? 0 : 1);
    }
    Study forgot("demo", argv.argc(), argv.data());
    run_demo_as_expected(forgot);
    EXPECT_EQ(forgot.finish(), 1);  // --full must produce it
    EXPECT_EQ(verdict(forgot.records().back()), Verdict::Fail);
}

TEST(Verdict, OneClassification) {
    CheckRecord r;
    EXPECT_EQ(verdict(r), Verdict::Shown);
    r.passed = true;
    EXPECT_EQ(verdict(r), Verdict::Pass);
    r.passed = false;
    EXPECT_EQ(verdict(r), Verdict::Fail);
    r.known_miss = "why";
    EXPECT_EQ(verdict(r), Verdict::KnownMiss);
    EXPECT_FALSE(fails_study(verdict(r)));
    r.passed = true;
    EXPECT_EQ(verdict(r), Verdict::UnexpectedPass);
    EXPECT_TRUE(fails_study(verdict(r)));
    EXPECT_THROW(CheckRecord::from_json({{"id", "x"}, {"passed", true}}), fem::InputError);
}

TEST(Study, RefusesUnknownIdsAndOptions) {
    TempDir dir;
    write(dir.path / "demo.toml", kReference);
    DemoArgs argv(dir.path / "demo.toml", dir.path / "r");
    Study study("demo", argv.argc(), argv.data());
    EXPECT_THROW(study.check("no/such/id", 1.0), std::out_of_range);
    EXPECT_THROW(study.check("fig-9-2/order", 1.0), std::logic_error);
    std::string name = "demo", option = "--frobnicate";
    char* bad_argv[] = {name.data(), option.data()};
    EXPECT_THROW(Study("demo", 2, bad_argv), fem::InputError);
}

// Items in thesis order (chapter, then tables before figures before sections, then number: 9-4
// before 9-12), and a figure item under the checked item that names it by its whole number: "Fig 9-1"
// is not "Fig 9-12"'s, so it is an item of its own, in its place.
TEST(Report, ItemsInThesisOrderAndFiguresByWholeNumber) {
    TempDir dir;
    fs::create_directories(dir.path / "reference");
    std::string toml = "study = \"order\"\ntitle = \"Order\"\n[figures]\n\"Fig 9-1\" = [\"fig-9-1.md\"]\n"
                       "\"Table 9-4\" = [\"table-9-4.md\"]\n\"Fig 9-12\" = [\"fig-9-12.md\"]\n";
    const std::vector<std::pair<std::string, std::string>> checks = {{"sec/a", "Sec 9.2"}, {"fig-9-12/a", "Fig 9-12"}, {"fig-9-4/a", "Fig 9-4"}};
    for (const auto& [id, source] : checks)
        toml += "\n[[check]]\nid = \"" + id + "\"\nsource = \"" + source +
                "\"\nquantity = \"a\"\nbasis = \"exact\"\nkind = \"consistency\"\nthesis = 1.0\ntolerance = { abs = 0.5 }\nreason = \"r\"\n";
    write(dir.path / "reference" / "order.toml", toml);
    DemoArgs argv(dir.path / "reference" / "order.toml", dir.path / "results" / "order");
    {
        Study study("order", argv.argc(), argv.data());
        for (const auto& [id, source] : checks) study.check(id, 1.0);
        EXPECT_EQ(study.finish(), 0);
    }
    fs::create_directories(dir.path / "figures");
    write(dir.path / "figures" / "fig-9-1.md", "| one |\n|---|\n| 1 |\n");
    write(dir.path / "figures" / "table-9-4.md", "| four |\n|---|\n| 4 |\n");
    write(dir.path / "figures" / "fig-9-12.md", "| twelve |\n|---|\n| 12 |\n");
    EXPECT_EQ(write_report({dir.path / "reference", dir.path / "results", dir.path / "figures"}), 0);
    std::ifstream md_in(dir.path / "figures" / "REPORT.md");
    const std::string md((std::istreambuf_iterator<char>(md_in)), {});
    std::vector<std::size_t> at;
    for (const char* h : {"### Table 9-4\n", "| four |", "### Fig 9-1\n", "| one |", "### Fig 9-4\n", "### Fig 9-12\n", "| twelve |",
                          "### Sec 9.2\n"}) {
        at.push_back(md.find(h));
        EXPECT_NE(at.back(), std::string::npos) << h;
    }
    EXPECT_TRUE(std::is_sorted(at.begin(), at.end())) << md.substr(md.find("## order"));
}

TEST(Report, ListsEveryStudyAndTheDiscrepancies) {
    TempDir dir;
    run_demo_study(dir.path, [](Study& study) {
        study.record_run({"run 1",
                          {{"steps", 1234567},
                           {"nodes", 8},
                           {"min_dt_s", 1.25e-6},
                           {"max_dt_s", 1.5e-6},
                           {"wall_s", 2170.4},
                           {"element_cycles_per_s", 1e6},
                           {"threads", 2},
                           {"timing_s", {{"elements", 0.25}, {"update", 0.125}, {"contact_search", 0.0625}, {"contact_forces", 0.0625}}},
                           {"contact_interfaces", nlohmann::json::array({{{"name", "fingers on ball"}, {"forces_s", 0.0625}},
                                                                         {{"name", "ball on floor"}, {"forces_s", 0.5}}})}}});
        study.record_run({"modes 1", {{"modes", 10}, {"solver", {{"name", "CHOLMOD"}, {"nonzeros", 100}}}, {"final_compliance_J", 2.5}}});
    });
    // A second reference file without results: listed as not run.
    auto other = std::string(kReference);
    other.replace(other.find("\"demo\""), 6, "\"other\"");
    write(dir.path / "reference" / "other.toml", other);
    write(dir.path / "figures_table.md", "");
    fs::create_directories(dir.path / "figures");
    write(dir.path / "figures" / "table-9-1.md", "| a |\n|---|\n| 1 |\n");

    EXPECT_EQ(write_report({dir.path / "reference", dir.path / "results", dir.path / "figures"}), 0);
    std::ifstream md_in(dir.path / "figures" / "REPORT.md");
    const std::string md((std::istreambuf_iterator<char>(md_in)), {});
    EXPECT_NE(md.find("## Scorecard"), std::string::npos);
    EXPECT_NE(md.find("## Thesis discrepancies"), std::string::npos);
    EXPECT_NE(md.find("the printed value is twice another row"), std::string::npos);
    EXPECT_NE(md.find("### Table 9-1"), std::string::npos);
    EXPECT_NE(md.find("| other |"), std::string::npos);
    EXPECT_NE(md.find("not run"), std::string::npos);
    EXPECT_NE(md.find("Solver runs"), std::string::npos);
    // An explicit run (steps and a timing table) in the summary columns, where its wall time went as
    // shares (contact = search + forces; ties by name), every value named in runs.json; not 38 raw keys.
    EXPECT_NE(md.find("| run | nodes | elements | end time (s) | steps | step (us) |"), std::string::npos) << md;
    EXPECT_NE(md.find("| run 1 | 8 |  |  | 1234567 | 1.25-1.5 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| 2170 (2) | 1 | elements 50\u00a0%, update 25\u00a0%, contact 25\u00a0% |"), std::string::npos) << md;
    EXPECT_NE(md.find("`build/results/demo/runs.json`"), std::string::npos);
    EXPECT_EQ(md.find("contact_search"), std::string::npos);
    // Any other run with all its values, keys as headings, objects read as words, not JSON.
    EXPECT_NE(md.find("| run | final compliance (J) | modes | solver |"), std::string::npos) << md;
    EXPECT_NE(md.find("| modes 1 | 2.5 | 10 | CHOLMOD: nonzeros 100 |"), std::string::npos) << md;
    EXPECT_EQ(md.find("{\"name\""), std::string::npos);
    // The cost of each study's runs, after the scorecard: element-cycles = rate x wall time.
    EXPECT_NE(md.find("## Solver cost"), std::string::npos);
    EXPECT_NE(md.find("| demo | 1 | 1234567 | 2.17 | 2170 | 1 | run 1 (2170 s) | 1 | 0 |"), std::string::npos) << md;
    // Headline by kind, reproduction first: series 3 + miss + 3 modes = 7 reproduction records, 5 pass.
    EXPECT_NE(md.find("Reproduction: 5 of 7 thesis results reproduced by our models, 2 not reproduced (known misses), 0 failed"),
              std::string::npos) << md.substr(0, 2000);
    EXPECT_NE(md.find("partly reproduced (5 of 7)"), std::string::npos);
    EXPECT_NE(md.find("## Not reproduced"), std::string::npos);
    EXPECT_NE(md.find("the joint is too soft"), std::string::npos);
    EXPECT_NE(md.find("## Entries changed after their first run"), std::string::npos);
    EXPECT_NE(md.find("a miss is not hidden as shown"), std::string::npos);
    EXPECT_TRUE(fs::exists(dir.path / "figures" / "REPORT.html"));
    // A table a study regenerated as Markdown is shown as a table, not as a (broken) image.
    std::ifstream html_in(dir.path / "figures" / "REPORT.html");
    const std::string html((std::istreambuf_iterator<char>(html_in)), {});
    EXPECT_EQ(html.find("<img src=\"table-9-1.md\""), std::string::npos);
    EXPECT_NE(md.find("Table 9-1, regenerated (table-9-1.md):\n\n| a |\n|---|\n| 1 |"), std::string::npos);
    // The page's filters: every check row carries its verdict, kind and basis.
    EXPECT_NE(html.find("data-verdict=\"miss\" data-kind=\"reproduction\" data-basis=\"model\""), std::string::npos);
    EXPECT_NE(html.find("<button class=\"badge miss\" data-filter=\"verdict=miss\" data-count=\"2\">"), std::string::npos);

    // fem-report refuses a reference entry without a kind, naming the file and the entry.
    auto no_kind = std::string(kReference);
    no_kind.replace(no_kind.find("kind = \"consistency\"\n"), std::string("kind = \"consistency\"\n").size(), "");
    write(dir.path / "reference" / "other.toml", no_kind);
    try {
        write_report({dir.path / "reference", dir.path / "results", dir.path / "figures"});
        ADD_FAILURE() << "a reference entry without a kind was accepted";
    } catch (const fem::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("other.toml"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("'table-9-1/a' lacks 'kind'"), std::string::npos) << e.what();
    }
}

TEST(Report, SolverRunsNameAFailedHealthAndSurviveAMalformedRunsFile) {
    TempDir dir;
    run_demo_study(dir.path);
    // A run that failed its health, one exempt from a limit (passed, its verdict says so), one whose
    // balance error was not a number (null in JSON), one without values, one with values of the wrong
    // types, a number.
    write(dir.path / "results" / "demo" / "runs.json", R"([
        {"name": "drop", "values": {"steps": 10, "timing_s": {"elements": 3.0, "update": 1.0}},
         "health": {"passed": false, "balance_error": 0.02, "balance_limit": 0.01, "balance_verdict": "failed",
                    "hourglass_fraction": 0.05, "hourglass_limit": 0.1, "hourglass_verdict": "ok"}},
        {"name": "slide", "values": {"steps": 20, "timing_s": {"elements": 1.0}},
         "health": {"passed": true, "balance_error": 0.001, "balance_limit": 0.01, "balance_verdict": "ok",
                    "hourglass_fraction": 0.5, "hourglass_limit": 0.1, "hourglass_verdict": "exempt",
                    "hourglass_exemption": "a rigid block"}},
        {"name": "blown", "values": {"steps": 30, "timing_s": {"elements": 1.0}},
         "health": {"passed": false, "balance_error": null, "balance_limit": 0.01, "balance_verdict": "failed",
                    "hourglass_fraction": null, "hourglass_limit": 0.1, "hourglass_verdict": "failed"}},
        {"name": "bare"},
        {"name": "odd", "values": {"steps": "many", "timing_s": {"elements": "x"}, "restarted_from": 3}, "health": []},
        7])");
    EXPECT_EQ(write_report({dir.path / "reference", dir.path / "results", dir.path / "figures"}), 0);
    std::ifstream md_in(dir.path / "figures" / "REPORT.md");
    const std::string md((std::istreambuf_iterator<char>(md_in)), {});
    EXPECT_NE(md.find("| drop |  |  |  | 10 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| failed: balance 0.02 > 0.01 |  |  | elements 75\u00a0%, update 25\u00a0% |"), std::string::npos) << md;
    EXPECT_NE(md.find("| exempt: hourglass 0.5 > 0.1 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| failed: balance (not a number), hourglass (not a number) |"), std::string::npos) << md;
    EXPECT_NE(md.find("| odd |  |  |  |  |"), std::string::npos) << md;  // "many" steps: not a count
    EXPECT_NE(md.find("| bare |"), std::string::npos) << md;
}

TEST(Report, DrawsThesisCurveValuesOnOurCurve) {
    TempDir dir;
    fs::create_directories(dir.path / "reference");
    const char* reference = R"toml(
study = "demo"
[[check]]
id = "fig-9-4/values"
source = "Fig 9-4"
quantity = "twist at two times"
unit = "deg"
basis = "model"
kind = "reproduction"
thesis = [10.0, 25.0]
labels = ["early", "peak"]
tolerance = { rel = 0.1 }
reason = "mesh"
curve = { file = "fig-9-4.dat", x = "t_ms", y = "twist_deg", x_label = "time (ms)", at = [1.0, 3.0] }
)toml";
    write(dir.path / "reference" / "demo.toml", reference);
    DemoArgs argv(dir.path / "reference" / "demo.toml", dir.path / "results" / "demo");
    {
        Study study("demo", argv.argc(), argv.data());
        // Our curve: twist = 10 t (deg, t in ms); the thesis's 25 deg at 3 ms lies 5 deg below it.
        fem::io::Table curve;
        curve.add("t_ms", {0.0, 2.0, 4.0}).add("twist_deg", {0.0, 20.0, 40.0});
        fem::io::write_dat(study.results_dir() / "fig-9-4.dat", curve);
        const std::vector<double> ours = {10.0, 30.0};
        study.check("fig-9-4/values", ours);
        EXPECT_EQ(study.finish(), 1);  // 30 against 25 +- 10 %: fails
    }
    std::ifstream in(dir.path / "results" / "demo" / "checks.json");
    const auto j = nlohmann::json::parse(in);
    EXPECT_EQ(j[1]["curve"]["at"], 3.0);
    EXPECT_EQ(CheckRecord::from_json(j[1]).on_curve->curve.y, "twist_deg");

    EXPECT_EQ(write_report({dir.path / "reference", dir.path / "results", dir.path / "figures"}), 1);
    std::ifstream md_in(dir.path / "figures" / "REPORT.md");
    const std::string md((std::istreambuf_iterator<char>(md_in)), {});
    EXPECT_NE(md.find("| fig-9-4/values/early | 1 | 10 | 9 .. 11 | 10 | 10 | pass |"), std::string::npos) << md;
    EXPECT_NE(md.find("| fig-9-4/values/peak | 3 | 25 | 22.5 .. 27.5 | 30 | 30 | FAIL |"), std::string::npos) << md;
    std::ifstream html_in(dir.path / "figures" / "REPORT.html");
    const std::string html((std::istreambuf_iterator<char>(html_in)), {});
    EXPECT_NE(html.find("<svg class=\"plot\""), std::string::npos);
    EXPECT_NE(html.find("<circle class=\"point fail\""), std::string::npos);
    EXPECT_NE(html.find("<circle class=\"point pass\""), std::string::npos);

    // An abscissa per thesis value, or the reference file is refused naming the entry.
    std::string bad = reference;
    bad.replace(bad.find("at = [1.0, 3.0]"), 15, "at = 1.0");
    write(dir.path / "reference" / "demo.toml", bad);
    try {
        load_reference(dir.path / "reference" / "demo.toml");
        ADD_FAILURE() << "a curve without an abscissa per value was accepted";
    } catch (const fem::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("'fig-9-4/values': curve needs 'at': 2"), std::string::npos) << e.what();
    }
}
