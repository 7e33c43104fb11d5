#include "check/reference.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <toml++/toml.h>

#include "core/error.hpp"

namespace fem::check {

bool Tolerance::allows(double reproduced, double reference) const {
    if (!std::isfinite(reproduced)) return false;
    return std::abs(reproduced - reference) <= abs + rel * std::abs(reference);
}

std::string_view kind_name(Kind kind) {
    switch (kind) {
        case Kind::Reproduction: return "reproduction";
        case Kind::Consistency: return "consistency";
        case Kind::Verification: return "verification";
        case Kind::Trend: return "trend";
        case Kind::Shown: return "shown";
    }
    return "?";
}

const std::vector<Kind>& all_kinds() {
    static const std::vector<Kind> kinds = {Kind::Reproduction, Kind::Trend, Kind::Consistency, Kind::Verification,
                                            Kind::Shown};
    return kinds;
}

std::optional<Kind> parse_kind(std::string_view name) {
    for (Kind k : all_kinds())
        if (kind_name(k) == name) return k;
    return std::nullopt;
}

std::string ReferenceEntry::member_label(std::size_t k) const {
    return k < labels.size() ? labels[k] : std::to_string(k + 1);
}

bool ReferenceEntry::member_is_known_miss(const std::string& label) const {
    if (!is_known_miss()) return false;
    if (known_miss_labels.empty()) return true;
    return std::find(known_miss_labels.begin(), known_miss_labels.end(), label) != known_miss_labels.end();
}

std::optional<CurvePoint> ReferenceEntry::curve_point(std::size_t k) const {
    if (!curve || k >= curve_at.size()) return std::nullopt;
    return CurvePoint{*curve, curve_at[k]};
}

const ReferenceEntry& ReferenceFile::entry(std::string_view id) const {
    for (const auto& e : entries)
        if (e.id == id) return e;
    throw std::out_of_range("check id '" + std::string(id) + "' is not in " + path.string());
}

namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const toml::source_region& where, const std::string& what) {
    std::ostringstream msg;
    msg << path.string() << ":" << where.begin.line << ": " << what;
    throw InputError(msg.str());
}

std::string optional_string(const toml::table& t, const char* key) {
    return t[key].value<std::string>().value_or("");
}

// curve = { file = "fig-3-41.dat", x = "t_ms", y = "twist_deg", at = 5.7 (or one per series member),
//           x_label = "time (ms)", y_label = "twist (deg)" }
void parse_curve(const toml::table& t, const std::filesystem::path& path, ReferenceEntry& e) {
    const toml::table* c = t["curve"].as_table();
    auto bad = [&](const std::string& what) {
        fail(path, t.source(), "check '" + e.id + "': curve " + what +
                                   " (curve = { file = \"<data file of the study>\", x = \"<column>\", y = \"<column>\", "
                                   "at = <abscissa of the thesis value, or one per series member> })");
    };
    if (!c) bad("must be a table");
    CurveRef ref;
    for (auto [key, field] : {std::pair{"file", &ref.file}, {"x", &ref.x}, {"y", &ref.y}}) {
        auto v = (*c)[key].value<std::string>();
        if (!v || v->empty()) bad(std::string("lacks '") + key + "'");
        *field = *v;
    }
    ref.x_label = (*c)["x_label"].value<std::string>().value_or("");
    ref.y_label = (*c)["y_label"].value<std::string>().value_or("");
    const std::filesystem::path file(ref.file);
    if (file.is_absolute() || file.filename() != file) bad("file '" + ref.file + "' must be a file name in the study's results folder");
    if (e.is_trend()) bad("is for a numeric thesis value, not a trend");
    if (auto at = (*c)["at"].value<double>()) e.curve_at.push_back(*at);
    else if (const toml::array* a = (*c)["at"].as_array())
        for (const auto& v : *a) {
            auto d = v.value<double>();
            if (!d) bad("'at' holds a non-number");
            e.curve_at.push_back(*d);
        }
    const std::size_t n = e.is_series() ? std::get<std::vector<double>>(e.thesis).size() : 1;
    if (e.curve_at.size() != n) bad("needs 'at': " + std::to_string(n) + " abscissa(s), one per thesis value");
    e.curve = ref;
}

