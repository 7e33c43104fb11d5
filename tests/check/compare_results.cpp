// fem-compare-results: are two runs of a study the same apart from timings? For the CTest test that
// runs a study over MPI ranks against its serial run (check/cases.hpp).
//   fem-compare-results <serial dir> <other dir> [<serial figures dir> <other figures dir>]
// Every file under <other dir> must exist under <serial dir> with the same bytes, and every file of
// <serial dir> must exist under <other dir>; runs.json is compared with the facts of the run's
// environment removed from each run's values (wall and CPU times, rates, thread counts, the timing
// split). With figure folders: every file of <other figures dir> must equal its namesake in <serial
// figures dir> (which holds every study's figures). Prints each difference; exit 1 when any.
// (Environment keys: the explicit summary's wall_s, element_cycles_per_s, threads, timing_s,
// contact_share and its contact interfaces' search_s and forces_s; a study's own wall and set-up
// times.)
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <set>
#include <string>

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
                                               "threads",  "contact_share", "search_s", "forces_s"};
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

void compare_file(const fs::path& a, const fs::path& b) {
    if (!fs::exists(a)) return differ(b.string() + " has no counterpart " + a.string());
    if (a.filename() == "runs.json") {
        const auto ja = without_environment(nlohmann::json::parse(read(a)));
        const auto jb = without_environment(nlohmann::json::parse(read(b)));
        if (ja != jb) differ(a.string() + " vs " + b.string() + " (apart from timings)");
        return;
    }
    if (read(a) != read(b)) differ(a.string() + " vs " + b.string());
}
}  // namespace

int main(int argc, char** argv) {
    if (argc != 3 && argc != 5) {
        std::cerr << "usage: fem-compare-results <serial dir> <other dir> [<serial figures> <other figures>]\n";
        return 2;
    }
    const fs::path serial = argv[1], other = argv[2];
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
    if (argc == 5) {
        const fs::path sf = argv[3], of = argv[4];
        for (const auto& e : fs::recursive_directory_iterator(of))
            if (e.is_regular_file()) ++files, compare_file(sf / fs::relative(e.path(), of), e.path());
    }
    std::cout << files << " files compared, " << differences << " differ\n";
    return differences ? 1 : 0;
}
