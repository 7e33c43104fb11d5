#include "explicit_case/sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <mutex>
#include <optional>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "check/cases.hpp"
#include "core/error.hpp"
#include "core/progress.hpp"
#include "explicit_case/case_file.hpp"
#include "io/atomic_file.hpp"
#include "io/gnuplot.hpp"
#include "io/run_folder.hpp"
#include "input/numbers.hpp"
#include "io/table.hpp"

namespace fem::explicit_case {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr const char* kCaseRecord = "sweep-case.json";  // in each case folder: its settings and status

// A string value's TOML text without its quotes (what a table shows); other values as they are.
std::string shown(const std::string& toml_text) {
    if (toml_text.size() >= 2 && toml_text.front() == '"' && toml_text.back() == '"') {
        try {
            return toml::parse("v = " + toml_text)["v"].value_or(toml_text);
        } catch (const toml::parse_error&) {
        }
    }
    return toml_text;
}

}  // namespace

// --- the sweep file -----------------------------------------------------------------------------------

int Sweep::size() const {
    if (parameters.empty()) return 1;
    if (!grid) {
        std::size_t n = 1;
        for (const auto& p : parameters) n = std::max(n, p.values.size());
        return static_cast<int>(n);
    }
    long long n = 1;
    for (const auto& p : parameters) n *= static_cast<long long>(p.values.size());
    return static_cast<int>(n);
}

namespace {
// The index of each parameter's value in case k.
std::vector<std::size_t> value_indices(const Sweep& s, int k) {
    std::vector<std::size_t> at(s.parameters.size(), static_cast<std::size_t>(k));
    for (std::size_t i = 0; i < s.parameters.size(); ++i)
        if (s.parameters[i].values.size() == 1) at[i] = 0;  // one value: the same in every case
    if (s.grid) {
        long long rest = k;
        for (std::size_t i = s.parameters.size(); i-- > 0;) {
            const auto n = static_cast<long long>(s.parameters[i].values.size());
            at[i] = static_cast<std::size_t>(rest % n);
            rest /= n;
        }
    }
    return at;
}
}  // namespace

std::vector<input::Setting> Sweep::settings(int k) const {
    const auto at = value_indices(*this, k);
    std::vector<input::Setting> out;
    for (std::size_t i = 0; i < parameters.size(); ++i) {
        const SweepParameter& p = parameters[i];
        const std::string& v = p.values[at[i]];
        out.push_back({p.key, v, fmt::format("{}:{}: parameter[{}] ({} = {}, case {})", source, p.line, i, p.key, v, k)});
    }
    return out;
}

std::vector<std::string> Sweep::shown_values(int k) const {
    const auto at = value_indices(*this, k);
    std::vector<std::string> out;
    for (std::size_t i = 0; i < parameters.size(); ++i) out.push_back(shown(parameters[i].values[at[i]]));
    return out;
}

std::filesystem::path Sweep::case_folder(int k) const {
    const int digits = static_cast<int>(std::to_string(std::max(0, size() - 1)).size());
    return folder / fmt::format("case-{:0{}}", k, digits);
}

