#pragma once
// What a study program uses to compare its results with the thesis. A study:
//
//   int main(int argc, char** argv) {
//       return fem::check::run_study("cfl_tables", argc, argv, [](fem::check::Study& study) {
//           ...
//           study.check("table-2-2/quad-2/dt", dt / units::us);          // numeric, from the reference file
//           study.trend("sec-2.3.5/obs-1", most_sensitive_parameter);    // statement vs statement
//           study.plot();                                                // runs studies/<name>/<name>.gp
//       });
//   }
//
// Every check id must exist in reference/<study>.toml (tolerance written before the run), and every
// entry of that file must be checked: a forgotten entry fails the study. finish() writes
// build/results/<study>/checks.json (DESIGN.md format), prints a table, and gives the exit status.
#include <filesystem>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "check/reference.hpp"
#include "check/run_health.hpp"

namespace fem::io {
class RunFolder;
}

namespace fem::check {

/// One line of checks.json.
struct CheckRecord {
    std::string id, source, quantity, unit, basis;
    Kind kind = Kind::Reproduction;
    nlohmann::json thesis;      // printed value (number or statement)
    nlohmann::json reproduced;  // ours
    std::optional<double> reference;  // the value compared against when it is not the printed one
    std::optional<Tolerance> tolerance;
    std::optional<bool> passed;  // within tolerance (trend: holds); empty for kind "shown"
    std::string note, discrepancy, reason;
    std::string known_miss;      // why this is expected to miss (empty: it is expected to pass)
    std::string full_only;       // why only `make all` (--full) judges it (ReferenceEntry::full_only)
    bool not_run = false;        // a full_only check in a run without --full: listed, not judged
    std::vector<HistoryEntry> history;
    std::optional<CurvePoint> on_curve;  // the thesis value is a point of this curve of ours (report plot)

    nlohmann::json to_json() const;
    /// Throws InputError for a record without a valid kind (written before kinds existed: re-run).
    static CheckRecord from_json(const nlohmann::json& j);
    /// Relative deviation of ours from the printed thesis value, when both are numbers.
    std::optional<double> deviation() const;
};

/// The verdict of a record: the one place that classifies checks (studies' exit status, the report's
/// counts, tables and sections all use it).
enum class Verdict {
    Pass,            // within tolerance / the trend holds
    Fail,            // misses, and is not a known miss
    KnownMiss,       // misses, as its entry's known_miss says: "not reproduced"
    UnexpectedPass,  // a known miss that now passes: fails the study until the entry is updated
    Shown,           // kind "shown": nothing to judge against
    NotRun,          // a full_only check in a run without --full (CTest): judged by `make all` only
};
Verdict verdict(const CheckRecord& r);
/// "pass", "FAIL", "not reproduced", "FAIL: known miss passes", "shown", "not run (make all only)".
std::string_view verdict_label(Verdict v);
/// Whether the verdict fails the study (Fail, UnexpectedPass).
bool fails_study(Verdict v);

/// The run summary of one solver run, listed in the report (wall time, steps, element-cycles/s).
struct RunRecord {
    std::string name;
    nlohmann::json values;  // e.g. {"nodes": 1234, "elements": 1000, "steps": 5000, "wall_s": 1.2, ...}
};

class Study {
public:
    /// Parses the command line (--results DIR, --figures DIR, --reference FILE, --help) and loads
    /// reference/<name>.toml.
    Study(std::string name, int argc, char** argv);
    ~Study();

    const std::string& name() const { return name_; }
    /// Where the study writes its results: the staging folder of build/results/<study>/
    /// (io::RunFolder: checked and locked on construction; finish() moves the files into place, so
    /// the folder always holds one complete run's set).
    const std::filesystem::path& results_dir() const { return results_dir_; }
    /// The source tree (studies/<name>/ holds a study's case file and gnuplot script).
    const std::filesystem::path& source_dir() const { return source_dir_; }
    /// Where figures are drawn (figures/ for `make`, build/figures for CTest); empty: none.
    const std::filesystem::path& figures_dir() const { return figures_dir_; }
    const ReferenceFile& reference() const { return reference_; }
    /// --full: also run the thesis-size runs CTest leaves out (`make all` passes it). They may only
    /// add shown results, and judge the reference entries marked full_only: checks.json is the same
    /// with and without it but for those, which a run without --full lists as not run.
    bool full() const { return full_; }
    /// --jobs N: independent cases run at once (check/cases.hpp); 0 when not given.
    int jobs() const { return jobs_; }

    /// Numeric check of `reproduced` against the entry `id`.
    const CheckRecord& check(std::string_view id, double reproduced, std::string note = {});
    /// Series check: one record per member, ids "<id>/<label>".
    void check(std::string_view id, std::span<const double> reproduced, std::string note = {});
    /// Trend check: passes when our statement equals the thesis's.
    const CheckRecord& trend(std::string_view id, std::string reproduced, std::string note = {});
    /// Trend check whose truth the study computes; `reproduced` says what we found.
    const CheckRecord& trend_holds(std::string_view id, bool holds, std::string reproduced, std::string note = {});

    /// Writes a regenerated thesis table (Markdown, e.g. "table-2-2.md") into the results folder and,
    /// when figures are drawn, into the figures folder beside them (the report shows it there).
    void write_markdown(const std::string& file_name, const std::string& text) const;

    /// Adds a solver run to runs.json and the report.
    void record_run(RunRecord run);

    /// Draws the study's figures when a figures folder was given: runs studies/<name>/<name>.gp
    /// twice with the string variables results, figures, term and ext set (term 'svg', ext 'svg';
    /// then term 'pngcairo', ext 'png'). Scripts open each figure with
    ///   set terminal @term size 900,650 enhanced font 'sans,12' background rgb 'white'
    ///   set output figures.'/fig-2-6.'.ext
    void plot();

    /// Writes checks.json and runs.json, puts the run's files in place (replacing the previous run's
    /// set), prints the verdicts; returns 0 when every check passed.
    int finish();

    const std::deque<CheckRecord>& records() const { return records_; }

private:
    const CheckRecord& add(CheckRecord record);
    /// The entry `id`, refused (std::logic_error) when it is full_only and this run is not --full.
    const ReferenceEntry& entry_to_check(std::string_view id) const;
    CheckRecord start_record(const ReferenceEntry& e, std::string note) const;

    std::string name_;
    std::filesystem::path results_dir_, figures_dir_, source_dir_;
    bool full_ = false;
    int jobs_ = 0;
    bool scratch_ = false;  // an MPI rank other than 0: results_dir_ is a scratch folder, removed at finish()
    ReferenceFile reference_;
    std::deque<CheckRecord> records_;  // deque: references handed out stay valid
    std::vector<std::string> checked_ids_;
    std::vector<RunRecord> runs_;
    std::unique_ptr<io::RunFolder> output_;
    std::vector<HealthExemption> health_exemptions_;  // reference file's [[health_exemption]] (run_health.hpp)
};

/// main() of a study: builds the Study, runs body, finishes; InputError/SolverError become a
/// message and a non-zero exit (see fem::run_program).
int run_study(std::string name, int argc, char** argv, const std::function<void(Study&)>& body);

/// The options every study program takes (Study's constructor reads them; a study with side runs of
/// its own, e.g. chicken_shackling --grasp, knows them so as to refuse them by name there).
const std::vector<std::string_view>& study_options();
/// A study program's usage (its --help) on standard output.
void print_study_usage(const std::string& name);

/// The canonical order of the thesis's studies (DESIGN.md), used by the report.
const std::vector<std::string>& study_order();

}  // namespace fem::check
