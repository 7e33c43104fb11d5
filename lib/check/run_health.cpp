#include "check/run_health.hpp"

#include <fnmatch.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "input/toml_input.hpp"

namespace fem::check {

std::vector<HealthExemption> load_health_exemptions(const std::filesystem::path& reference_file) {
    return read_health_exemptions(input::TomlDocument::read(reference_file).root());
}

std::vector<HealthExemption> read_health_exemptions(const input::TomlTable& root) {
    std::vector<HealthExemption> out;
    for (const input::TomlTable& t : root.tables("health_exemption")) {
        t.allow({"run", "balance", "hourglass"});
        HealthExemption e;
        e.run = t.string("run");
        e.balance = t.string_or("balance", "");
        e.hourglass = t.string_or("hourglass", "");
        e.line = t.where().line;
        if (e.balance.empty() && e.hourglass.empty())
            t.fail("an exemption needs its reason: balance = \"...\" and/or hourglass = \"...\"");
        out.push_back(std::move(e));
    }
    return out;
}

const char* RunHealth::limit_verdict(bool ok, const std::string& exemption) {
    return ok ? "ok" : exemption.empty() ? "failed" : "exempt";
}

nlohmann::json RunHealth::to_json() const {
    nlohmann::json j = {{"balance_error", balance_error},
                        {"balance_limit", kMaxBalanceError},
                        {"balance_verdict", limit_verdict(balance_ok, balance_exemption)},
                        {"hourglass_fraction", hourglass_fraction},
                        {"hourglass_limit", kMaxHourglassFraction},
                        {"hourglass_verdict", limit_verdict(hourglass_ok, hourglass_exemption)},
                        {"passed", passed()}};
    if (!balance_exemption.empty()) j["balance_exemption"] = balance_exemption;
    if (!hourglass_exemption.empty()) j["hourglass_exemption"] = hourglass_exemption;
    return j;
}

std::string RunHealth::text() const {
    auto verdict = [](bool ok, const std::string& exemption) {
        const std::string v = limit_verdict(ok, exemption);
        return v == "failed" ? std::string("FAIL") : v;
    };
    return fmt::format("{:<6} run health {}: energy balance error {:.3g} % ({}, limit {:g} %), hourglass {:.3g} % of "
                       "internal ({}, limit {:g} %)",
                       passed() ? "pass" : "FAIL", run, 100 * balance_error, verdict(balance_ok, balance_exemption),
                       100 * kMaxBalanceError, 100 * hourglass_fraction, verdict(hourglass_ok, hourglass_exemption),
                       100 * kMaxHourglassFraction);
}

std::optional<RunHealth> judge_run(const std::string& name, const nlohmann::json& values,
                                   const std::vector<HealthExemption>& exemptions) {
    if (!values.is_object() || !values.contains("energy_balance_relative_error") ||
        !values.contains("hourglass_fraction_of_internal"))
        return std::nullopt;
    RunHealth h;
    h.run = name;
    h.balance_error = values["energy_balance_relative_error"].get<double>();
    h.hourglass_fraction = values["hourglass_fraction_of_internal"].get<double>();
    h.balance_ok = h.balance_error <= kMaxBalanceError;  // nan fails
    h.hourglass_ok = h.hourglass_fraction <= kMaxHourglassFraction;
    for (const HealthExemption& e : exemptions) {
        if (!e.matches(name)) continue;
        if (!e.balance.empty()) h.balance_exemption = e.balance;
        if (!e.hourglass.empty()) h.hourglass_exemption = e.hourglass;
    }
    return h;
}

std::optional<RunHealth> judge_run_into(const std::string& name, const nlohmann::json& values,
                                        const std::vector<HealthExemption>& exemptions, std::vector<RunHealth>& judged,
                                        std::vector<std::string>& problems) {
    std::optional<RunHealth> h = judge_run(name, values, exemptions);
    if (h) {
        if (!h->passed()) problems.push_back(h->text());
        judged.push_back(*h);
    }
    return h;
}

std::vector<std::string> stale_exemptions(const std::vector<RunHealth>& judged, const std::vector<HealthExemption>& exemptions,
                                          const std::string& file) {
    std::vector<std::string> problems;
    for (const HealthExemption& e : exemptions) {
        // Did it match a run, and did a matched run need it (exceed that limit)?
        bool matched = false, balance_needed = false, hourglass_needed = false;
        for (const RunHealth& h : judged) {
            if (!e.matches(h.run)) continue;
            matched = true;
            balance_needed = balance_needed || !h.balance_ok;
            hourglass_needed = hourglass_needed || !h.hourglass_ok;
        }
        const std::string at = fmt::format("{}:{}", file, e.line);
        if (!matched)
            problems.push_back(fmt::format("{}: the health exemption names run '{}', which is not among the runs judged "
                                           "(runs are named as in runs.json or run.json)", at, e.run));
        else if (!e.balance.empty() && !balance_needed)
            problems.push_back(fmt::format("{}: run '{}' is exempt from the balance limit but meets it (<= {:g} %): remove "
                                           "the exemption", at, e.run, 100 * kMaxBalanceError));
        else if (!e.hourglass.empty() && !hourglass_needed)
            problems.push_back(fmt::format("{}: run '{}' is exempt from the hourglass limit but meets it (<= {:g} % of "
                                           "internal): remove the exemption", at, e.run, 100 * kMaxHourglassFraction));
    }
    return problems;
}

std::vector<RunHealth> judge_run_health(const std::vector<std::pair<std::string, nlohmann::json>>& runs,
                                        const std::vector<HealthExemption>& exemptions, const std::string& reference_file,
                                        std::vector<std::string>& problems) {
    std::vector<RunHealth> out;
    for (const auto& [name, values] : runs) judge_run_into(name, values, exemptions, out, problems);
    for (std::string& p : stale_exemptions(out, exemptions, reference_file)) problems.push_back(std::move(p));
    return out;
}

bool HealthExemption::matches(const std::string& name) const { return ::fnmatch(run.c_str(), name.c_str(), 0) == 0; }

}  // namespace fem::check
