#pragma once
// The report's document model: write_report() (report.cpp) builds one list of blocks from the check
// records, and the two writers below render it, as Markdown (figures/REPORT.md) and as a browsable
// web page (figures/REPORT.html), so that the two never disagree. Every verdict in it comes from
// check::verdict(); the writers classify nothing.
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace fem::check::report {

/// What a check-table row is, for the page's filters (HTML data attributes).
struct RowTags {
    std::string verdict;  // pass | fail | miss | shown (verdict_css)
    std::string kind;     // reproduction | consistency | verification | trend | shown
    std::string basis;    // exact | model | reconstructed | trend | experiment
    bool discrepancy = false;  // the thesis contradicts its own data (the check's `discrepancy`)
};

/// A count at the top of the report; on the page a button that filters the checks to those it counts.
struct Badge {
    std::string label;   // "not reproduced"
    int count = 0;
    std::string filter;  // "verdict=miss", "kind=reproduction", "disc=1"
    std::string css;     // pass | fail | miss | shown | kind
};

/// Thesis values that lie on one of our curves: the curve, and each value at its abscissa with its
/// tolerance band.
struct Plot {
    std::string title;             // "fig-3-41.dat: loading_line_deg over t_ms"
    std::string x_label, y_label;  // axis titles
    std::vector<std::pair<double, double>> curve;  // ours, in file order
    struct Point {
        std::string id;         // check id
        double x = 0, thesis = 0;
        double low = 0, high = 0;   // the tolerance band around the value judged against
        std::optional<double> ours_on_curve;  // our curve interpolated at x
        std::string ours;       // the check's reproduced value, as text
        std::string verdict;    // verdict label
        std::string css;        // verdict css
    };
    std::vector<Point> points;
};

struct Block {
    enum Kind { Heading, Paragraph, Table, Image, Plot, Badges } kind;
    int level = 0;
    std::string text;                            // heading / paragraph / image caption
    std::string file;                            // image
    std::vector<std::string> header;             // table
    std::vector<std::vector<std::string>> rows;  // table
    std::vector<RowTags> tags;                   // table: one per row when it lists checks, else empty
    std::string nav;                             // heading: its entry in the page's navigation (default: text)
    report::Plot plot;                           // plot
    std::vector<Badge> badges;                   // badges
};

/// A number as the report prints it (6 significant digits).
std::string number(double v);

std::string to_markdown(const std::vector<Block>& doc);
std::string to_html(const std::vector<Block>& doc);

/// A Markdown file's tables and paragraphs as blocks (the regenerated tables studies write).
std::vector<Block> markdown_blocks(const std::string& text);

/// The SVG drawing of a plot (inline in the page).
std::string plot_svg(const report::Plot& plot);

}  // namespace fem::check::report
