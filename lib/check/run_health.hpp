#pragma once
// The health of an explicit run (issue 14 item 8): its energy balance error and its hourglass
// energy as a fraction of its internal energy, judged against the usual limits of explicit codes:
//   balance error (max |error| over the largest total energy, incl. the work done: LS-DYNA glstat's
//   energy-ratio denominator, explicit/solver.hpp EnergySummary)             <= 1 %
//   hourglass energy / internal energy (their largest values)                <= 10 %
// both over the run's judged window (ExplicitOptions::health_from/health_until; the whole run by
// default), so that a study judges the window its checks read, with the same numbers as here.
// A study records its explicit runs with Study::record_run(summary.to_json()); finish() judges
// every recorded run that carries both measures and fails the study for an unhealthy run, unless
// reference/<study>.toml exempts that run with the reason (reference/README.md):
//
//   [[health_exemption]]
//   run = "Case D"           # the run's name as in runs.json; * and ? match any text (fnmatch), so
//                            # "table-3-3 *" covers every run of a search
//   balance = """why this run's balance error may exceed 1 %"""            # either or both
//   hourglass = """why its hourglass energy may exceed 10 % of internal"""
//
// An exemption is part of the reference file's honesty: one that matches no run of the study, or
// whose runs all meet the limit anyway, fails the study too, so that stale exemptions get removed.
// A fem-explicit case file takes the same [[health_exemption]] tables for its own runs
// (lib/explicit_case/CASE_FILE.md), judged the same way.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace fem::input {
class TomlTable;
}

namespace fem::check {

inline constexpr double kMaxBalanceError = 0.01;      // of the run's energy scale
inline constexpr double kMaxHourglassFraction = 0.10; // of the internal energy

struct HealthExemption {
    std::string run;                 // a run name, or a pattern with * and ?
    std::string balance, hourglass;  // the reasons; empty: not exempt from that limit
    int line = 0;                    // in the reference file, for messages
    bool matches(const std::string& run_name) const;
};

/// The [[health_exemption]] entries of a reference file (strict: unknown keys, a missing run name or
/// an exemption without a reason are InputErrors naming the line).
std::vector<HealthExemption> load_health_exemptions(const std::filesystem::path& reference_file);
/// The same from the root table of a TOML document already open (a case file's).
std::vector<HealthExemption> read_health_exemptions(const input::TomlTable& root);

/// The verdict on one recorded run.
struct RunHealth {
    std::string run;
    double balance_error = 0, hourglass_fraction = 0;
    bool balance_ok = true, hourglass_ok = true;
    std::string balance_exemption, hourglass_exemption;  // the reason, when exempt
    bool passed() const { return (balance_ok || !balance_exemption.empty()) && (hourglass_ok || !hourglass_exemption.empty()); }
    /// The verdict on one limit: "ok" (met), "exempt" (broken, with an exemption) or "failed".
    static const char* limit_verdict(bool ok, const std::string& exemption);
    /// runs.json's "health": the measures, limits and verdicts ("balance_verdict",
    /// "hourglass_verdict"), "passed", and the exemptions' reasons; the report shows the verdicts.
    nlohmann::json to_json() const;
    std::string text() const;  // one line for the study's printout
};

/// The verdict on one run, with the exemptions that match its name; none for values without
/// "energy_balance_relative_error" and "hourglass_fraction_of_internal" (not an explicit run).
std::optional<RunHealth> judge_run(const std::string& name, const nlohmann::json& values,
                                   const std::vector<HealthExemption>& exemptions);

/// judge_run, its verdict appended to `judged` and, when failed, its line to `problems`; the verdict
/// (none for a run that is not explicit).
std::optional<RunHealth> judge_run_into(const std::string& name, const nlohmann::json& values,
                                        const std::vector<HealthExemption>& exemptions, std::vector<RunHealth>& judged,
                                        std::vector<std::string>& problems);

/// The exemptions that are stale once every run has been judged: one that names no run of `judged`,
/// or whose runs all meet the limit it exempts from (`file` and the entry's line name it).
std::vector<std::string> stale_exemptions(const std::vector<RunHealth>& judged, const std::vector<HealthExemption>& exemptions,
                                          const std::string& file);

/// Judges every run whose values carry "energy_balance_relative_error" and
/// "hourglass_fraction_of_internal" (explicit runs); `problems` receives the failures the study must
/// report: unhealthy runs without exemption, and exemptions that name no run or that are not needed.
std::vector<RunHealth> judge_run_health(const std::vector<std::pair<std::string, nlohmann::json>>& runs,
                                        const std::vector<HealthExemption>& exemptions, const std::string& reference_file,
                                        std::vector<std::string>& problems);

}  // namespace fem::check