Sweep read_sweep(const std::filesystem::path& file) {
    const input::TomlDocument doc = input::TomlDocument::read(file);
    const input::TomlTable root = doc.root();
    root.allow({"case", "combine", "folder", "parameter", "result"});
    Sweep s;
    s.source = doc.source();
    s.case_file = root.path("case");
    s.grid = root.choice_or("combine", {"grid", "list"}, "grid") == "grid";
    s.folder = root.has("folder") ? root.path("folder") : doc.base() / (file.stem().string() + "_results");
    std::set<std::string> keys;
    for (const input::TomlTable& t : root.tables("parameter")) {
        t.allow({"key", "values"});
        SweepParameter p;
        p.key = t.string("key");
        p.line = t.where("key").line;
        if (!keys.insert(p.key).second) t.fail("key", fmt::format("'{}' is swept twice", p.key));
        p.values = t.value_texts("values");
        s.parameters.push_back(std::move(p));
    }
    if (s.parameters.empty()) root.fail("parameter", "a sweep needs at least one [[parameter]] (key and values)");
    if (!s.grid) {  // every list as long as the longest, or one value for every case
        std::size_t longest = 0, which = 0;
        for (std::size_t i = 0; i < s.parameters.size(); ++i)
            if (s.parameters[i].values.size() > longest) longest = s.parameters[i].values.size(), which = i;
        for (std::size_t i = 0; i < s.parameters.size(); ++i)
            if (s.parameters[i].values.size() != longest && s.parameters[i].values.size() != 1)
                root.tables("parameter")[i].fail(
                    "values", fmt::format("combine = \"list\" takes the k-th value of every parameter together: {} values here, {} in "
                                          "parameter[{}] (one value would be used in every case)",
                                          s.parameters[i].values.size(), longest, which));
    }
    if (s.grid) {
        long long n = 1;
        for (const auto& p : s.parameters) n *= static_cast<long long>(p.values.size());
        if (n > 100000) root.fail("parameter", fmt::format("the grid has {} cases; more than 100,000 is surely a mistake", n));
    }
    std::set<std::string> names;
    for (const input::TomlTable& t : root.tables("result")) {
        t.allow({"name", "file", "column", "reduce", "phase"});
        SweepResult r;
        r.file = t.choice_or("file", {"histories", "energies"}, "histories");
        r.column = t.string("column");
        r.reduce = t.choice("reduce", {"max", "min", "max_abs", "final"});
        r.name = t.string_or("name", r.reduce + " " + r.column);
        r.phase = t.string_or("phase", "");
        r.line = t.where("column").line;
        if (!names.insert(r.name).second) t.fail("name", fmt::format("two results are named '{}'", r.name));
        s.results.push_back(std::move(r));
    }
    doc.finish();
    return s;
}

// --- rows -----------------------------------------------------------------------------------------------

const std::vector<std::string>& sweep_solver_columns() {
    static const std::vector<std::string> columns{"steps", "end_time_s", "wall_s", "element_cycles_per_s",
                                                  "energy_balance_relative_error", "hourglass_fraction_of_internal",
                                                  "flat_hex_margin"};
    return columns;
}

void to_json(nlohmann::json& j, const SweepRow& r) {
    nlohmann::json numbers = nlohmann::json::array();
    for (double v : r.numbers) numbers.push_back(std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr));
    j = {{"status", r.status}, {"message", r.message}, {"numbers", numbers}, {"wall_s", r.seconds}};
}

void from_json(const nlohmann::json& j, SweepRow& r) {
    r.status = j.at("status").get<std::string>();
    r.message = j.at("message").get<std::string>();
    r.numbers.clear();
    for (const auto& v : j.at("numbers")) r.numbers.push_back(v.is_null() ? kNaN : v.get<double>());
    r.seconds = j.at("wall_s").get<double>();
}

bool SweepOutcome::all_ok() const {
    return std::all_of(rows.begin(), rows.end(), [](const SweepRow& r) { return r.status == "ok"; });
}

