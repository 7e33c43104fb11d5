#include "check/reference.hpp"

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
    e.judged = t["judged"].value<bool>().value_or(true);

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
    } else if (e.judged && !e.tolerance) {
        fail(path, t.source(), "check '" + e.id + "': a judged numeric check needs a tolerance (or judged = false)");
    }
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
