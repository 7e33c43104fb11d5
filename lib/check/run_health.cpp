#include "check/run_health.hpp"

#include <fnmatch.h>

#include <fmt/format.h>

#include "input/toml_input.hpp"

namespace fem::check {

std::vector<HealthExemption> load_health_exemptions(const std::filesystem::path& reference_file) {
    const input::TomlDocument doc = input::TomlDocument::read(reference_file);
    std::vector<HealthExemption> out;
    for (const input::TomlTable& t : doc.root().tables("health_exemption")) {
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

nlohmann::json RunHealth::to_json() const {
    nlohmann::json j = {{"balance_error", balance_error},
                        {"balance_limit", kMaxBalanceError},
                        {"hourglass_fraction", hourglass_fraction},
                        {"hourglass_limit", kMaxHourglassFraction},
                        {"passed", passed()}};
    if (!balance_exemption.empty()) j["balance_exemption"] = balance_exemption;
    if (!hourglass_exemption.empty()) j["hourglass_exemption"] = hourglass_exemption;
    return j;
}

std::string RunHealth::text() const {
    auto verdict = [](bool ok, const std::string& exemption) { return ok ? "ok" : exemption.empty() ? "FAIL" : "exempt"; };
    return fmt::format("{:<6} run health {}: energy balance error {:.3g} % ({}, limit {:g} %), hourglass {:.3g} % of "
                       "internal ({}, limit {:g} %)",
                       passed() ? "pass" : "FAIL", run, 100 * balance_error, verdict(balance_ok, balance_exemption),
                       100 * kMaxBalanceError, 100 * hourglass_fraction, verdict(hourglass_ok, hourglass_exemption),
                       100 * kMaxHourglassFraction);
}

std::vector<RunHealth> judge_run_health(const std::vector<std::pair<std::string, nlohmann::json>>& runs,
                                        const std::vector<HealthExemption>& exemptions, const std::string& reference_file,
                                        std::vector<std::string>& problems) {
    std::vector<RunHealth> out;
    // Per exemption: did it match a run, and did a matched run need it (exceed that limit)?
    std::vector<bool> matched(exemptions.size(), false), balance_needed(exemptions.size(), false),
        hourglass_needed(exemptions.size(), false);
    for (const auto& [name, values] : runs) {
        if (!values.is_object() || !values.contains("energy_balance_relative_error") ||
            !values.contains("hourglass_fraction_of_internal"))
            continue;
        RunHealth h;
        h.run = name;
        h.balance_error = values["energy_balance_relative_error"].get<double>();
        h.hourglass_fraction = values["hourglass_fraction_of_internal"].get<double>();
        h.balance_ok = h.balance_error <= kMaxBalanceError;  // nan fails
        h.hourglass_ok = h.hourglass_fraction <= kMaxHourglassFraction;
        for (std::size_t k = 0; k < exemptions.size(); ++k) {
            const HealthExemption& e = exemptions[k];
            if (!e.matches(name)) continue;
            matched[k] = true;
            if (!e.balance.empty()) {
                h.balance_exemption = e.balance;
                balance_needed[k] = balance_needed[k] || !h.balance_ok;
            }
            if (!e.hourglass.empty()) {
                h.hourglass_exemption = e.hourglass;
                hourglass_needed[k] = hourglass_needed[k] || !h.hourglass_ok;
            }
        }
        if (!h.passed()) problems.push_back(h.text());
        out.push_back(std::move(h));
    }
    for (std::size_t k = 0; k < exemptions.size(); ++k) {
        const HealthExemption& e = exemptions[k];
        const std::string at = fmt::format("{}:{}", reference_file, e.line);
        if (!matched[k])
            problems.push_back(fmt::format("{}: the health exemption names run '{}', which the study did not record "
                                           "(runs are named as in runs.json)", at, e.run));
        else if (!e.balance.empty() && !balance_needed[k])
            problems.push_back(fmt::format("{}: run '{}' is exempt from the balance limit but meets it (<= {:g} %): remove "
                                           "the exemption", at, e.run, 100 * kMaxBalanceError));
        else if (!e.hourglass.empty() && !hourglass_needed[k])
            problems.push_back(fmt::format("{}: run '{}' is exempt from the hourglass limit but meets it (<= {:g} % of "
                                           "internal): remove the exemption", at, e.run, 100 * kMaxHourglassFraction));
    }
    return out;
}

bool HealthExemption::matches(const std::string& name) const { return ::fnmatch(run.c_str(), name.c_str(), 0) == 0; }

}  // namespace fem::check
