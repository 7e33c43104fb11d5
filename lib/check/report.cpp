#include "check/report.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <map>
#include <optional>
#include <set>
#include <tuple>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "check/reference.hpp"
#include "check/report_document.hpp"
#include "check/study.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/table.hpp"

namespace fem::check {
namespace {

using report::Block;
using report::number;

// CSS class of a verdict (the page's colours and filters).
std::string verdict_css(Verdict v) {
    switch (v) {
        case Verdict::Pass: return "pass";
        case Verdict::KnownMiss: return "miss";
        case Verdict::Shown: return "shown";
        case Verdict::NotRun: return "notrun";
        case Verdict::Fail:
        case Verdict::UnexpectedPass: return "fail";
    }
    return "";
}

// Our curve at x (linear between the first pair of neighbouring samples that brackets x); none when
// x lies outside the curve.
std::optional<double> interpolate(const std::vector<std::pair<double, double>>& curve, double x) {
    for (std::size_t i = 0; i + 1 < curve.size(); ++i) {
        const auto [xa, ya] = curve[i];
        const auto [xb, yb] = curve[i + 1];
        if ((xa <= x && x <= xb) || (xb <= x && x <= xa)) return xa == xb ? ya : ya + (yb - ya) * (x - xa) / (xb - xa);
    }
    return std::nullopt;
}


std::string value_text(const nlohmann::json& v) {
    if (v.is_null()) return "(none)";
    if (v.is_number()) return number(v.get<double>());
    if (v.is_string()) return v.get<std::string>();
    if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
    if (v.is_array()) {
        // A list of objects (a run's contact interfaces, its parts) one after the other: ';' between them.
        const bool objects = !v.empty() && v.front().is_object();
        std::string out;
        for (const auto& x : v) out += (out.empty() ? "" : objects ? "; " : ", ") + value_text(x);
        return out;
    }
    // An object (a run's timing table, one contact interface) as "name: key value, key value", its
    // name first, for a reader rather than as JSON.
    std::string out = v.contains("name") && v["name"].is_string() ? v["name"].get<std::string>() + ":" : "";
    for (const auto& [key, x] : v.items()) {
        if (key == "name") continue;
        out += (out.empty() ? "" : out.back() == ':' ? " " : ", ") + key + " " + value_text(x);
    }
    return out.empty() ? "(none)" : out;
}

std::string tolerance_text(const CheckRecord& r) {
    if (!r.tolerance) return r.basis == "trend" ? "must hold" : "-";
    std::string out;
    if (r.tolerance->rel > 0) out += number(100 * r.tolerance->rel) + " %";
    // An absolute tolerance on a value in percent is in percentage points.
    const std::string unit = r.unit == "%" ? "points" : r.unit;
    if (r.tolerance->abs > 0 || r.tolerance->rel == 0) out += (out.empty() ? "" : " + ") + number(r.tolerance->abs) + (unit.empty() ? "" : " " + unit);
    return out;
}

std::string thesis_text(const CheckRecord& r) {
    std::string thesis = value_text(r.thesis);
    if (r.reference) thesis += " (its data give " + number(*r.reference) + ")";
    return thesis;
}

// Counts of records by kind and verdict.
class Tally {
public:
    void add(const CheckRecord& r) {
        ++n_[{r.kind, verdict(r)}];
        if (r.reference) ++follows_[r.kind];
    }
    int count(Kind k, Verdict v) const {
        const auto it = n_.find({k, v});
        return it == n_.end() ? 0 : it->second;
    }
    int count(Kind k) const { return sum([&](Kind kk, Verdict) { return kk == k; }); }
    int count(Verdict v) const { return sum([&](Kind, Verdict vv) { return vv == v; }); }
    int count() const { return sum([](Kind, Verdict) { return true; }); }
    int failed(Kind k) const { return sum([&](Kind kk, Verdict v) { return kk == k && fails_study(v); }); }
    int failed() const { return sum([](Kind, Verdict v) { return fails_study(v); }); }
    /// Checks judged against the value that follows from the thesis's data rather than the printed one.
    int discrepancies(Kind k) const {
        const auto it = follows_.find(k);
        return it == follows_.end() ? 0 : it->second;
    }
    int discrepancies() const {
        int n = 0;
        for (const auto& [k, c] : follows_) n += c;
        return n;
    }

private:
    template <class Pred>
    int sum(Pred pred) const {
        int n = 0;
        for (const auto& [key, c] : n_)
            if (pred(key.first, key.second)) n += c;
        return n;
    }
    std::map<std::pair<Kind, Verdict>, int> n_;
    std::map<Kind, int> follows_;
};

/// A study's status in the summary: "reproduced" only when every reproduction check passes.
std::string study_status(bool has_results, const Tally& t) {
    if (!has_results) return "not run";
    if (t.failed() > 0) return "FAILING (" + std::to_string(t.failed()) + " failed)";
    // Checks not run (make all only) are left out of the status and named after it.
    const int not_run = t.count(Verdict::NotRun);
    const std::string after = not_run > 0 ? "; " + std::to_string(not_run) + " checks not run (make all only)" : "";
    const int n = t.count(Kind::Reproduction) - t.count(Kind::Reproduction, Verdict::NotRun),
              k = t.count(Kind::Reproduction, Verdict::Pass);
    if (n == 0) return "no reproduction checks" + after;
    if (k == n) return "reproduced" + after;
    return "partly reproduced (" + std::to_string(k) + " of " + std::to_string(n) + ")" + after;
}

std::string deviation_text(const CheckRecord& r) {
    auto d = r.deviation();
    if (!d) return "-";
    std::ostringstream s;
    s << std::showpos << std::fixed << std::setprecision(std::abs(*d) < 0.01 ? 3 : 1) << 100 * *d << " %";
    return s.str();
}

struct StudyResults {
    std::string name;
    std::optional<ReferenceFile> reference;
    std::vector<CheckRecord> records;
    nlohmann::json runs = nlohmann::json::array();
    bool has_results = false;
};

nlohmann::json read_json(const std::filesystem::path& path) {
    std::ifstream in(path);
    try {
        return nlohmann::json::parse(in);
    } catch (const nlohmann::json::parse_error& e) {
        throw InputError(path.string() + ": not valid JSON (" + e.what() + ")");
    }
}

// ---- A study's solver runs (runs.json) as the report's tables ---------------------------------------
// An explicit run's summary has some forty values (ExplicitSolver's RunSummary::to_json); a table of all
// of them was 38 columns of raw keys. The report shows what a reader of LS-DYNA's d3hsp looks for first:
// size, time and step, what controls the step, added mass, energy balance, hourglass, health, and
// where the wall time went. Every value stays in runs.json, which the section names.

// A run's values ({} when runs.json has none: a hand-edited or truncated file is shown, not fatal).
const nlohmann::json& values_of(const nlohmann::json& run) {
    static const nlohmann::json none = nlohmann::json::object();
    if (!run.is_object()) return none;
    const auto it = run.find("values");
    return it != run.end() && it->is_object() ? *it : none;
}

std::string name_of(const nlohmann::json& run) {
    const auto it = run.is_object() ? run.find("name") : run.end();
    return it != run.end() && it->is_string() ? it->get<std::string>() : "";
}

bool is_explicit_run(const nlohmann::json& run) {
    const nlohmann::json& v = values_of(run);
    return v.contains("steps") && v.contains("timing_s") && v["timing_s"].is_object();
}

std::optional<double> number_at(const nlohmann::json& object, const char* key) {
    const auto it = object.find(key);
    if (it == object.end() || !it->is_number()) return std::nullopt;
    return it->get<double>();
}

// Three significant digits, without an exponent from 1,000 to 1e9 (a wall time of 2170 s, not 2.17e+03).
std::string compact(double v) {
    return std::abs(v) >= 1e3 && std::abs(v) < 1e9 ? fmt::format("{:.0f}", v) : fmt::format("{:.3g}", v);
}

// The value at `key` as compact text, "" when the run does not have it.
std::string compact_at(const nlohmann::json& values, const char* key, double scale = 1.0) {
    const auto x = number_at(values, key);
    return x ? compact(scale * *x) : "";
}

// A count (nodes, steps) in full: 1234567, not 1.23457e+06.
std::string count_at(const nlohmann::json& values, const char* key) {
    const auto x = number_at(values, key);
    return x ? fmt::format("{:.0f}", *x) : "";
}

// "elements 84 %, update 15 %, contact 0.9 %": the timing table's shares of its total, largest first
// (contact = search + forces; the timers' own cost counts with "other"); a no-break space before each
// "%" keeps a share on one line of the table.
std::string time_split(const nlohmann::json& timing) {
    std::map<std::string, double> share;
    double total = 0;
    for (const auto& [key, t] : timing.items()) {
        if (!t.is_number()) continue;
        const std::string group = key.starts_with("contact") ? "contact" : key == "timers_own_cost" ? "other" : key;
        share[group] += t.get<double>();
        total += t.get<double>();
    }
    if (!(total > 0)) return "";
    std::vector<std::pair<double, std::string>> order;
    for (const auto& [group, t] : share)
        if (t >= 5e-4 * total) order.emplace_back(t, group);
    std::ranges::sort(order, std::greater<>());
    std::string out;
    for (const auto& [t, group] : order) out += (out.empty() ? "" : ", ") + group + " " + fmt::format("{:.2g}\u00a0%", 100 * t / total);
    return out;
}

// "ok"; "exempt" or "failed" with the limits the run broke, as its judgement recorded them
// (RunHealth::to_json: a verdict per limit).
std::string health_text(const nlohmann::json& run) {
    const auto it = run.is_object() ? run.find("health") : run.end();
    if (it == run.end() || !it->is_object()) return "-";
    const nlohmann::json& h = *it;
    const auto passed = h.find("passed");
    const bool ok = passed != h.end() && passed->is_boolean() && passed->get<bool>();
    std::string broken;  // "balance 0.02 > 0.01" per limit not met
    for (const auto& [what, value, limit] : {std::tuple{"balance", "balance_error", "balance_limit"},
                                             std::tuple{"hourglass", "hourglass_fraction", "hourglass_limit"}}) {
        const auto verdict = h.find(std::string(what) + "_verdict");
        if (verdict == h.end() || !verdict->is_string() || *verdict == "ok") continue;
        const auto x = number_at(h, value), lim = number_at(h, limit);
        broken += std::string(broken.empty() ? ": " : ", ") + what + (x ? " " + compact(*x) : " (not a number)");
        if (x && lim) broken += " > " + compact(*lim);
    }
    if (ok) return broken.empty() ? "ok" : "exempt" + broken;
    return "failed" + broken;
}

std::vector<std::string> explicit_run_row(const nlohmann::json& run) {
    const nlohmann::json& v = values_of(run);
    std::string name = name_of(run);
    if (const auto from = v.find("restarted_from"); from != v.end() && from->is_object())
        if (const auto t = number_at(*from, "time")) name += " (restarted at " + compact(*t) + " s)";
    std::string step = compact_at(v, "min_dt_s", 1e6);
    if (const std::string hi = compact_at(v, "max_dt_s", 1e6); !hi.empty() && hi != step) step += "-" + hi;
    const auto controlling = v.find("controlling_element");
    const std::string threads = count_at(v, "threads");
    return {name,
            count_at(v, "nodes"),
            count_at(v, "elements"),
            compact_at(v, "end_time_s"),
            count_at(v, "steps"),
            step,
            controlling != v.end() && controlling->is_string() ? controlling->get<std::string>() : "",
            compact_at(v, "added_mass_fraction", 100.0),
            compact_at(v, "energy_balance_relative_error"),
            compact_at(v, "hourglass_fraction_of_internal"),
            health_text(run),
            compact_at(v, "wall_s") + (threads.empty() ? "" : " (" + threads + ")"),
            compact_at(v, "element_cycles_per_s", 1e-6),
            time_split(v["timing_s"])};
}

// A runs.json key as a column heading: "wall_s" -> "wall (s)", "final_compliance_J" -> "final compliance (J)".
std::string key_heading(std::string key) {
    std::string unit;
    for (const char* u : {"_s", "_J", "_kg", "_m", "_Hz"})
        if (key.size() > std::strlen(u) && key.ends_with(u)) {
            unit = std::string(" (") + (u + 1) + ")";
            key.resize(key.size() - std::strlen(u));
            break;
        }
    std::ranges::replace(key, '_', ' ');
    return key + unit;
}

// The solver runs of a study: the explicit runs in the table above, the other runs (modal, topology
// optimization: a dozen values each) with all their values.
std::vector<Block> solver_run_tables(const nlohmann::json& runs) {
    std::vector<Block> out;
    Block expl{Block::Table};
    expl.header = {"run", "nodes", "elements", "end time (s)", "steps", "step (us)", "controlling element (at the end)", "added mass (%)",
                   "energy balance error", "hourglass / internal", "health", "wall (s) (threads)", "M element-cycles/s",
                   "where the wall time went"};
    std::vector<std::string> keys;
    std::vector<const nlohmann::json*> others;
    for (const auto& run : runs) {
        if (is_explicit_run(run)) {
            expl.rows.push_back(explicit_run_row(run));
            continue;
        }
        others.push_back(&run);
        for (const auto& [k, x] : values_of(run).items())
            if (k != "name" && std::ranges::find(keys, k) == keys.end()) keys.push_back(k);
    }
    if (!expl.rows.empty()) out.push_back(std::move(expl));
    if (!others.empty()) {
        Block other{Block::Table};
        other.header = {"run"};
        for (const auto& k : keys) other.header.push_back(key_heading(k));
        for (const nlohmann::json* run : others) {
            std::vector<std::string> row = {name_of(*run)};
            const nlohmann::json& v = values_of(*run);
            for (const auto& k : keys) row.push_back(v.contains(k) ? value_text(v[k]) : "");
            other.rows.push_back(std::move(row));
        }
        out.push_back(std::move(other));
    }
    return out;
}

// The cost of every study's recorded solver runs, one row a study: where the project's CPU goes
// (explicit runs: steps and element-cycles, the solver's own measure; other runs: their wall time).
// Runs of a study may have run at once on several cores, so the summed wall time is work, not the
// study's elapsed time.
Block solver_cost_table(const std::vector<StudyResults>& studies) {
    Block t{Block::Table};
    t.header = {"study", "explicit runs", "steps", "element-cycles (G)", "explicit wall time, summed (s)",
                "M element-cycles/s (overall)", "longest explicit run", "other runs", "their wall time, summed (s)"};
    for (const auto& s : studies) {
        int n_explicit = 0, n_other = 0;
        double steps = 0, cycles = 0, wall = 0, other_wall = 0, longest = -1;
        std::string longest_name;
        for (const auto& run : s.runs) {
            const nlohmann::json& v = values_of(run);
            const double w = number_at(v, "wall_s").value_or(0.0);
            if (!is_explicit_run(run)) {
                ++n_other;
                other_wall += w;
                continue;
            }
            ++n_explicit;
            steps += number_at(v, "steps").value_or(0.0);
            cycles += number_at(v, "element_cycles_per_s").value_or(0.0) * w;
            wall += w;
            if (w > longest) longest = w, longest_name = name_of(run);
        }
        if (n_explicit + n_other == 0) continue;
        t.rows.push_back({s.name, std::to_string(n_explicit), n_explicit ? fmt::format("{:.0f}", steps) : "",
                          n_explicit ? compact(cycles * 1e-9) : "", n_explicit ? compact(wall) : "",
                          wall > 0 ? compact(cycles / wall * 1e-6) : "",
                          n_explicit ? longest_name + " (" + compact(longest) + " s)" : "", std::to_string(n_other),
                          n_other ? compact(other_wall) : ""});
    }
    return t;
}

// Thesis order of items: by chapter (the appendices, lettered, after the chapters), then tables,
// figures, equations, sections, appendices, then number: "Table 5-4" before "Fig 5-10" before
// "Sec 5.4.2, Figs 5-20, 5-24"; "Fig D-2" and "App E" after every chapter.
std::string item_sort_key(const std::string& item) {
    // A run of digits zero-padded to 6, so that text order is number order (5-4 before 5-10).
    const auto padded = [](const std::string& digits) { return std::string(6 - std::min<std::size_t>(6, digits.size()), '0') + digits; };
    const std::size_t space = item.find(' ');
    std::string chapter = "~";  // no chapter: last
    for (std::size_t i = space == std::string::npos ? item.size() : space + 1; i < item.size(); ++i) {
        const unsigned char c = item[i];
        if (std::isdigit(c)) {
            std::size_t end = i;
            while (end < item.size() && std::isdigit(static_cast<unsigned char>(item[end]))) ++end;
            chapter = padded(item.substr(i, end - i));
            break;
        }
        if (std::isupper(c)) {
            chapter = std::string("~") + item[i];  // an appendix
            break;
        }
    }
    char kind = '5';
    for (const auto& [prefix, rank] : {std::pair{"Table", '0'}, {"Fig", '1'}, {"Eq", '2'}, {"Sec", '3'}, {"App", '4'}})
        if (item.rfind(prefix, 0) == 0) {
            kind = rank;
            break;
        }
    // Then the numbers after the kind's word ("Figs 5-10, 5-11" between "Fig 5-6" and "Fig 5-11"),
    // zero-padded so that 5-4 sorts before 5-10; the whole item breaks ties.
    std::string key = chapter + kind;
    std::string digits;
    auto flush = [&]() {
        if (!digits.empty()) {
            key += padded(digits);
            digits.clear();
        }
    };
    for (char c : item.substr(space == std::string::npos ? item.size() : space) + "\x01" + item) {
        if (std::isdigit(static_cast<unsigned char>(c))) digits += c;
        else {
            flush();
            key += c;
        }
    }
    flush();
    return key;
}

// Does the report item `item` (a check's source, "Table 2-2, Fig 2-5") name the figure item
// `figure` ("Table 2-2")? Whole numbers only: "Fig 5-14" does not name "Fig 5-1".
bool names_item(const std::string& item, const std::string& figure) {
    for (std::size_t at = item.find(figure); at != std::string::npos; at = item.find(figure, at + 1)) {
        const std::size_t end = at + figure.size();
        if (end == item.size() || !std::isdigit(static_cast<unsigned char>(item[end]))) return true;
    }
    return false;
}

}  // namespace

int write_report(const ReportInputs& in) {
    // Studies: every reference file, in the canonical order, then any others alphabetically.
    std::vector<StudyResults> studies;
    std::vector<std::string> names;
    if (std::filesystem::exists(in.reference_dir))
        for (const auto& f : std::filesystem::directory_iterator(in.reference_dir))
            if (f.path().extension() == ".toml") names.push_back(f.path().stem().string());
    if (std::filesystem::exists(in.results_dir))
        for (const auto& d : std::filesystem::directory_iterator(in.results_dir))
            if (std::filesystem::exists(d.path() / "checks.json")) names.push_back(d.path().filename().string());
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    const auto& order = study_order();
    std::stable_sort(names.begin(), names.end(), [&](const std::string& a, const std::string& b) {
        auto ia = std::find(order.begin(), order.end(), a) - order.begin();
        auto ib = std::find(order.begin(), order.end(), b) - order.begin();
        return ia < ib;
    });
    for (const auto& name : names) {
        StudyResults s;
        s.name = name;
        const auto ref_path = in.reference_dir / (name + ".toml");
        if (std::filesystem::exists(ref_path)) s.reference = load_reference(ref_path);
        const auto checks_path = in.results_dir / name / "checks.json";
        if (std::filesystem::exists(checks_path)) {
            s.has_results = true;
            for (const auto& j : read_json(checks_path)) s.records.push_back(CheckRecord::from_json(j));
        }
        const auto runs_path = in.results_dir / name / "runs.json";
        if (std::filesystem::exists(runs_path)) s.runs = read_json(runs_path);
        studies.push_back(std::move(s));
    }

    // Every verdict comes from check::verdict(); the counts, the summary, the sections below and the
    // study tables all read this one tally.
    Tally all;
    for (const auto& s : studies)
        for (const auto& r : s.records) all.add(r);

    std::vector<Block> doc;
    auto heading = [&](int level, std::string text) { doc.push_back({Block::Heading, level, std::move(text)}); };
    auto paragraph = [&](std::string text) { doc.push_back({Block::Paragraph, 0, std::move(text)}); };

    const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::ostringstream stamp;
    stamp << std::put_time(std::gmtime(&now), "%Y-%m-%d %H:%M UTC");
    heading(1, "Reproduction report");
    paragraph("Every table and figure of the thesis \"A Finite Element Based Dynamic Modeling Method for Design "
              "Analysis of Flexible Multibody Systems\" that a study of this project checks: the regenerated "
              "figure, the thesis's value, ours, the deviation, the tolerance (with its basis: exact, model, "
              "reconstructed, trend or experiment, and its reason), the verdict and the note. Each check states its "
              "kind: reproduction (our model's output against a result the thesis printed), trend (a conclusion the "
              "thesis draws, tested on our results), consistency (the thesis's own numbers and formulas re-derived), "
              "verification (a method recovers a known input, or a property holds by construction) or shown "
              "(nothing to judge against). A known miss is judged like any other check and counted as not "
              "reproduced. Generated " + stamp.str() + ".");
    {
        // The counts at the top; on the page each is a button that filters the checks to those it counts.
        Block by_verdict{Block::Badges};
        by_verdict.text = "Checks by verdict:";
        for (Verdict v : {Verdict::Pass, Verdict::KnownMiss, Verdict::Shown, Verdict::NotRun})
            if (v != Verdict::NotRun || all.count(v) > 0)  // not run: only in a report of a run without --full
                by_verdict.badges.push_back({std::string(verdict_label(v)), all.count(v), "verdict=" + verdict_css(v), verdict_css(v)});
        by_verdict.badges.push_back({"failed", all.failed(), "verdict=fail", "fail"});
        int discrepancies = 0;
        for (const auto& s : studies)
            for (const auto& r : s.records) discrepancies += !r.discrepancy.empty();
        by_verdict.badges.push_back({"thesis discrepancies", discrepancies, "disc=1", "disc"});
        doc.push_back(by_verdict);
        Block by_kind{Block::Badges};
        by_kind.text = "Checks by kind:";
        for (Kind k : all_kinds())
            by_kind.badges.push_back({std::string(kind_name(k)), all.count(k), "kind=" + std::string(kind_name(k)), "kind"});
        doc.push_back(by_kind);
    }
    heading(2, "Scorecard");
    {
        const int n = all.count(Kind::Reproduction);
        paragraph("Reproduction: " + std::to_string(all.count(Kind::Reproduction, Verdict::Pass)) + " of " +
                  std::to_string(n) + " thesis results reproduced by our models, " +
                  std::to_string(all.count(Kind::Reproduction, Verdict::KnownMiss)) + " not reproduced (known misses), " +
                  std::to_string(all.failed(Kind::Reproduction)) + " failed" +
                  (all.count(Verdict::NotRun) > 0
                       ? "; " + std::to_string(all.count(Verdict::NotRun)) +
                             " checks were not run: `make all` (--full) judges them, their runs cost more than CTest's budget"
                       : std::string()) +
                  ". All " + std::to_string(all.count()) + " checks by kind and verdict:");
    }
    {
        Block kinds{Block::Table};
        kinds.header = {"kind", "checks", "passed", "not reproduced (known misses)", "failed", "shown",
                        "not run (make all only)", "against a value that follows from the thesis's data"};
        for (Kind k : all_kinds())
            kinds.rows.push_back({std::string(kind_name(k)), std::to_string(all.count(k)),
                                  std::to_string(all.count(k, Verdict::Pass)), std::to_string(all.count(k, Verdict::KnownMiss)),
                                  std::to_string(all.failed(k)), std::to_string(all.count(k, Verdict::Shown)),
                                  std::to_string(all.count(k, Verdict::NotRun)), std::to_string(all.discrepancies(k))});
        kinds.rows.push_back({"all", std::to_string(all.count()), std::to_string(all.count(Verdict::Pass)),
                              std::to_string(all.count(Verdict::KnownMiss)), std::to_string(all.failed()),
                              std::to_string(all.count(Verdict::Shown)), std::to_string(all.count(Verdict::NotRun)),
                              std::to_string(all.discrepancies())});
        doc.push_back(kinds);
    }

    Block summary{Block::Table};
    summary.header = {"study", "thesis section", "reproduction passed", "not reproduced", "trends held", "consistency",
                      "verification", "shown", "failed", "status"};
    for (const auto& s : studies) {
        Tally t;
        for (const auto& r : s.records) t.add(r);
        auto held = [&](Kind k) { return std::to_string(t.count(k, Verdict::Pass)) + " of " + std::to_string(t.count(k)); };
        summary.rows.push_back({s.name, s.reference ? s.reference->section : "", held(Kind::Reproduction),
                                std::to_string(t.count(Verdict::KnownMiss)), held(Kind::Trend), held(Kind::Consistency),
                                held(Kind::Verification), std::to_string(t.count(Verdict::Shown)), std::to_string(t.failed()),
                                study_status(s.has_results, t)});
    }
    doc.push_back(summary);
    paragraph("Status: \"reproduced\" when every reproduction check of the study passes, \"partly reproduced (k of n)\" "
              "otherwise; \"FAILING\" when a check fails unexpectedly (a miss that is not a known miss, or a known "
              "miss that now passes).");
    if (const Block cost = solver_cost_table(studies); !cost.rows.empty()) {
        heading(2, "Solver cost");
        paragraph("What the studies' recorded solver runs cost in this run of them (each study's \"Solver runs\" table "
                  "has the runs; runs.json every value): explicit runs in steps and element-cycles, the solver's measure "
                  "of work, and wall time summed over the runs, which may have run at once on several cores.");
        doc.push_back(cost);
    }

    // Failures first when there are any: they make the studies exit non-zero.
    if (all.failed() > 0) {
        heading(2, "Failed checks");
        Block failed{Block::Table};
        failed.header = {"study", "item", "check", "kind", "thesis", "ours", "deviation", "tolerance", "verdict"};
        for (const auto& s : studies)
            for (const auto& r : s.records)
                if (fails_study(verdict(r)))
                    failed.rows.push_back({s.name, r.source, r.id, std::string(kind_name(r.kind)), thesis_text(r),
                                           value_text(r.reproduced), deviation_text(r), tolerance_text(r),
                                           std::string(verdict_label(verdict(r)))});
        doc.push_back(failed);
    }

    // What we do not reproduce, beside what the thesis gets wrong.
    heading(2, "Not reproduced");
    {
        // One row per entry: the members of a series that miss share their reason.
        Block miss{Block::Table};
        miss.header = {"study", "item", "check", "kind", "thesis", "ours", "deviation", "tolerance", "why we miss"};
        std::string last_key;
        for (const auto& s : studies)
            for (const auto& r : s.records) {
                if (verdict(r) != Verdict::KnownMiss) continue;
                const std::string key = s.name + "\x01" + r.source + "\x01" + r.quantity + "\x01" + r.known_miss;
                if (key == last_key) {
                    auto& row = miss.rows.back();
                    row[2] += ", " + r.id.substr(r.id.rfind('/') + 1);
                    row[4] += "; " + thesis_text(r);
                    row[5] += "; " + value_text(r.reproduced);
                    row[6] += "; " + deviation_text(r);
                    continue;
                }
                last_key = key;
                miss.rows.push_back({s.name, r.source, r.id, std::string(kind_name(r.kind)), thesis_text(r),
                                     value_text(r.reproduced), deviation_text(r), tolerance_text(r), r.known_miss});
            }
        if (miss.rows.empty()) paragraph("None.");
        else {
            paragraph("Known misses: thesis results our models do not reach yet, each judged against the printed value "
                      "with its tolerance, with why we miss, what was tried and the hypothesis (the study's README "
                      "has the investigation). A known miss that starts to pass fails its study until its entry is "
                      "updated.");
            doc.push_back(miss);
        }
    }

    // Thesis discrepancies: every check whose reference carries one.
    heading(2, "Thesis discrepancies");
    Block disc{Block::Table};
    disc.header = {"item", "check", "thesis prints", "follows from the thesis's data", "ours", "verdict", "explanation"};
    for (const auto& s : studies)
        for (const auto& r : s.records)
            if (!r.discrepancy.empty())
                disc.rows.push_back({r.source, r.id, value_text(r.thesis), r.reference ? number(*r.reference) : "-",
                                     value_text(r.reproduced), std::string(verdict_label(verdict(r))), r.discrepancy});
    if (disc.rows.empty()) paragraph("None recorded yet.");
    else {
        paragraph("Where the thesis contradicts its own data, the check compares ours with the value that follows "
                  "from the thesis's data and lists the printed value here. These checks are consistency checks: "
                  "agreement with the corrected value, not with the printed one.");
        doc.push_back(disc);
    }

    // Entries changed after their first run, with their earlier form (series members share one history).
    heading(2, "Entries changed after their first run");
    {
        Block changed{Block::Table};
        changed.header = {"study", "check", "date", "change", "was", "why"};
        std::set<std::string> seen;
        for (const auto& s : studies)
            for (const auto& r : s.records) {
                if (r.history.empty() || !seen.insert(s.name + "\x01" + r.source + "\x01" + r.quantity).second) continue;
                for (const auto& h : r.history) changed.rows.push_back({s.name, r.id, h.date, h.change, h.was, h.why});
            }
        if (changed.rows.empty()) paragraph("None.");
        else doc.push_back(changed);
    }

    // A figure of an item: an image, or a table the study regenerated as Markdown (shown as a table).
    auto add_figure = [&](const std::string& item, const std::string& file) {
        const auto path = in.figures_dir / file;
        if (!std::filesystem::exists(path)) {
            paragraph("(" + item + ": " + file + " not drawn yet: run `make all`)");
        } else if (path.extension() == ".md") {
            std::ifstream md(path);
            const std::string text((std::istreambuf_iterator<char>(md)), {});
            paragraph(item + ", regenerated (" + file + "):");
            for (auto& b : report::markdown_blocks(text)) doc.push_back(std::move(b));
        } else {
            doc.push_back({Block::Image, 0, item, file});
        }
    };
    // Thesis values that lie on a curve of ours (reference key `curve`): one plot per curve.
    auto add_curve_plots = [&](const std::string& study, const std::vector<const CheckRecord*>& records) {
        std::map<std::tuple<std::string, std::string, std::string>, std::vector<const CheckRecord*>> curves;
        for (const CheckRecord* r : records)
            if (r->on_curve && r->thesis.is_number())
                curves[{r->on_curve->curve.file, r->on_curve->curve.x, r->on_curve->curve.y}].push_back(r);
        for (const auto& [key, points] : curves) {
            const CurveRef& ref = points.front()->on_curve->curve;
            Block plot{Block::Plot};
            const CheckRecord& first = *points.front();
            plot.plot.title = first.quantity + " (" + ref.file + ": " + ref.y + " over " + ref.x + ")";
            plot.plot.x_label = ref.x_label.empty() ? ref.x : ref.x_label;
            plot.plot.y_label = !ref.y_label.empty() ? ref.y_label : ref.y + (first.unit.empty() ? "" : " (" + first.unit + ")");
            try {
                const auto path = in.results_dir / study / ref.file;
                const io::Table data = io::read_dat(path);
                const auto& xs = io::column(data, ref.x, path);
                const auto& ys = io::column(data, ref.y, path);
                for (std::size_t i = 0; i < xs.size(); ++i) plot.plot.curve.emplace_back(xs[i], ys[i]);
            } catch (const InputError& e) {
                paragraph(std::string("(curve of ") + first.id + " not drawn: " + e.what() + ")");
                continue;
            }
            for (const CheckRecord* r : points) {
                report::Plot::Point p;
                p.id = r->id;
                p.x = r->on_curve->at;
                p.thesis = r->thesis.get<double>();
                const double against = r->reference.value_or(p.thesis);
                const double band = r->tolerance ? r->tolerance->abs + r->tolerance->rel * std::abs(against) : 0.0;
                p.low = against - band;
                p.high = against + band;
                p.ours_on_curve = interpolate(plot.plot.curve, p.x);
                p.ours = value_text(r->reproduced);
                p.verdict = verdict_label(verdict(*r));
                p.css = verdict_css(verdict(*r));
                plot.plot.points.push_back(p);
            }
            doc.push_back(std::move(plot));
        }
    };

    for (const auto& s : studies) {
        const std::string title = s.reference ? s.reference->title : s.name;
        heading(2, s.name + ": " + title);
        doc.back().nav = s.name;
        if (s.reference && !s.reference->section.empty()) paragraph("Thesis " + s.reference->section + ". Study: `studies/" + s.name + "/`, reference values: `reference/" + s.name + ".toml`.");
        if (s.reference && !s.reference->summary.empty()) paragraph(s.reference->summary);
        if (!s.has_results) {
            paragraph("Not run: no build/results/" + s.name + "/checks.json. Run `make " + s.name + "`.");
            continue;
        }
        // Items in thesis order; an item's figures come first, then its checks. A figure item (reference
        // [figures]) belongs to the first checked item that names it ("Table 2-2" to "Table 2-2, Fig 2-5");
        // one that none names is an item of its own, in its place in the order.
        std::map<std::string, std::vector<const CheckRecord*>> items;
        for (const auto& r : s.records) items[item_sort_key(r.source) + "\x01" + r.source].push_back(&r);
        const auto item_of = [](const std::string& key) { return key.substr(key.rfind('\x01') + 1); };
        if (s.reference)
            for (const auto& figure : s.reference->figures) {
                const std::string& fig_item = figure.first;
                const bool named = std::ranges::any_of(items, [&](const auto& i) { return names_item(item_of(i.first), fig_item); });
                if (!named) items.try_emplace(item_sort_key(fig_item) + "\x01" + fig_item);
            }
        std::set<std::string> figure_item_done;
        for (const auto& [key, records] : items) {
            const std::string item = item_of(key);
            heading(3, item);
            if (s.reference) {
                for (const auto& [fig_item, files] : s.reference->figures) {
                    if (!names_item(item, fig_item) || !figure_item_done.insert(fig_item).second) continue;
                    for (const auto& file : files) add_figure(fig_item, file);
                }
            }
            if (records.empty()) continue;  // a figure item without checks
            add_curve_plots(s.name, records);
            Block table{Block::Table};
            table.header = {"check", "kind", "quantity", "unit", "basis", "thesis", "ours", "deviation", "tolerance", "verdict", "note"};
            for (const CheckRecord* r : records) {
                std::string note = r->note;
                auto append = [&](const std::string& label, const std::string& text) {
                    if (!text.empty()) note += (note.empty() ? "" : " ") + label + text;
                };
                append("Not reproduced: ", r->known_miss);
                append("Discrepancy: ", r->discrepancy);
                append("Tolerance: ", r->reason);
                for (const auto& h : r->history)
                    append("History (" + h.date + "): ", h.change + "; was: " + h.was + "; why: " + h.why);
                table.rows.push_back({r->id, std::string(kind_name(r->kind)), r->quantity, r->unit, r->basis, thesis_text(*r),
                                      value_text(r->reproduced), deviation_text(*r), tolerance_text(*r),
                                      std::string(verdict_label(verdict(*r))), note});
                table.tags.push_back({verdict_css(verdict(*r)), std::string(kind_name(r->kind)), r->basis, !r->discrepancy.empty()});
            }
            doc.push_back(table);
        }
        if (!s.runs.empty()) {
            heading(3, "Solver runs");
            paragraph("Every value of every run (energies, step limits, per-part and per-contact-interface figures, the "
                      "timing table in seconds): `build/results/" + s.name + "/runs.json`.");
            for (Block& table : solver_run_tables(s.runs)) doc.push_back(std::move(table));
        }
    }

    std::filesystem::create_directories(in.figures_dir);
    io::write_text_file(in.figures_dir / "REPORT.md", report::to_markdown(doc));
    io::write_text_file(in.figures_dir / "REPORT.html", report::to_html(doc));
    return all.failed();
}

}  // namespace fem::check
