// fem-sweep's design sweeps (lib/explicit_case/sweep.hpp): the cases of a sweep file, each case the
// same run as the case file with its values set (fem-explicit --set), the table against the closed
// form of the bar wave, failed cases as rows, resuming, and bad sweeps refused before anything runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <tuple>

#include <unistd.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "check/build_paths.hpp"
#include "core/error.hpp"
#include "element/critical_time_step.hpp"
#include "explicit_case/case_file.hpp"
#include "explicit_case/sweep.hpp"

namespace fs = std::filesystem;
using namespace fem;
using namespace fem::explicit_case;

namespace {

const fs::path kCaseFiles = check::source_dir() / "tests/explicit_case/cases";

fs::path sweep_scratch(const std::string& name) {
    const fs::path p = fs::temp_directory_path() / ("fem_sweep_" + std::to_string(::getpid())) / name;
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

std::string file_text(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A sweep file in `dir` over the bar wave case (copied beside it) with the given parameter and result text.
fs::path sweep_file(const fs::path& dir, const std::string& body) {
    fs::copy_file(kCaseFiles / "bar_wave.toml", dir / "bar_wave.toml", fs::copy_options::overwrite_existing);
    std::ofstream(dir / "sweep.toml") << "case = \"bar_wave.toml\"\n" << body;
    return dir / "sweep.toml";
}

std::string sweep_error(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace

TEST(SweepFile, GridCasesVaryTheLastParameterFastestAndListCasesGoTogether) {
    const fs::path dir = sweep_scratch("grid");
    const Sweep grid = read_sweep(sweep_file(dir, R"(
[[parameter]]
key = "material[steel].E"
values = [70e9, 210e9]
[[parameter]]
key = "control.end_time"
values = [1e-4, 2e-4, 3e-4]
)"));
    ASSERT_EQ(grid.size(), 6);
    EXPECT_EQ(grid.settings(0)[0].value, "7e+10");
    EXPECT_EQ(grid.settings(0)[1].value, "1e-04");  // the shortest text that reads back to the same double
    EXPECT_EQ(grid.settings(2)[1].value, "3e-04");
    EXPECT_EQ(grid.settings(3)[0].value, "2.1e+11");
    EXPECT_EQ(grid.settings(3)[1].value, "1e-04");
    EXPECT_EQ(grid.case_folder(5), dir / "sweep_results" / "case-5");
    EXPECT_NE(grid.settings(4)[1].origin.find("sweep.toml:7: parameter[1] (control.end_time = 2e-04, case 4)"), std::string::npos)
        << grid.settings(4)[1].origin;

    const Sweep list = read_sweep(sweep_file(dir, R"(
combine = "list"
folder = "out"
[[parameter]]
key = "part[bar].elements"
values = [[10, 1, 1], [20, 1, 1], [40, 1, 1], [80, 1, 1], [160, 1, 1], [320, 1, 1], [640, 1, 1], [1280, 1, 1], [2560, 1, 1], [5120, 1, 1], [10240, 1, 1]]
[[parameter]]
key = "output.node[0].name"
values = ["a", "b", "c", "d", "e", "f", "g", "h", "i", "j", "k"]
[[parameter]]
key = "control.end_time"
values = [2e-4]
)"));
    ASSERT_EQ(list.size(), 11);
    EXPECT_EQ(list.settings(7)[2].value, "2e-04");  // one value: every case's
    EXPECT_EQ(list.settings(10)[0].value, "[10240, 1, 1]");
    EXPECT_EQ(list.shown_values(10)[1], "k");  // a string shown without its quotes
    EXPECT_EQ(list.case_folder(3), dir / "out" / "case-03");  // zero-padded to the largest number's digits
}

TEST(SweepFile, BadSweepsAreRefusedWithTheirLine) {
    const fs::path dir = sweep_scratch("bad-file");
    EXPECT_NE(sweep_error([&] { read_sweep(sweep_file(dir, "combine = \"list\"\n[[parameter]]\nkey = \"a\"\nvalues = [1, 2]\n[[parameter]]\n"
                                                   "key = \"b\"\nvalues = [1, 2, 3]\n")); })
                  .find("sweep.toml:5: parameter[0].values: combine = \"list\" takes the k-th value of every parameter together: 2 "
                        "values here, 3 in parameter[1] (one value would be used in every case)"),
              std::string::npos);
    EXPECT_NE(sweep_error([&] { read_sweep(sweep_file(dir, "[[parameter]]\nkey = \"a\"\nvalues = [1]\n[[parameter]]\nkey = \"a\"\nvalues = [2]\n")); })
                  .find("sweep.toml:6: parameter[1].key: 'a' is swept twice"),
              std::string::npos);
    EXPECT_NE(sweep_error([&] { read_sweep(sweep_file(dir, "combine = \"grid\"\n")); }).find("at least one [[parameter]]"), std::string::npos);
    EXPECT_NE(sweep_error([&] { read_sweep(sweep_file(dir, "[[parameter]]\nkey = \"a\"\nvalue = [1]\n")); }).find("did you mean 'values'?"),
              std::string::npos);
    EXPECT_NE(sweep_error([&] {
                  read_sweep(sweep_file(dir, "[[parameter]]\nkey = \"a\"\nvalues = [1]\n[[result]]\ncolumn = \"x\"\nreduce = \"mx\"\n"));
              }).find("did you mean 'max'?"),
              std::string::npos);
}

TEST(Sweep, EachCaseIsTheCaseFileWithItsValuesSetAndMatchesTheClosedForm) {
    const fs::path dir = sweep_scratch("bar");
    fs::copy_file(kCaseFiles / "bar_wave.toml", dir / "bar_wave.toml");
    fs::copy_file(kCaseFiles / "bar_wave_sweep.toml", dir / "bar_wave_sweep.toml");
    const Sweep sweep = read_sweep(dir / "bar_wave_sweep.toml");
    ASSERT_EQ(sweep.size(), 4);
    const SweepOutcome out = run_sweep(sweep, {.jobs = 2, .quiet = true});
    ASSERT_TRUE(out.all_ok()) << out.table;
    const std::size_t peak = sweep_solver_columns().size();  // the first [[result]]
    for (int k = 0; k < 4; ++k) {
        // The closed form of the free end at the run's end time T: 2 v0 (T - L/c).
        const double E = k < 2 ? 70e9 : 210e9, v0 = k % 2 == 0 ? 1.0 : 2.0;
        const double T = out.rows[k].numbers[1], c = std::sqrt(E / 7800.0);
        const double exact = 2.0 * v0 * (T - 1.0 / c);
        EXPECT_NEAR(out.rows[k].numbers[peak], exact, 0.01 * exact) << "case " << k;
        // The same run as the case file read with the case's settings (fem-explicit --set): the same bytes.
        ExplicitCase single = read_case(dir / "bar_wave.toml", sweep.settings(k));
        single.output.folder = dir / fmt::format("single-{}", k);
        ASSERT_TRUE(run_case(single, true).healthy());
        EXPECT_EQ(file_text(single.output.folder / "histories.dat"), file_text(sweep.case_folder(k) / "histories.dat")) << "case " << k;
    }
    // The table files: a header and one row per case.
    const std::string csv = file_text(sweep.folder / "sweep.csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);
    EXPECT_EQ(csv.substr(0, csv.find('\n')),
              "case,material[steel].E,boundary[0].velocity,status,steps,end_time_s,wall_s,element_cycles_per_s,"
              "energy_balance_relative_error,hourglass_fraction_of_internal,flat_hex_margin,free end peak ux,final kinetic energy");
    const nlohmann::json j = nlohmann::json::parse(file_text(sweep.folder / "sweep.json"));
    ASSERT_EQ(j.at("cases").size(), 4u);
    EXPECT_EQ(j["cases"][3]["settings"]["material[steel].E"], "2.1e+11");
    EXPECT_EQ(j["cases"][3]["values"]["free end peak ux"].get<double>(), out.rows[3].numbers[peak]);
    EXPECT_TRUE(fs::exists(sweep.folder / "sweep.dat"));
    // The figures: each result against Young's modulus, one line per impact velocity, drawn from sweep.gp.
    EXPECT_NE(out.table.find("figures: sweep-free_end_peak_ux.svg, sweep-final_kinetic_energy.svg"), std::string::npos) << out.table;
    const std::string gp = file_text(sweep.folder / "sweep.gp");
    EXPECT_NE(gp.find("set xlabel 'material[steel].E'"), std::string::npos);
    EXPECT_NE(gp.find("title 'boundary[0].velocity = [2.0, 0.0, 0.0]'"), std::string::npos);
    for (const char* svg : {"sweep-free_end_peak_ux.svg", "sweep-final_kinetic_energy.svg"})
        EXPECT_NE(file_text(sweep.folder / svg).find("</svg>"), std::string::npos) << svg;
}

TEST(Sweep, FailedCasesAreRowsAndAResumeKeepsCompletedCases) {
    const fs::path dir = sweep_scratch("resume");
    const Sweep sweep = read_sweep(sweep_file(dir, R"(
combine = "list"
[[parameter]]
key = "boundary[0].velocity"
values = [[1.0, 0.0, 0.0], [20000.0, 0.0, 0.0], [2.0, 0.0, 0.0]]
[[parameter]]
key = "control.end_time"
values = [1e-4, 1e-4, 2e-4]
)"));
    const SweepOutcome first = run_sweep(sweep, {.jobs = 1, .quiet = true});
    EXPECT_FALSE(first.all_ok());
    EXPECT_EQ(first.rows[0].status, "ok");
    EXPECT_EQ(first.rows[1].status, "unstable");  // 20 km/s inverts the struck element at once
    EXPECT_NE(first.rows[1].message.find("went unstable"), std::string::npos) << first.rows[1].message;
    EXPECT_TRUE(std::isnan(first.rows[1].numbers[0]));
    EXPECT_EQ(first.rows[2].status, "ok");
    EXPECT_NE(first.table.find("case 1 unstable: explicit run"), std::string::npos) << first.table;

    // Resumed: nothing runs again (each case's record and files untouched), the same rows.
    const std::string record = file_text(sweep.case_folder(2) / "sweep-case.json");
    const auto written = fs::last_write_time(sweep.case_folder(2) / "histories.dat");
    const SweepOutcome again = run_sweep(sweep, {.jobs = 1, .quiet = true, .resume = true});
    for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(again.rows[k].status, first.rows[k].status);
        for (std::size_t i = 0; i < first.rows[k].numbers.size(); ++i)
            if (!std::isnan(first.rows[k].numbers[i])) {
                EXPECT_EQ(again.rows[k].numbers[i], first.rows[k].numbers[i]);
            }
    }
    EXPECT_EQ(file_text(sweep.case_folder(2) / "sweep-case.json"), record);
    EXPECT_EQ(fs::last_write_time(sweep.case_folder(2) / "histories.dat"), written);

    // A case whose settings changed runs again; a smaller sweep into the folder removes the cases it no longer has.
    const Sweep smaller = read_sweep(sweep_file(dir, R"(
combine = "list"
[[parameter]]
key = "boundary[0].velocity"
values = [[1.0, 0.0, 0.0], [3.0, 0.0, 0.0]]
[[parameter]]
key = "control.end_time"
values = [1e-4, 1e-4]
)"));
    const SweepOutcome third = run_sweep(smaller, {.jobs = 1, .quiet = true, .resume = true});
    EXPECT_TRUE(third.all_ok()) << third.table;
    EXPECT_FALSE(fs::exists(sweep.case_folder(2)));
    EXPECT_EQ(fs::last_write_time(smaller.case_folder(0) / "histories.dat"), fs::last_write_time(sweep.case_folder(0) / "histories.dat"));
}

TEST(Sweep, ASettingTheCaseRefusesStopsTheSweepBeforeAnythingRuns) {
    const fs::path dir = sweep_scratch("refused");
    const Sweep sweep = read_sweep(sweep_file(dir, R"(
[[parameter]]
key = "material[steel].E"
values = [210e9, -1.0]
)"));
    EXPECT_EQ(sweep_error([&] { run_sweep(sweep, {.quiet = true}); }),
              fmt::format("{}:4: parameter[0] (material[steel].E = -1.0, case 1): material[0].E: must be a finite number > 0, got -1",
                          (dir / "sweep.toml").string()));
    EXPECT_FALSE(fs::exists(sweep.folder));  // nothing ran, nothing written

    // A result column the run does not write names the result and the file's columns.
    const Sweep bad_column = read_sweep(sweep_file(dir, R"(
[[parameter]]
key = "material[steel].E"
values = [210e9]
[[result]]
column = "free_end_uy"
reduce = "max"
)"));
    const std::string message = sweep_error([&] { run_sweep(bad_column, {.quiet = true}); });
    EXPECT_NE(message.find("result 'max free_end_uy': histories.dat has no column 'free_end_uy' (did you mean 'free_end_uy_m'?)"),
              std::string::npos)
        << message;
    EXPECT_FALSE(fs::exists(bad_column.folder));  // found before anything ran
}

TEST(Sweep, TheSummaryNamesTheFlatHexahedronNearestItsDampedStepLimit) {
    // bar_wave's 10 x 20 x 20 mm elements: cbrt(V) = 15.87 mm over V / A_max = 10 mm, not flat enough to
    // name. Cut into 1.25 mm slabs (800 elements) the ratio is 6.35: named, its damped limit
    // cfl::flat_hexahedron_step_factor over the step bound dt_scale x Table 2-1's (the slabs control the
    // step), and at dt_scale 0.5 far from it. 600 slabs at dt_scale 0.9 are within 3 % of it: the run
    // warns (and, as README "Flat hexahedra and bulk viscosity" measured, still runs).
    const fs::path dir = sweep_scratch("flat");
    struct Row {
        const char* elements;
        double dt_scale;
        bool named, warned;
    };
    for (const Row& row : {Row{"[100, 1, 1]", 0.5, false, false}, Row{"[800, 1, 1]", 0.5, true, false},
                           Row{"[600, 1, 1]", 0.9, true, true}}) {
        ExplicitCase c = read_case(kCaseFiles / "bar_wave.toml", {{"part[bar].elements", row.elements, "test"},
                                                                 {"control.end_time", "1e-6", "test"},
                                                                 {"control.dt_scale", fmt::format("{}", row.dt_scale), "test"}});
        c.output.folder = dir / row.elements;
        const CaseOutcome o = run_case(c, true);
        const nlohmann::json run = nlohmann::json::parse(file_text(c.output.folder / "run.json"));
        EXPECT_EQ(o.summary.find("flat hexahedron with bulk viscosity nearest its damped step limit: part 'bar' hex8 element") !=
                      std::string::npos,
                  row.named)
            << o.summary;
        EXPECT_EQ(o.summary.find("WARNING: the run's step bound is") != std::string::npos, row.warned) << o.summary;
        if (!row.named) {
            EXPECT_EQ(run.at("flat_hex").get<std::string>(), "");
            EXPECT_TRUE(run.at("flat_hex_ratio").is_null());  // no flat element: no number, not 0
            EXPECT_TRUE(run.at("flat_hex_margin").is_null());
            continue;
        }
        const int n = std::stoi(std::string(row.elements).substr(1));
        const double slab = 1.0 / n, ratio = std::cbrt(0.02 * 0.02 * slab) / slab;
        EXPECT_NEAR(run.at("flat_hex_ratio").get<double>(), ratio, 1e-9 * ratio) << row.elements;
        const double margin = cfl::flat_hexahedron_step_factor(ratio, BulkViscosity{}.linear) / row.dt_scale;
        EXPECT_NEAR(run.at("flat_hex_margin").get<double>(), margin, 1e-9 * margin) << row.elements;
    }
}

TEST(Sweep, TheFlatHexahedronMarginIsAColumnLeftEmptyWhereNoElementIsFlat) {
    // A mesh-density sweep shows how near each mesh's flattest hexahedron comes to its damped step
    // limit: the 100-element bar has none flat enough to name (an empty cell and null, not a margin
    // of 0), the 800 slabs have one: the case's run.json margin, which TheSummaryNames... above holds
    // to cfl::flat_hexahedron_step_factor.
    const fs::path dir = sweep_scratch("flat_column");
    const Sweep sweep = read_sweep(sweep_file(dir, R"(
[[parameter]]
key = "part[bar].elements"
values = [[100, 1, 1], [800, 1, 1]]
[[parameter]]
key = "control.end_time"
values = [1e-6]
[[parameter]]
key = "control.dt_scale"
values = [0.5]
)"));
    const SweepOutcome out = run_sweep(sweep, {.quiet = true});
    ASSERT_TRUE(out.all_ok()) << out.table;
    const nlohmann::json j = nlohmann::json::parse(file_text(sweep.folder / "sweep.json"));
    EXPECT_TRUE(j.at("cases").at(0).at("values").at("flat_hex_margin").is_null()) << j.dump(2);
    const double margin = j.at("cases").at(1).at("values").at("flat_hex_margin").get<double>();
    const nlohmann::json run = nlohmann::json::parse(file_text(sweep.case_folder(1) / "run.json"));
    EXPECT_EQ(margin, run.at("flat_hex_margin").get<double>());
    EXPECT_GT(margin, 1.0);  // dt_scale 0.5: far from the limit
    // sweep.csv: the column is the last of the solver's, before the results (none here); case 0's cell empty.
    const std::string csv = file_text(sweep.folder / "sweep.csv");
    const std::string header = csv.substr(0, csv.find('\n'));
    EXPECT_TRUE(header.ends_with(",hourglass_fraction_of_internal,flat_hex_margin")) << header;
    const std::size_t row0 = csv.find('\n') + 1;
    const std::string line0 = csv.substr(row0, csv.find('\n', row0) - row0);
    EXPECT_TRUE(line0.ends_with(",")) << line0;
}

TEST(Sweep, ListReadsEveryCaseAndRunsNothing) {
    const fs::path dir = sweep_scratch("list");
    const Sweep sweep = read_sweep(sweep_file(dir, R"(
[[parameter]]
key = "material[steel].E"
values = [70e9, 210e9]
[[parameter]]
key = "part[bar].elements"
values = [[10, 1, 1], [20, 1, 1]]
)"));
    const SweepOutcome listing = run_sweep(sweep, {.list = true});
    EXPECT_TRUE(listing.rows.empty());
    EXPECT_NE(listing.table.find("4 cases of"), std::string::npos) << listing.table;
    EXPECT_NE(listing.table.find("3     2.1e+11            [20, 1, 1]          " + sweep.case_folder(3).string()), std::string::npos)
        << listing.table;
    EXPECT_FALSE(fs::exists(sweep.folder));
    // A case the list cannot read is refused as a run would be.
    const Sweep bad = read_sweep(sweep_file(dir, "[[parameter]]\nkey = \"part[bar].elements\"\nvalues = [[10, 1, 1], [0, 1, 1]]\n"));
    EXPECT_NE(sweep_error([&] { run_sweep(bad, {.list = true}); }).find("parameter[0] (part[bar].elements = [0, 1, 1], case 1)"),
              std::string::npos);
}
