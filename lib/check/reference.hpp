#pragma once
// The thesis's values for one study, as written in reference/<study>.toml: for every check its source
// (table, figure, equation), quantity, unit, basis, kind, tolerance and the reason for that tolerance,
// whether it is a known miss, and how the entry changed after its first run. See reference/README.md
// for the file format and DESIGN.md ("Tolerance policy") for the rules.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace fem::check {

/// Allowed deviation |ours - reference| <= abs + rel * |reference|.
struct Tolerance {
    double rel = 0.0;
    double abs = 0.0;
    bool allows(double reproduced, double reference) const;
};

/// What a check tests (issue 13; DESIGN.md "Outputs"). The report counts each kind on its own and
/// leads with reproduction.
enum class Kind {
    Reproduction,  // our model's output against a result the thesis printed
    Consistency,   // the thesis's own numbers and formulas re-derived (refits, closed forms, discrepancies)
    Verification,  // a method recovers a known input, or a property that holds by construction
    Trend,         // a conclusion the thesis draws, tested on our results
    Shown,         // nothing to judge against (experiment curves not printed, diagnostics): never judged
};
/// "reproduction", "consistency", ... as written in reference files and check records.
std::string_view kind_name(Kind kind);
/// The kind named `name`; std::nullopt for an unknown name.
std::optional<Kind> parse_kind(std::string_view name);
/// Every kind, reproduction first (the report's order).
const std::vector<Kind>& all_kinds();

/// One change of an entry after its first run (tolerance, measurand, kind, known-miss status):
/// the earlier form and the reason, kept in the entry and shown by the report.
struct HistoryEntry {
    std::string date;    // "2026-12-01"
    std::string change;  // what changed
    std::string was;     // the earlier form
    std::string why;     // the reason
};

/// One of our curves, a column of a data file the study writes into its results folder
/// (build/results/<study>/<file>, whitespace-separated, the first line "# <column names>").
struct CurveRef {
    std::string file;     // "fig-3-41.dat"
    std::string x, y;     // column names: "t_ms", "loading_line_deg"
    std::string x_label, y_label;  // axis titles; the column names when empty
};

/// Where a thesis value lies on one of our curves: the report draws the curve and marks the
/// thesis's point (at, thesis value) on it, with its tolerance (reference file key `curve`).
struct CurvePoint {
    CurveRef curve;
    double at = 0.0;  // the abscissa of the thesis's value, in the x column's unit
};

/// One [[check]] entry of a reference file.
struct ReferenceEntry {
    std::string id;        // "table-2-2/quad-2/steps-1ms"
    std::string source;    // "Table 2-2": the thesis item the report files it under
    std::string quantity;  // "steps to solve 1 ms"
    std::string unit;      // "us", "" for a pure number
    std::string basis;     // exact | model | reconstructed | trend | experiment
    // The thesis's printed value: a number, a statement (trend checks), or a series of numbers.
    std::variant<double, std::string, std::vector<double>> thesis;
    std::vector<std::string> labels;     // names of a series' members (default 1, 2, ...)
    std::optional<Tolerance> tolerance;  // absent for trend checks and for shown-only values
    std::string reason;                  // why this tolerance
    std::string note;                    // what a reader should know about the comparison
    // A thesis inconsistency: the value that follows from the thesis's own data (checked against
    // instead of the printed one), and the explanation.
    std::optional<double> follows;
    std::string discrepancy;
    Kind kind = Kind::Reproduction;  // required in the file
    // A known miss: a reproduction (or trend) we do not reach yet, with why, what was tried and the
    // hypothesis. Still judged with its tolerance; the study accepts it while it misses and fails
    // when it starts to pass, so that the entry gets updated.
    std::string known_miss;
    // For a series: the members (labels) that are known misses; empty means every member.
    std::vector<std::string> known_miss_labels;
    std::vector<HistoryEntry> history;
    // Judged only by `make all` (--full), with why: the runs it needs cost more than CTest's budget
    // (chicken_shackling's Step 3: five 1.1 s runs, ~100 CPU minutes). A run without --full lists the
    // entry as not run (Verdict::NotRun); with --full it is judged like any other.
    std::string full_only;
    // Where the thesis printed a value of a curve: our curve and the abscissa of each value (one per
    // member of a series), e.g. curve = { file = "fig-3-41.dat", x = "t_ms", y = "twist_deg", at = 5.7 }.
    std::optional<CurveRef> curve;
    std::vector<double> curve_at;

    /// The curve point of the single value, or of series member k.
    std::optional<CurvePoint> curve_point(std::size_t k = 0) const;

    /// Judged against the thesis: every kind but Shown.
    bool judged() const { return kind != Kind::Shown; }
    bool is_known_miss() const { return !known_miss.empty(); }
    bool is_full_only() const { return !full_only.empty(); }
    /// Whether the series member `label` (or the single value, label empty) is a known miss.
    bool member_is_known_miss(const std::string& label) const;
    /// The label of series member k (the entry's labels, or "1", "2", ...).
    std::string member_label(std::size_t k) const;
    bool is_trend() const { return std::holds_alternative<std::string>(thesis); }
    bool is_series() const { return std::holds_alternative<std::vector<double>>(thesis); }
};

/// A whole reference file.
struct ReferenceFile {
    std::string study;
    std::string title;    // "Critical time step: Tables 2-1..2-3, Figs 2-5, 2-6"
    std::string section;  // "Sec 2.3.2-2.3.5"
    std::string summary;  // a paragraph for the report
    // Report item ("Fig 2-6", "Table 2-2") -> figure files in figures/ that show it.
    std::map<std::string, std::vector<std::string>> figures;
    std::vector<ReferenceEntry> entries;

    /// The entry with this id; throws std::out_of_range naming the id and the file.
    const ReferenceEntry& entry(std::string_view id) const;
    std::filesystem::path path;
};

/// reference/<study>.toml of the source tree this program was built from (a study's default
/// reference file, whatever the current directory).
std::filesystem::path default_reference_path(std::string_view study);

/// Reads and validates a reference file; throws InputError naming the file, line and field.
ReferenceFile load_reference(const std::filesystem::path& path);

}  // namespace fem::check