const std::set<std::string> kBases = {"exact", "model", "reconstructed", "trend", "experiment"};

ReferenceEntry parse_entry(const toml::table& t, const std::filesystem::path& path) {
    ReferenceEntry e;
    auto required = [&](const char* key) {
        auto v = t[key].value<std::string>();
        if (!v || v->empty()) fail(path, t.source(), std::string("check entry lacks the string field '") + key + "'");
        return *v;
    };
    e.id = required("id");
    e.source = required("source");
    e.quantity = required("quantity");
    e.basis = required("basis");
    if (!kBases.count(e.basis))
        fail(path, t.source(), "check '" + e.id + "': basis '" + e.basis +
                                   "' is not one of exact, model, reconstructed, trend, experiment");
    e.unit = optional_string(t, "unit");
    e.reason = optional_string(t, "reason");
    e.note = optional_string(t, "note");
    e.discrepancy = optional_string(t, "discrepancy");

    // kind: required. judged = false survives only as a redundant mark of kind "shown".
    const auto kind_text = t["kind"].value<std::string>();
    if (!kind_text)
        fail(path, t.source(), "check '" + e.id +
                                   "' lacks 'kind' (reproduction, consistency, verification, trend or shown)");
    const auto kind = parse_kind(*kind_text);
    if (!kind)
        fail(path, t.source(), "check '" + e.id + "': kind '" + *kind_text +
                                   "' is not one of reproduction, consistency, verification, trend, shown");
    e.kind = *kind;
    if (const auto judged = t["judged"].value<bool>()) {
        if (!*judged && e.kind != Kind::Shown)
            fail(path, t.source(), "check '" + e.id + "': judged = false is only for kind \"shown\" (nothing to judge "
                                   "against); a miss is a known_miss with its reason");
        if (*judged && e.kind == Kind::Shown)
            fail(path, t.source(), "check '" + e.id + "': kind \"shown\" is never judged");
    }
    e.known_miss = optional_string(t, "known_miss");
    if (e.is_known_miss() && e.kind == Kind::Shown)
        fail(path, t.source(), "check '" + e.id + "': a known_miss is judged; kind \"shown\" is not");
    if (t.contains("known_miss") && e.known_miss.empty())
        fail(path, t.source(), "check '" + e.id + "': known_miss must say why we miss (a non-empty string)");
    e.full_only = optional_string(t, "full_only");
    if (t.contains("full_only") && e.full_only.empty())
        fail(path, t.source(), "check '" + e.id + "': full_only must say why CTest cannot judge it (a non-empty string)");
    if (const toml::array* h = t["history"].as_array()) {
        for (const auto& item : *h) {
            const toml::table* ht = item.as_table();
            if (!ht) fail(path, t.source(), "check '" + e.id + "': history holds a non-table");
            HistoryEntry he;
            auto field = [&](const char* key) {
                auto v = (*ht)[key].value<std::string>();
                if (!v || v->empty())
                    fail(path, ht->source(), "check '" + e.id + "': a history entry lacks '" + key +
                                                 "' (date, change, was and why are required)");
                return *v;
            };
            he.date = field("date");
            he.change = field("change");
            he.was = field("was");
            he.why = field("why");
            e.history.push_back(std::move(he));
        }
    } else if (t.contains("history")) {
        fail(path, t.source(), "check '" + e.id + "': history must be an array of { date, change, was, why }");
    }

    const toml::node_view thesis = t["thesis"];
    if (auto s = thesis.value<std::string>()) {
        e.thesis = *s;
    } else if (auto d = thesis.value<double>()) {
        e.thesis = *d;
    } else if (const toml::array* a = thesis.as_array()) {
        std::vector<double> values;
        for (const auto& v : *a) {
            auto d = v.value<double>();
            if (!d) fail(path, t.source(), "check '" + e.id + "': thesis series holds a non-number");
            values.push_back(*d);
        }
        e.thesis = values;
        if (const toml::array* labels = t["labels"].as_array()) {
            for (const auto& l : *labels) e.labels.push_back(l.value<std::string>().value_or("?"));
            if (e.labels.size() != values.size())
                fail(path, t.source(), "check '" + e.id + "': labels and thesis series differ in length");
        }
    } else {
        fail(path, t.source(), "check '" + e.id + "' lacks 'thesis' (a number, a statement or a list of numbers)");
    }

    if (const toml::table* tol = t["tolerance"].as_table()) {
        Tolerance tolerance;
        tolerance.rel = (*tol)["rel"].value<double>().value_or(0.0);
        tolerance.abs = (*tol)["abs"].value<double>().value_or(0.0);
        if (tolerance.rel < 0 || tolerance.abs < 0 || (tolerance.rel == 0 && tolerance.abs == 0 && !tol->contains("abs")))
            fail(path, t.source(), "check '" + e.id + "': tolerance needs rel and/or abs >= 0");
        e.tolerance = tolerance;
        if (e.reason.empty()) fail(path, t.source(), "check '" + e.id + "': a tolerance needs its 'reason'");
    }
    if (auto f = t["follows"].value<double>()) {
        e.follows = *f;
        if (e.discrepancy.empty())
            fail(path, t.source(), "check '" + e.id + "': 'follows' needs a 'discrepancy' that explains it");
    }
    if (e.is_trend()) {
        if (e.tolerance) fail(path, t.source(), "check '" + e.id + "': a trend check has no tolerance");
    } else if (e.judged() && !e.tolerance) {
        fail(path, t.source(), "check '" + e.id + "': a judged numeric check needs a tolerance (kind \"shown\" only when "
                               "there is nothing to judge against)");
    } else if (!e.judged() && e.tolerance) {
        fail(path, t.source(), "check '" + e.id + "': kind \"shown\" is not judged, so it takes no tolerance");
    }
    if (const toml::array* members = t["known_miss_labels"].as_array()) {
        if (!e.is_series() || !e.is_known_miss())
            fail(path, t.source(), "check '" + e.id + "': known_miss_labels is for a series entry with a known_miss");
        const auto n = std::get<std::vector<double>>(e.thesis).size();
        for (const auto& m : *members) {
            const std::string label = m.value<std::string>().value_or("");
            bool found = false;
            for (std::size_t k = 0; k < n; ++k) found = found || e.member_label(k) == label;
            if (!found) fail(path, t.source(), "check '" + e.id + "': known_miss_labels names '" + label + "', not a member");
            e.known_miss_labels.push_back(label);
        }
    }
    if (t.contains("curve")) parse_curve(t, path, e);
    return e;
}

}  // namespace

