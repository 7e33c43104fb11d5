#include "check/study.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include <unistd.h>

#include <fmt/format.h>

#include "check/build_paths.hpp"
#include "check/cases.hpp"
#include "check/run_health.hpp"
#include "core/error.hpp"
#include "core/progress.hpp"
#include "core/program.hpp"
#include "input/arguments.hpp"
#include "io/atomic_file.hpp"
#include "io/gnuplot.hpp"
#include "io/run_folder.hpp"

namespace fem::check {

// ------------------------------------------------------------------------------------------------
// CheckRecord <-> JSON (DESIGN.md "Outputs"; the optional fields reference, discrepancy and reason
// extend the documented record without changing it).

nlohmann::json CheckRecord::to_json() const {
    nlohmann::json j;
    j["id"] = id;
    j["source"] = source;
    j["quantity"] = quantity;
    j["unit"] = unit;
    j["basis"] = basis;
    j["kind"] = std::string(kind_name(kind));
    j["thesis"] = thesis;
    j["reproduced"] = reproduced;
    if (tolerance) {
        nlohmann::json t = nlohmann::json::object();
        if (tolerance->rel > 0) t["rel"] = tolerance->rel;
        if (tolerance->abs > 0 || tolerance->rel == 0) t["abs"] = tolerance->abs;
        j["tolerance"] = t;
    } else {
        j["tolerance"] = nullptr;
    }
    j["passed"] = passed ? nlohmann::json(*passed) : nlohmann::json(nullptr);
    j["note"] = note;
    if (reference) j["reference"] = *reference;
    if (!discrepancy.empty()) j["discrepancy"] = discrepancy;
    if (!reason.empty()) j["reason"] = reason;
    if (!known_miss.empty()) j["known_miss"] = known_miss;
    if (!full_only.empty()) j["full_only"] = full_only;
    if (not_run) j["not_run"] = true;
    if (!history.empty()) {
        nlohmann::json h = nlohmann::json::array();
        for (const auto& e : history) h.push_back({{"date", e.date}, {"change", e.change}, {"was", e.was}, {"why", e.why}});
        j["history"] = h;
    }
    if (on_curve)
        j["curve"] = {{"file", on_curve->curve.file}, {"x", on_curve->curve.x}, {"y", on_curve->curve.y},
                      {"x_label", on_curve->curve.x_label}, {"y_label", on_curve->curve.y_label}, {"at", on_curve->at}};
    return j;
}

CheckRecord CheckRecord::from_json(const nlohmann::json& j) {
    CheckRecord r;
    r.id = j.value("id", "");
    r.source = j.value("source", "");
    r.quantity = j.value("quantity", "");
    r.unit = j.value("unit", "");
    r.basis = j.value("basis", "");
    const auto kind = parse_kind(j.value("kind", ""));
    if (!kind)
        throw InputError("check record '" + r.id + "' has no valid 'kind' (" + j.value("kind", std::string("missing")) +
                         "): its checks.json predates kinds; re-run the study");
    r.kind = *kind;
    r.thesis = j.value("thesis", nlohmann::json());
    r.reproduced = j.value("reproduced", nlohmann::json());
    if (j.contains("tolerance") && j["tolerance"].is_object()) {
        Tolerance t;
        t.rel = j["tolerance"].value("rel", 0.0);
        t.abs = j["tolerance"].value("abs", 0.0);
        r.tolerance = t;
    }
    if (j.contains("passed") && j["passed"].is_boolean()) r.passed = j["passed"].get<bool>();
    r.note = j.value("note", "");
    if (j.contains("reference") && j["reference"].is_number()) r.reference = j["reference"].get<double>();
    r.discrepancy = j.value("discrepancy", "");
    r.reason = j.value("reason", "");
    r.known_miss = j.value("known_miss", "");
    r.full_only = j.value("full_only", "");
    r.not_run = j.value("not_run", false);
    if (j.contains("history") && j["history"].is_array())
        for (const auto& e : j["history"])
            r.history.push_back({e.value("date", ""), e.value("change", ""), e.value("was", ""), e.value("why", "")});
    if (j.contains("curve") && j["curve"].is_object()) {
        const auto& c = j["curve"];
        r.on_curve = CurvePoint{{c.value("file", ""), c.value("x", ""), c.value("y", ""), c.value("x_label", ""), c.value("y_label", "")},
                                c.value("at", 0.0)};
    }
    return r;
}

Verdict verdict(const CheckRecord& r) {
    if (r.not_run) return Verdict::NotRun;
    if (!r.passed) return Verdict::Shown;
    if (r.known_miss.empty()) return *r.passed ? Verdict::Pass : Verdict::Fail;
    return *r.passed ? Verdict::UnexpectedPass : Verdict::KnownMiss;
}

std::string_view verdict_label(Verdict v) {
    switch (v) {
        case Verdict::Pass: return "pass";
        case Verdict::Fail: return "FAIL";
        case Verdict::KnownMiss: return "not reproduced";
        case Verdict::UnexpectedPass: return "FAIL: known miss passes";
        case Verdict::Shown: return "shown";
        case Verdict::NotRun: return "not run (make all only)";
    }
    return "?";
}

bool fails_study(Verdict v) { return v == Verdict::Fail || v == Verdict::UnexpectedPass; }

std::optional<double> CheckRecord::deviation() const {
    if (!thesis.is_number() || !reproduced.is_number()) return std::nullopt;
    const double t = thesis.get<double>(), o = reproduced.get<double>();
    if (t == 0.0) return std::nullopt;
    return (o - t) / std::abs(t);
}

// ------------------------------------------------------------------------------------------------

const std::vector<std::string>& study_order() {
    static const std::vector<std::string> order = {
        "cfl_tables",       "portal_frame_modes",      "compliant_beam_damping", "finger_damping",
        "finger_twist",     "rotating_finger_contact", "football_sweep",         "ellipsoid_flip",
        "chicken_shackling", "topology_cases"};
    return order;
}

const std::vector<std::string_view>& study_options() {
    static const std::vector<std::string_view> options = {"--results", "--figures", "--reference", "--full",
                                                          "--jobs",    "--quiet",   "--help",      "-h"};
    return options;
}

void print_study_usage(const std::string& name) {
    std::cout << "usage: " << name << " [--results DIR] [--figures DIR] [--reference FILE] [--full] [--jobs N] [--quiet]\n"
              << "  Runs the study, compares with reference/" << name << ".toml and writes DIR/checks.json.\n"
              << "  --results DIR    where data, checks.json and runs.json go (default build/results/" << name << ")\n"
              << "  --figures DIR    draw the figures there with gnuplot (default: no figures)\n"
              << "  --reference FILE the reference values (default reference/" << name << ".toml)\n"
              << "  --full           also run the thesis-size runs that CTest leaves out (make all passes it;\n"
              << "                   the study's README says what they are); checks are the same\n"
              << "  --jobs N         independent cases run at once (default: FEM_JOBS, else the number of\n"
              << "                   hardware threads; 1: one after another); results are the same\n"
              << "  --quiet          no progress lines of long runs on stderr (core/progress.hpp)\n";
}

namespace {

std::string join_joined(const std::string& a, const std::string& b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    return a + " " + b;
}

}  // namespace

Study::Study(std::string name, int argc, char** argv) : name_(std::move(name)) {
    source_dir_ = check::source_dir();
    results_dir_ = check::results_dir() / name_;
    std::filesystem::path reference_path = default_reference_path(name_);
    input::Arguments args(argc, argv, study_options());
    while (args.next()) {
        if (args.is("--results")) results_dir_ = args.value();
        else if (args.is("--figures")) figures_dir_ = args.value();
        else if (args.is("--reference")) reference_path = args.value();
        else if (args.is("--full")) full_ = true;
        else if (args.is("--quiet")) Progress::set_quiet(true);
        else if (args.is("--jobs")) jobs_ = args.integer<int>({.min = 1});
        else if (args.is("--help") || args.is("-h")) {
            print_study_usage(name_);
            std::exit(0);
        } else args.unknown();
    }
    reference_ = load_reference(reference_path);
    health_exemptions_ = load_health_exemptions(reference_path);
    if (reference_.study != name_)
        throw InputError(reference_path.string() + " is for study '" + reference_.study + "', not '" + name_ + "'");
    if (ranks().rank() > 0) {
        // An MPI rank other than 0 runs the study alike (check/cases.hpp) but writes nothing of it.
        results_dir_ = std::filesystem::temp_directory_path() /
                       ("fem-" + name_ + "-rank-" + std::to_string(ranks().rank()) + "-" + std::to_string(::getpid()));
        figures_dir_.clear();
        scratch_ = true;
        std::filesystem::create_directories(results_dir_);
    } else {
        // The results folder holds one run's set (io::RunFolder): checked and locked now, the study
        // writes into its staging folder, finish() puts the set in place.
        output_ = std::make_unique<io::RunFolder>(std::filesystem::absolute(results_dir_), name_);
        results_dir_ = output_->staging();
    }
    if (!figures_dir_.empty()) {
        figures_dir_ = std::filesystem::absolute(figures_dir_);
        std::filesystem::create_directories(figures_dir_);
    }
}

Study::~Study() = default;

std::filesystem::path default_reference_path(std::string_view study) {
    return source_dir() / "reference" / (std::string(study) + ".toml");
}

const ReferenceEntry& Study::entry_to_check(std::string_view id) const {
    const ReferenceEntry& e = reference_.entry(id);
    if (e.is_full_only() && !full_)
        throw std::logic_error("check '" + e.id + "' is full_only in " + reference_.path.string() +
                               ": the study judges it only under --full (its runs cost more than CTest's budget)");
    return e;
}

CheckRecord Study::start_record(const ReferenceEntry& e, std::string note) const {
    CheckRecord r;
    r.id = e.id;
    r.source = e.source;
    r.quantity = e.quantity;
    r.unit = e.unit;
    r.basis = e.basis;
    r.kind = e.kind;
    r.known_miss = e.known_miss;
    r.full_only = e.full_only;
    r.history = e.history;
    r.tolerance = e.tolerance;
    r.reason = e.reason;
    r.discrepancy = e.discrepancy;
    r.note = join_joined(e.note, note);
    r.on_curve = e.curve_point();
    return r;
}

const CheckRecord& Study::add(CheckRecord record) {
    records_.push_back(std::move(record));
    return records_.back();
}

const CheckRecord& Study::check(std::string_view id, double reproduced, std::string note) {
    const ReferenceEntry& e = entry_to_check(id);
    if (e.is_trend() || e.is_series())
        throw std::logic_error("check '" + e.id + "' is not a single number in " + reference_.path.string());
    checked_ids_.push_back(e.id);
    CheckRecord r = start_record(e, std::move(note));
    const double printed = std::get<double>(e.thesis);
    r.thesis = printed;
    r.reproduced = reproduced;
    const double against = e.follows.value_or(printed);
    if (e.follows) r.reference = *e.follows;
    if (e.judged()) r.passed = e.tolerance->allows(reproduced, against);
    return add(std::move(r));
}

void Study::check(std::string_view id, std::span<const double> reproduced, std::string note) {
    const ReferenceEntry& e = entry_to_check(id);
    if (!e.is_series()) throw std::logic_error("check '" + e.id + "' is not a series in " + reference_.path.string());
    const auto& thesis = std::get<std::vector<double>>(e.thesis);
    if (thesis.size() != reproduced.size())
        throw std::logic_error("check '" + e.id + "': the thesis has " + std::to_string(thesis.size()) +
                               " values, the study gave " + std::to_string(reproduced.size()));
    checked_ids_.push_back(e.id);
    for (std::size_t k = 0; k < thesis.size(); ++k) {
        CheckRecord r = start_record(e, note);
        r.id = e.id + "/" + e.member_label(k);
        r.on_curve = e.curve_point(k);
        if (!e.member_is_known_miss(e.member_label(k))) r.known_miss.clear();
        r.thesis = thesis[k];
        r.reproduced = reproduced[k];
        if (e.judged()) r.passed = e.tolerance->allows(reproduced[k], thesis[k]);
        add(std::move(r));
    }
}

const CheckRecord& Study::trend(std::string_view id, std::string reproduced, std::string note) {
    const ReferenceEntry& e = entry_to_check(id);
    if (!e.is_trend()) throw std::logic_error("check '" + e.id + "' is not a trend in " + reference_.path.string());
    const bool holds = reproduced == std::get<std::string>(e.thesis);
    return trend_holds(id, holds, std::move(reproduced), std::move(note));
}

const CheckRecord& Study::trend_holds(std::string_view id, bool holds, std::string reproduced, std::string note) {
    const ReferenceEntry& e = entry_to_check(id);
    if (!e.is_trend()) throw std::logic_error("check '" + e.id + "' is not a trend in " + reference_.path.string());
    checked_ids_.push_back(e.id);
    CheckRecord r = start_record(e, std::move(note));
    r.thesis = std::get<std::string>(e.thesis);
    r.reproduced = std::move(reproduced);
    if (e.judged()) r.passed = holds;
    return add(std::move(r));
}

void Study::write_markdown(const std::string& file_name, const std::string& text) const {
    io::write_text_file(results_dir_ / file_name, text);
    if (!figures_dir_.empty()) io::write_text_file(figures_dir_ / file_name, text);
}

void Study::record_run(RunRecord run) { runs_.push_back(std::move(run)); }

void Study::plot() {
    if (figures_dir_.empty()) return;
    // Each figure is drawn twice, as SVG (for the report) and as PNG: the script writes
    // figures.'/<name>.'.ext with `set terminal @term size W,H ...`.
    const auto script = source_dir_ / "studies" / name_ / (name_ + ".gp");
    for (const auto& [term, ext] : {std::pair{"svg", "svg"}, std::pair{"pngcairo", "png"}})
        io::run_gnuplot(script, {{"results", results_dir_.string()}, {"figures", figures_dir_.string()},
                                 {"term", term}, {"ext", ext}});
}

int Study::finish() {
    // Every reference entry must have been checked: a study cannot skip a check silently. A
    // full_only entry in a run without --full is listed as not run (`make all` judges it).
    for (const auto& e : reference_.entries) {
        if (std::find(checked_ids_.begin(), checked_ids_.end(), e.id) != checked_ids_.end()) continue;
        const bool not_run = e.is_full_only() && !full_;
        CheckRecord r = start_record(e, not_run ? "not run here: judged by `make all` (--full) only, because " + e.full_only
                                                : std::string("the study did not produce this value"));
        if (e.is_trend()) r.thesis = std::get<std::string>(e.thesis);
        else if (e.is_series()) r.thesis = std::get<std::vector<double>>(e.thesis);
        else r.thesis = std::get<double>(e.thesis);
        r.reproduced = nullptr;
        if (not_run) {
            r.not_run = true;
        } else {
            r.passed = false;
            r.known_miss.clear();  // a value the study did not produce fails, known miss or not
        }
        add(std::move(r));
    }

    nlohmann::json checks = nlohmann::json::array();
    for (const auto& r : records_) checks.push_back(r.to_json());
    io::write_text_file(results_dir_ / "checks.json", checks.dump(2) + "\n");
    // Explicit runs are judged on their energy health (check/run_health.hpp); the verdict goes into
    // runs.json beside the run's values.
    std::vector<std::pair<std::string, nlohmann::json>> recorded;
    for (const auto& run : runs_) recorded.emplace_back(run.name, run.values);
    std::vector<std::string> health_problems;
    const auto health = judge_run_health(recorded, health_exemptions_, reference_.path.string(), health_problems);
    nlohmann::json runs = nlohmann::json::array();
    for (const auto& run : runs_) {
        nlohmann::json j = {{"name", run.name}, {"values", run.values}};
        for (const auto& h : health)
            if (h.run == run.name) j["health"] = h.to_json();
        runs.push_back(std::move(j));
    }
    io::write_text_file(results_dir_ / "runs.json", runs.dump(2) + "\n");
    if (output_) output_->commit();

    std::map<Verdict, int> count;
    std::cout << "\n" << name_ << ": checks against the thesis\n";
    for (const auto& r : records_) {
        const Verdict v = verdict(r);
        ++count[v];
        std::cout << "  " << std::left << std::setw(14) << verdict_label(v) << " " << std::setw(13) << kind_name(r.kind) << " "
                  << std::setw(48) << r.id << " thesis " << r.thesis.dump() << "  ours " << r.reproduced.dump();
        if (r.reference) std::cout << "  (checked against " << *r.reference << ")";
        std::cout << '\n';
        if (v == Verdict::UnexpectedPass)
            std::cout << "    ^ a known miss now passes: update its entry in the reference file (known_miss, history)\n";
    }
    for (const auto& h : health) std::cout << "  " << h.text() << '\n';
    for (const auto& p : health_problems) std::cerr << name_ << ": " << p << '\n';
    const int failed = count[Verdict::Fail] + count[Verdict::UnexpectedPass];
    std::cout << name_ << ": " << count[Verdict::Pass] << " passed, " << count[Verdict::KnownMiss]
              << " not reproduced (known misses), " << failed << " failed, " << count[Verdict::Shown] << " shown"
              << (count[Verdict::NotRun] ? fmt::format(", {} not run (make all only)", count[Verdict::NotRun]) : "")
              << (health.empty() ? "" : fmt::format("; {} explicit runs judged on energy health, {} problems", health.size(),
                                                     health_problems.size()))
              << "\n"
              << "results: " << (output_ ? output_->path() : results_dir_).string() << "/checks.json\n";
    if (scratch_) std::filesystem::remove_all(results_dir_);
    return failed == 0 && health_problems.empty() ? 0 : 1;
}

int run_study(std::string name, int argc, char** argv, const std::function<void(Study&)>& body) {
    const std::string program = name;
    return run_program(program.c_str(), [&]() {
        // MPI ranks other than 0 print nothing (rank 0 prints what a serial run prints); errors still
        // go to stderr.
        if (ranks().rank() > 0 && !std::freopen("/dev/null", "w", stdout))
            throw std::runtime_error("cannot silence the standard output of MPI rank " + std::to_string(ranks().rank()));
        detail::share_cores_among_local_ranks();
        Study study(std::move(name), argc, argv);
        body(study);
        return study.finish();
    });
}

}  // namespace fem::check