namespace {

double reduce(const std::vector<double>& v, const std::string& how) {
    if (v.empty()) return kNaN;
    if (how == "final") return v.back();
    double out = how == "max_abs" ? std::abs(v.front()) : v.front();
    for (double x : v) {
        if (how == "max") out = std::max(out, x);
        else if (how == "min") out = std::min(out, x);
        else out = std::max(out, std::abs(x));
    }
    return out;
}

// The folder of a case's run whose files a row reads: the case folder, or its phase's subfolder.
std::filesystem::path run_folder(const ExplicitCase& c, const std::string& phase) {
    if (c.phases.empty()) return c.output.folder;
    return c.output.folder / (phase.empty() ? c.phases.back().name : phase);
}

// The numbers of a row from the files of a case's run. A result that cannot be read (a column the
// run did not write) is an InputError naming the result and the file's columns.
void read_numbers(const Sweep& s, const ExplicitCase& c, SweepRow& row) {
    row.numbers.assign(sweep_solver_columns().size() + s.results.size(), kNaN);
    const std::filesystem::path run_json = run_folder(c, "") / "run.json";
    if (std::ifstream in(run_json); in) {
        const nlohmann::json j = nlohmann::json::parse(in);
        for (std::size_t i = 0; i < sweep_solver_columns().size(); ++i)
            if (const auto it = j.find(sweep_solver_columns()[i]); it != j.end() && it->is_number()) row.numbers[i] = it->get<double>();
    }
    for (std::size_t i = 0; i < s.results.size(); ++i) {
        const SweepResult& r = s.results[i];
        const std::filesystem::path dat = run_folder(c, r.phase) / (r.file + ".dat");
        try {
            const io::Table t = io::read_dat(dat);
            row.numbers[sweep_solver_columns().size() + i] = reduce(io::column(t, r.column, dat), r.reduce);
        } catch (const InputError& e) {
            throw InputError(fmt::format("{}:{}: result '{}': {}", s.source, r.line, r.name, e.what()));
        }
    }
}

// sweep-case.json: a case's settings and how its run ended; a resumed sweep keeps the case when its
// settings are the same.
// A case's settings as JSON: key -> TOML text (sweep-case.json, sweep.json).
nlohmann::json settings_json(const std::vector<input::Setting>& settings) {
    nlohmann::json set = nlohmann::json::object();
    for (const auto& st : settings) set[st.key] = st.value;
    return set;
}

nlohmann::json case_record(const std::vector<input::Setting>& settings, const SweepRow& row) {
    return {{"settings", settings_json(settings)}, {"status", row.status}, {"message", row.message}, {"wall_s", row.seconds}};
}

std::optional<SweepRow> completed_case(const std::filesystem::path& folder, const std::vector<input::Setting>& settings) {
    std::ifstream in(folder / kCaseRecord);
    if (!in) return std::nullopt;
    try {
        const nlohmann::json j = nlohmann::json::parse(in);
        if (j.at("settings") != settings_json(settings)) return std::nullopt;
        SweepRow row;
        row.status = j.at("status").get<std::string>();
        row.message = j.at("message").get<std::string>();
        row.seconds = j.at("wall_s").get<double>();
        return row;
    } catch (const nlohmann::json::exception&) {
        return std::nullopt;  // not a record this program wrote: the case runs again
    }
}

std::string one_line(std::string s) {
    std::replace(s.begin(), s.end(), '\n', ' ');
    return s;
}

// A number as the table shows it (10 significant digits; empty for none).
std::string number_text(double v) { return std::isfinite(v) ? fmt::format("{:.10g}", v) : ""; }

// Rows of text in columns two spaces apart (the first row the header).
std::string aligned_table(const std::vector<std::vector<std::string>>& lines) {
    std::vector<std::size_t> width;
    for (const auto& line : lines)
        for (std::size_t i = 0; i < line.size(); ++i) {
            if (width.size() <= i) width.push_back(0);
            width[i] = std::max(width[i], line[i].size());
        }
    std::string out;
    for (const auto& line : lines) {
        std::string t;
        for (std::size_t i = 0; i < line.size(); ++i) t += fmt::format("{}{:<{}}", i ? "  " : "", line[i], width[i]);
        while (!t.empty() && t.back() == ' ') t.pop_back();
        out += t + "\n";
    }
    return out;
}

std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

// Every case's shown values (Sweep::shown_values), case by case.
std::vector<std::vector<std::string>> shown_table(const Sweep& s) {
    std::vector<std::vector<std::string>> shown;
    for (int k = 0; k < s.size(); ++k) shown.push_back(s.shown_values(k));
    return shown;
}

// Parameter i's value in every case when each is a number (whole-string, input::to_real), else none.
std::optional<std::vector<double>> numeric_values(const std::vector<std::vector<std::string>>& shown, std::size_t i) {
    std::vector<double> v;
    for (const auto& values : shown) {
        const std::optional<double> x = input::to_real(values[i]);
        if (!x) return std::nullopt;
        v.push_back(*x);
    }
    return v;
}

// sweep.gp and one SVG per [[result]] (sweep-<result>.svg): the result against the first parameter
// whose values are numbers and differ (else against the case number), one line per combination of
// the other parameters' values. The data are in the script, so `gnuplot sweep.gp` in the folder draws
// the same figures again. Returns the figures' names.
std::vector<std::string> write_plots(const Sweep& s, const std::vector<std::vector<std::string>>& shown,
                                     const std::vector<SweepRow>& rows, const std::filesystem::path& folder) {
    const int n = s.size();
    const std::size_t first_result = sweep_solver_columns().size();
    int x = -1;  // the parameter on the x axis
    std::vector<double> xs(n);
    for (int k = 0; k < n; ++k) xs[k] = k;
    for (std::size_t i = 0; i < s.parameters.size() && x < 0; ++i)
        if (const auto v = numeric_values(shown, i);
            v && std::all_of(v->begin(), v->end(), [](double a) { return std::isfinite(a); }) &&
            std::set<double>(v->begin(), v->end()).size() > 1) {
            x = static_cast<int>(i);
            xs = *v;
        }
    // The lines: cases grouped by the values of the parameters other than x that vary.
    std::vector<std::string> group_of(n);
    for (int k = 0; k < n; ++k)
        for (std::size_t i = 0; i < s.parameters.size(); ++i)
            if (static_cast<int>(i) != x && s.parameters[i].values.size() > 1)
                group_of[k] += fmt::format("{}{} = {}", group_of[k].empty() ? "" : ", ", s.parameters[i].key, shown[k][i]);
    std::vector<std::string> groups;
    for (const auto& g : group_of)
        if (std::find(groups.begin(), groups.end(), g) == groups.end()) groups.push_back(g);

    std::string gp = fmt::format(
        "# fem-sweep's figures of {} ({} cases): each [[result]] against {}, one line per combination of the\n"
        "# other parameters. Written with sweep.csv; `gnuplot sweep.gp` in this folder draws them again.\n"
        "if (!exists('folder')) folder = '.'\n"
        "set terminal svg size 900,560 noenhanced font 'sans,12' background rgb 'white'\n"
        "set grid\nset key outside bottom center horizontal font 'sans,10'\nset xlabel {}\n",
        s.source, n, x >= 0 ? s.parameters[x].key : "the case number", io::gnuplot_string(x >= 0 ? s.parameters[x].key : "case"));
    std::vector<std::string> figures;
    for (std::size_t r = 0; r < s.results.size(); ++r) {
        const std::string figure = "sweep-" + io::safe_file_name(s.results[r].name) + ".svg";
        std::string plot, data;
        for (std::size_t g = 0; g < groups.size(); ++g) {
            std::vector<std::pair<double, double>> points;
            for (int k = 0; k < n; ++k)
                if (group_of[k] == groups[g] && std::isfinite(rows[k].numbers[first_result + r]))
                    points.emplace_back(xs[k], rows[k].numbers[first_result + r]);
            std::sort(points.begin(), points.end());
            const std::string block = fmt::format("$r{}g{}", r, g);
            data += block + " << EOD\n";
            for (const auto& [px, py] : points) data += fmt::format("{} {}\n", px, py);
            data += "EOD\n";
            plot += fmt::format("{}{} using 1:2 with linespoints lw 2 pt 7 title {}", plot.empty() ? "plot " : ", \\\n     ", block,
                                io::gnuplot_string(groups[g].empty() ? s.results[r].name : groups[g]));
        }
        gp += fmt::format("\n# {}\n{}set output folder.'/{}'\nset title {}\nset ylabel {}\n{}\n", s.results[r].name, data, figure,
                          io::gnuplot_string(fmt::format("{} ({} of {})", s.results[r].name, s.results[r].reduce, s.results[r].column)),
                          io::gnuplot_string(s.results[r].column), plot);
        figures.push_back(figure);
    }
    io::write_text_file(folder / "sweep.gp", gp);
    return figures;
}

}  // namespace

