// fem-compare-results: are two runs of a study the same apart from timings? For the CTest tests that
// run a study or fem-sweep over MPI ranks against its serial run (check/cases.hpp).
//   fem-compare-results [--skip NAME ...] <serial dir> <other dir> [<serial figures dir> <other figures dir>]
// Every file under <other dir> must exist under <serial dir> with the same bytes, and every file of
// <serial dir> must exist under <other dir>; JSON files (runs.json, a run's run.json, fem-sweep's
// sweep.json) are compared with the facts of the run's environment removed from each run's values
// (wall and CPU times, rates, thread counts, the timing split), tables (.dat, .csv with a header
// line) without the columns so named, Markdown files (a study's table-3-2.md) without the columns of
// their tables whose heading names a wall time or a rate. Files named by --skip (a run's summary.txt, whose text quotes
// its timings) are only required to exist. With figure folders: every file of <other figures dir> must equal its namesake in <serial
// figures dir> (which holds every study's figures). Prints each difference; exit 1 when any.
// (Environment keys: the explicit summary's wall_s, element_cycles_per_s, threads, timing_s,
// contact_share and its contact interfaces' search_s and forces_s; a study's own wall and set-up
// times, topology_cases' s_per_iteration. Markdown columns: a heading that starts with "wall s" or
// names element-cycles/s, as finger_damping's Table 3-2 of wall times.)
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

namespace {
std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// What a run's values may differ in between two runs of the same study: facts of the machine and
// the schedule, not of the results.
bool environment_key(const std::string& key) {
    static const std::set<std::string> keys = {"wall_s",   "cpu_s",         "setup_s",  "element_cycles_per_s",
                                               "threads",  "contact_share", "search_s", "forces_s",
                                               "s_per_iteration"};
    return keys.count(key) > 0 || key.rfind("timing", 0) == 0 || key.rfind("time_split", 0) == 0;
}

nlohmann::json without_environment(nlohmann::json j) {
    if (j.is_object()) {
        nlohmann::json out = nlohmann::json::object();
        for (auto it = j.begin(); it != j.end(); ++it)
            if (!environment_key(it.key())) out[it.key()] = without_environment(it.value());
        return out;
    }
    if (j.is_array()) {
        for (auto& x : j) x = without_environment(x);
        return j;
    }
    return j;
}

int differences = 0;
void differ(const std::string& what) {
    ++differences;
    std::cout << "DIFFERS: " << what << '\n';
}

// A text's lines (without their line ends).
std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::string line;
    for (char c : text) {
        if (c == '\n') lines.push_back(line), line.clear();
        else line += c;
    }
    if (!line.empty()) lines.push_back(line);
    return lines;
}

// The fields of one line of a table: whitespace-separated (.dat, '#' header), or comma-separated
// with "quoted" fields (.csv).
std::vector<std::string> fields(const std::string& line, bool csv) {
    std::vector<std::string> out;
    std::string f;
    bool quoted = false, any = false;
    for (char c : line) {
        if (csv && c == '"') quoted = !quoted;
        const bool split = csv ? (c == ',' && !quoted) : (c == ' ' || c == '\t');
        if (split) {
            if (csv || any) out.push_back(f);
            f.clear();
            any = false;
        } else {
            f += c;
            any = true;
        }
    }
    if (csv || any) out.push_back(f);
    return out;
}

// A table's text without its environment columns (named in the first line).
std::string without_environment_columns(const std::string& text, bool csv) {
    const std::vector<std::string> lines = lines_of(text);
    if (lines.empty()) return text;
    std::vector<std::string> header = fields(lines[0], csv);
    if (!csv && !header.empty() && header[0] == "#") header.erase(header.begin());
    std::set<std::size_t> drop;
    for (std::size_t i = 0; i < header.size(); ++i)
        if (environment_key(header[i])) drop.insert(i);
    std::string out;
    for (std::size_t l = 0; l < lines.size(); ++l) {
        std::vector<std::string> f = fields(lines[l], csv);
        if (l == 0 && !csv && !f.empty() && f[0] == "#") f.erase(f.begin());
        for (std::size_t i = 0; i < f.size(); ++i)
            if (!drop.count(i)) out += f[i] + "|";
        out += "\n";
    }
    return out;
}

