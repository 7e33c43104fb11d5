#pragma once
// The reproduction report: every check of every study that has run, grouped by thesis item, with
// the regenerated figures, and a section for the thesis discrepancies found. Written as Markdown
// (figures/REPORT.md) and as a static HTML page beside it (figures/REPORT.html).
#include <filesystem>

namespace fem::check {

struct ReportInputs {
    std::filesystem::path reference_dir;  // reference/*.toml: titles, sections, figure lists
    std::filesystem::path results_dir;    // build/results/<study>/checks.json and runs.json
    std::filesystem::path figures_dir;    // where the figures are and the report goes
};

/// Writes REPORT.md and REPORT.html; returns the number of failed checks.
int write_report(const ReportInputs& in);

}  // namespace fem::check
