#pragma once
// The thesis's values for one study, as written in reference/<study>.toml before any result is
// seen: for every check its source (table, figure, equation), quantity, unit, basis, tolerance and
// the reason for that tolerance. See reference/README.md for the file format.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace fem::check {

/// Allowed deviation |ours - reference| <= abs + rel * |reference|.
struct Tolerance {
    double rel = 0.0;
    double abs = 0.0;
    bool allows(double reproduced, double reference) const;
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
    bool judged = true;  // false: shown beside ours (e.g. an experiment the model cannot reach)

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

/// Reads and validates a reference file; throws InputError naming the file, line and field.
ReferenceFile load_reference(const std::filesystem::path& path);

}  // namespace fem::check