// A Markdown table's column heading that names a fact of the run's environment.
bool environment_heading(const std::string& heading) {
    return heading.rfind("wall s", 0) == 0 || heading.find("element-cycles/s") != std::string::npos ||
           environment_key(heading);
}

// The cells of a Markdown table row "| a | b |", trimmed.
std::vector<std::string> cells(const std::string& row) {
    std::vector<std::string> out;
    std::string cell;
    for (std::size_t i = 1; i < row.size(); ++i) {
        if (row[i] != '|') {
            cell += row[i];
            continue;
        }
        const auto first = cell.find_first_not_of(' '), last = cell.find_last_not_of(' ');
        out.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
        cell.clear();
    }
    return out;
}

// A Markdown text without the environment columns of its tables (a table's heading row is the row
// above its |---| rule); every other line as it is.
std::string without_environment_markdown(const std::string& text) {
    const std::vector<std::string> lines = lines_of(text);
    std::string out;
    std::set<std::size_t> drop;  // the current table's environment columns
    for (std::size_t l = 0; l < lines.size(); ++l) {
        if (lines[l].empty() || lines[l][0] != '|') {
            drop.clear();
            out += lines[l] + "\n";
            continue;
        }
        if (l + 1 < lines.size() && lines[l + 1].rfind("|---", 0) == 0) {  // a heading row starts a table
            drop.clear();
            const std::vector<std::string> headings = cells(lines[l]);
            for (std::size_t i = 0; i < headings.size(); ++i)
                if (environment_heading(headings[i])) drop.insert(i);
        }
        const std::vector<std::string> row = cells(lines[l]);
        for (std::size_t i = 0; i < row.size(); ++i)
            if (!drop.count(i)) out += row[i] + "|";
        out += "\n";
    }
    return out;
}

std::set<std::string> skipped;  // --skip NAME

void compare_file(const fs::path& a, const fs::path& b) {
    if (!fs::exists(a)) return differ(b.string() + " has no counterpart " + a.string());
    if (skipped.count(a.filename().string())) return;
    if (a.extension() == ".dat" || a.extension() == ".csv") {
        const bool csv = a.extension() == ".csv";
        if (without_environment_columns(read(a), csv) != without_environment_columns(read(b), csv))
            differ(a.string() + " vs " + b.string() + " (apart from timing columns)");
        return;
    }
    if (a.extension() == ".md") {
        if (without_environment_markdown(read(a)) != without_environment_markdown(read(b)))
            differ(a.string() + " vs " + b.string() + " (apart from timing columns)");
        return;
    }
    if (a.extension() == ".json") {
        const auto ja = without_environment(nlohmann::json::parse(read(a)));
        const auto jb = without_environment(nlohmann::json::parse(read(b)));
        if (ja != jb) differ(a.string() + " vs " + b.string() + " (apart from timings)");
        return;
    }
    if (read(a) != read(b)) differ(a.string() + " vs " + b.string());
}
}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args;
    for (int i = 1; i < argc; ++i) {
        if (std::string(argv[i]) == "--skip" && i + 1 < argc) skipped.insert(argv[++i]);
        else args.push_back(argv[i]);
    }
    if (args.size() != 2 && args.size() != 4) {
        std::cerr << "usage: fem-compare-results [--skip NAME ...] <serial dir> <other dir> [<serial figures> <other figures>]\n";
        return 2;
    }
    const fs::path serial = args[0], other = args[1];
    for (const fs::path& d : {serial, other})
        if (!fs::is_directory(d)) {
            std::cerr << "input error: '" << d.string() << "' is not a folder\n";
            return 2;
        }
    int files = 0;
    for (const auto& e : fs::recursive_directory_iterator(other))
        if (e.is_regular_file()) ++files, compare_file(serial / fs::relative(e.path(), other), e.path());
    for (const auto& e : fs::recursive_directory_iterator(serial))
        if (e.is_regular_file() && !fs::exists(other / fs::relative(e.path(), serial)))
            differ(e.path().string() + " is missing from " + other.string());
    if (args.size() == 4) {
        const fs::path sf = args[2], of = args[3];
        for (const auto& e : fs::recursive_directory_iterator(of))
            if (e.is_regular_file()) ++files, compare_file(sf / fs::relative(e.path(), of), e.path());
    }
    std::cout << files << " files compared, " << differences << " differ\n";
    return differences ? 1 : 0;
}