// --- running ------------------------------------------------------------------------------------------

SweepOutcome run_sweep(const Sweep& s, const SweepOptions& options) {
    const InterruptGuard interrupts;
    const int n = s.size();
    // Every case read first: a setting that does not apply stops the sweep before anything runs.
    std::vector<ExplicitCase> cases;
    cases.reserve(n);
    for (int k = 0; k < n; ++k) {
        ExplicitCase c = read_case(s.case_file, s.settings(k));
        c.output.folder = s.case_folder(k);
        cases.push_back(std::move(c));
    }
    // Every result's column must be one the runs write (history_columns: the case's [[output.node]]s).
    for (const SweepResult& r : s.results)
        for (const ExplicitCase& c : cases) {
            if (!r.phase.empty() && std::none_of(c.phases.begin(), c.phases.end(), [&](const Phase& p) { return p.name == r.phase; }))
                throw InputError(fmt::format("{}:{}: result '{}': the case has no phase '{}'", s.source, r.line, r.name, r.phase));
            const std::vector<std::string> columns = r.file == "histories" ? history_columns(c) : energy_columns();
            if (std::find(columns.begin(), columns.end(), r.column) == columns.end())
                throw InputError(fmt::format("{}:{}: result '{}': {}.dat has no column '{}'{}; its columns: {}", s.source, r.line,
                                             r.name, r.file, r.column, input::did_you_mean(r.column, columns), fmt::join(columns, ", ")));
        }
    if (options.list) {  // the cases as read, nothing run
        SweepOutcome listing;
        std::vector<std::vector<std::string>> lines{{"case"}};
        for (const auto& p : s.parameters) lines[0].push_back(p.key);
        lines[0].push_back("folder");
        const std::vector<std::vector<std::string>> shown = shown_table(s);
        for (int k = 0; k < n; ++k) {
            std::vector<std::string> line{std::to_string(k)};
            for (const auto& v : shown[k]) line.push_back(v);
            line.push_back(s.case_folder(k).string());
            lines.push_back(std::move(line));
        }
        listing.table = fmt::format("fem-sweep: {} cases of {} ({}), each read; nothing run\n", n, s.case_file.string(),
                                    s.grid ? "grid" : "list") +
                        aligned_table(lines);
        return listing;
    }
    std::error_code ec;
    std::filesystem::create_directories(s.folder, ec);
    if (ec) throw InputError(fmt::format("{}: the sweep's folder '{}' cannot be created: {}", s.source, s.folder.string(), ec.message()));

    const bool rank0 = check::ranks().rank() == 0;
    std::mutex print;
    const auto run_one = [&](int k) {
        const ExplicitCase& c = cases[k];
        const std::vector<input::Setting> settings = s.settings(k);
        SweepRow row;
        bool ran = false;
        if (options.resume) {
            // A kept run must still have its files (the folder of a case that ran holds its manifest).
            const auto kept = completed_case(c.output.folder, settings);
            const bool has_files = std::filesystem::exists(c.output.folder / io::RunFolder::manifest_name);
            // An unstable case is kept (it would go unstable again); one that could not be built runs
            // again (a mesh file may have been fixed since).
            if (kept && (kept->status == "unstable" || (has_files && kept->status != "error"))) row = *kept;
        }
        // After Ctrl-C the cases not yet started do not start (the running ones stop and throw).
        if (row.status.empty() && interrupt_requested())
            throw Interrupted(fmt::format("case {} not started; run again with --resume to go on", k));
        if (row.status.empty()) {
            ran = true;
            const auto start = std::chrono::steady_clock::now();
            try {
                const CaseOutcome o = run_case(c, true, false);
                row.status = o.healthy() ? "ok" : "unhealthy";
                std::vector<std::string> why = o.unhealthy;
                why.insert(why.end(), o.stale_exemptions.begin(), o.stale_exemptions.end());
                for (const auto& w : why) {
                    if (!row.message.empty()) row.message += "; ";
                    row.message += one_line(w);
                }
            } catch (const Interrupted&) {
                throw;
            } catch (const SolverError& e) {  // an unstable run, or another failure of the solver
                row.status = std::string(e.what()).find("went unstable") != std::string::npos ? "unstable" : "error";
                row.message = one_line(e.what());
            } catch (const std::exception& e) {  // an input error found while building (a mesh file), or another
                row.status = "error";
                row.message = one_line(e.what());
            }
            row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            io::write_text_file(c.output.folder / kCaseRecord, case_record(settings, row).dump(2) + "\n");
        }
        if (row.status == "ok" || row.status == "unhealthy") read_numbers(s, c, row);
        else row.numbers.assign(sweep_solver_columns().size() + s.results.size(), kNaN);
        if (!options.quiet) {
            const std::lock_guard lock(print);
            std::string values;
            for (const auto& st : settings) values += fmt::format("{}{} = {}", values.empty() ? "" : ", ", st.key, st.value);
            std::cerr << fmt::format("fem-sweep: case {} of {} ({}): {}{}{}\n", k, n, values, row.status,
                                     ran ? fmt::format(", {:.3g} s", row.seconds) : std::string(", kept from the last run"),
                                     row.message.empty() ? "" : ": " + row.message);
        }
        return row;
    };
    SweepOutcome out;
    out.rows = check::run_cases<SweepRow>(check::case_jobs(options.jobs), n, run_one);

    // The table: case, the parameters' values, status, the solver's numbers, the results.
    std::vector<std::string> header{"case"};
    for (const auto& p : s.parameters) header.push_back(p.key);
    header.push_back("status");
    for (const auto& c : sweep_solver_columns()) header.push_back(c);
    for (const auto& r : s.results) header.push_back(r.name);
    const std::vector<std::vector<std::string>> shown = shown_table(s);
    std::vector<std::vector<std::string>> cells;
    for (int k = 0; k < n; ++k) {
        std::vector<std::string> line{std::to_string(k)};
        for (const auto& v : shown[k]) line.push_back(v);
        line.push_back(out.rows[k].status);
        for (double v : out.rows[k].numbers) line.push_back(number_text(v));
        cells.push_back(std::move(line));
    }
    std::vector<std::vector<std::string>> lines{header};
    lines.insert(lines.end(), cells.begin(), cells.end());
    out.table = fmt::format("fem-sweep: {} cases of {} ({})\n", n, s.case_file.string(), s.grid ? "grid" : "list");
    out.table += aligned_table(lines);
    for (int k = 0; k < n; ++k)
        if (!out.rows[k].message.empty()) out.table += fmt::format("case {} {}: {}\n", k, out.rows[k].status, out.rows[k].message);

    if (rank0) {
        std::string csv;
        const auto csv_line = [&](const std::vector<std::string>& line) {
            for (std::size_t i = 0; i < line.size(); ++i) {
                if (i) csv += ',';
                csv += csv_field(line[i]);
            }
            csv += '\n';
        };
        csv_line(header);
        for (const auto& line : cells) csv_line(line);
        io::write_text_file(s.folder / "sweep.csv", csv);
        // sweep.dat for gnuplot: the case number, the parameters that are single numbers, the numbers.
        io::Table dat;
        std::vector<double> index(n);
        for (int k = 0; k < n; ++k) index[k] = k;
        dat.add("case", index);
        for (std::size_t i = 0; i < s.parameters.size(); ++i)
            if (const auto v = numeric_values(shown, i)) dat.add(io::safe_file_name(s.parameters[i].key), *v);
        for (std::size_t j = 0; j < sweep_solver_columns().size() + s.results.size(); ++j) {
            std::vector<double> v(n);
            for (int k = 0; k < n; ++k) v[k] = out.rows[k].numbers[j];
            dat.add(io::safe_file_name(j < sweep_solver_columns().size() ? sweep_solver_columns()[j]
                                                                 : s.results[j - sweep_solver_columns().size()].name),
                    v);
        }
        io::write_dat(s.folder / "sweep.dat", dat);
        nlohmann::json j = {{"case_file", s.case_file.string()}, {"combine", s.grid ? "grid" : "list"}, {"cases", nlohmann::json::array()}};
        for (int k = 0; k < n; ++k) {
            const SweepRow& r = out.rows[k];
            nlohmann::json values = nlohmann::json::object();
            for (std::size_t i = 0; i < r.numbers.size(); ++i)  // header: case, parameters, status, then the numbers
                values[header[s.parameters.size() + 2 + i]] = std::isfinite(r.numbers[i]) ? nlohmann::json(r.numbers[i]) : nlohmann::json(nullptr);
            j["cases"].push_back({{"case", k}, {"folder", s.case_folder(k).filename().string()}, {"settings", settings_json(s.settings(k))},
                                  {"status", r.status}, {"message", r.message}, {"wall_s", r.seconds}, {"values", values}});
        }
        io::write_text_file(s.folder / "sweep.json", j.dump(2) + "\n");
        // The figures: drawn by gnuplot from sweep.gp; a machine without gnuplot still gets the table.
        if (!s.results.empty()) {
            const std::vector<std::string> figures = write_plots(s, shown, out.rows, s.folder);
            try {
                io::run_gnuplot(s.folder / "sweep.gp", {{"folder", s.folder.string()}});
                out.table += fmt::format("figures: {}\n", fmt::join(figures, ", "));
            } catch (const std::exception& e) {
                out.table += fmt::format("figures: not drawn ({}); sweep.gp holds them\n", one_line(e.what()));
            }
        }
        io::write_text_file(s.folder / "summary.txt", out.table);
        // Case folders of an earlier, larger sweep into this folder (they hold our sweep-case.json)
        // would read as results of this one: removed. Nothing else in the folder is touched.
        std::set<std::filesystem::path> ours;
        for (int k = 0; k < n; ++k) ours.insert(s.case_folder(k).filename());
        std::vector<std::filesystem::path> stale;
        for (const auto& e : std::filesystem::directory_iterator(s.folder))
            if (e.is_directory() && e.path().filename().string().rfind("case-", 0) == 0 && !ours.count(e.path().filename()) &&
                std::filesystem::exists(e.path() / kCaseRecord))
                stale.push_back(e.path());
        for (const auto& p : stale) std::filesystem::remove_all(p);
    }
    return out;
}

}  // namespace fem::explicit_case