ReferenceFile load_reference(const std::filesystem::path& path) {
    if (!std::filesystem::exists(path)) throw InputError("reference file '" + path.string() + "' not found");
    toml::table root;
    try {
        root = toml::parse_file(path.string());
    } catch (const toml::parse_error& err) {
        std::ostringstream msg;
        msg << path.string() << ":" << err.source().begin.line << ": " << err.description();
        throw InputError(msg.str());
    }
    ReferenceFile ref;
    ref.path = path;
    ref.study = root["study"].value<std::string>().value_or("");
    if (ref.study.empty()) throw InputError(path.string() + ": lacks 'study = \"<name>\"'");
    ref.title = root["title"].value<std::string>().value_or(ref.study);
    ref.section = root["section"].value<std::string>().value_or("");
    ref.summary = root["summary"].value<std::string>().value_or("");
    if (const toml::table* figs = root["figures"].as_table()) {
        for (const auto& [item, files] : *figs) {
            auto& list = ref.figures[std::string(item.str())];
            if (auto s = files.value<std::string>()) list.push_back(*s);
            else if (const toml::array* a = files.as_array())
                for (const auto& f : *a) list.push_back(f.value<std::string>().value_or(""));
        }
    }
    std::set<std::string> seen;
    if (const toml::array* checks = root["check"].as_array()) {
        for (const auto& node : *checks) {
            const toml::table* t = node.as_table();
            if (!t) fail(path, node.source(), "[[check]] must be a table");
            ReferenceEntry e = parse_entry(*t, path);
            if (!seen.insert(e.id).second) fail(path, t->source(), "check id '" + e.id + "' appears twice");
            ref.entries.push_back(std::move(e));
        }
    }
    return ref;
}

}  // namespace fem::check
