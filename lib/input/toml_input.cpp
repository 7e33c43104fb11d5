#include "input/toml_input.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <unordered_set>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fem::input {

struct TomlDocument::State {
    toml::table root;
    std::string source;
    std::filesystem::path base;
    std::unordered_set<const toml::node*> read;                   // values the reader took
    std::map<const toml::table*, std::vector<std::string>> asked;  // keys the reader asked for, per table
    std::map<const toml::node*, std::string> set_by;               // values replaced by a Setting: its origin

    // Where a value is: its line in the file, or the Setting that put it there.
    Where at(const toml::node* n, int line, std::string key) const {
        if (n)
            if (const auto s = set_by.find(n); s != set_by.end()) return {s->second, 0, std::move(key)};
        return {source, line, std::move(key)};
    }
};

namespace {

int line_of(const toml::node& n) { return static_cast<int>(n.source().begin.line); }

// "a string (\"five\")", "2.5", "an array" ...: what the file holds, for "must be X, got Y".
std::string describe(const toml::node& n) {
    if (auto s = n.as_string()) return fmt::format("a string (\"{}\")", s->get());
    if (auto i = n.as_integer()) return std::to_string(i->get());
    if (auto f = n.as_floating_point()) return fmt::format("{:.10g}", f->get());
    if (auto b = n.as_boolean()) return fmt::format("a boolean ({})", b->get());
    if (n.is_array()) return "an array";
    if (n.is_table()) return "a table";
    return "a date or time";
}

// A character of a bare TOML key (A-Za-z0-9_-).
bool bare_key_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'; }

std::string quoted_key(std::string_view key) {
    for (char c : key)
        if (!bare_key_char(c)) return fmt::format("\"{}\"", key);
    return std::string(key);
}

void add_unique(std::vector<std::string>& v, std::string_view s) {
    for (const auto& x : v)
        if (x == s) return;
    v.emplace_back(s);
}

}  // namespace

// ------------------------------------------------------------------------------------------------

TomlDocument TomlDocument::parse(std::string_view text, std::string source, std::filesystem::path base) {
    auto state = std::make_shared<State>();
    state->source = std::move(source);
    state->base = std::move(base);
    try {
        state->root = toml::parse(text, state->source);
    } catch (const toml::parse_error& e) {
        fail({state->source, static_cast<int>(e.source().begin.line), ""}, e.description());
    }
    return TomlDocument(std::move(state));
}

TomlDocument TomlDocument::read(const std::filesystem::path& file) {
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) throw InputError("case file '" + file.string() + "' does not exist");
    if (std::filesystem::is_directory(file, ec)) throw InputError("case file '" + file.string() + "' is a folder");
    std::ifstream in(file, std::ios::binary);
    if (!in) throw InputError("case file '" + file.string() + "' cannot be opened for reading");
    std::ostringstream text;
    text << in.rdbuf();
    return parse(text.str(), file.string(), file.parent_path().empty() ? "." : file.parent_path());
}

TomlTable TomlDocument::root() const { return TomlTable(state_, &state_->root, ""); }
const std::string& TomlDocument::source() const { return state_->source; }
const std::filesystem::path& TomlDocument::base() const { return state_->base; }

void TomlDocument::finish() const {
    // Depth first in file order; the first unread key is reported.
    const auto visit = [&](const auto& self, const toml::table& t, const std::string& name) -> void {
        const TomlTable table(state_, &t, name);
        for (const auto& [k, v] : t) {
            const std::string key(k.str());
            const auto asked = state_->asked.find(&t);
            const std::vector<std::string> known = asked == state_->asked.end() ? std::vector<std::string>{} : asked->second;
            if (!state_->read.count(&v)) {
                const Where at = state_->at(&v, static_cast<int>(k.source().begin.line), name);
                if (std::find(known.begin(), known.end(), key) != known.end())
                    fail(at, fmt::format("'{}' has no effect with the other settings of this case; remove it", key));
                fail(at, fmt::format("unknown key '{}'{}", key, did_you_mean(key, known)));
            }
            const std::string child = name.empty() ? quoted_key(key) : name + "." + quoted_key(key);
            if (const auto* sub = v.as_table()) self(self, *sub, child);
            if (const auto* arr = v.as_array())
                for (std::size_t i = 0; i < arr->size(); ++i)
                    if (const auto* sub = (*arr)[i].as_table()) self(self, *sub, fmt::format("{}[{}]", child, i));
        }
    };
    visit(visit, state_->root, "");
}

Setting Setting::parse(std::string_view assignment, std::string origin) {
    const auto trim = [](std::string_view s) {
        while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
        while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
        return std::string(s);
    };
    const auto eq = assignment.find('=');
    if (eq == std::string_view::npos) fail({origin, 0, ""}, "expected KEY=VALUE (e.g. part[finger].alpha=20), got no '='");
    Setting s{trim(assignment.substr(0, eq)), trim(assignment.substr(eq + 1)), std::move(origin)};
    if (s.key.empty()) fail({s.origin, 0, ""}, "expected KEY=VALUE, got no key before '='");
    if (s.value.empty()) fail({s.origin, 0, ""}, "expected KEY=VALUE, got no value after '='");
    return s;
}

namespace {

// One step of a Setting's key: a key, and for an array of tables the entry ("[2]", "[finger]").
struct KeyStep {
    std::string key, entry;
    bool has_entry = false;
};

std::vector<KeyStep> key_steps(const Setting& s) {
    std::vector<KeyStep> steps;
    const std::string& k = s.key;
    std::size_t i = 0;
    while (i <= k.size()) {
        KeyStep step;
        while (i < k.size() && k[i] != '.' && k[i] != '[') step.key += k[i++];
        if (i < k.size() && k[i] == '[') {
            const auto close = k.find(']', i);
            if (close == std::string::npos) fail({s.origin, 0, ""}, fmt::format("key '{}': '[' without ']'", k));
            step.entry = k.substr(i + 1, close - i - 1);
            step.has_entry = true;
            i = close + 1;
        }
        const bool bare = !step.key.empty() && std::all_of(step.key.begin(), step.key.end(), bare_key_char);
        if (!bare || (step.has_entry && step.entry.empty()))
            fail({s.origin, 0, ""}, fmt::format("key '{}' is not of the form table.key, array[index].key or array[name].key", k));
        steps.push_back(std::move(step));
        if (i == k.size()) break;
        if (k[i] != '.') fail({s.origin, 0, ""}, fmt::format("key '{}': expected '.' after ']'", k));
        ++i;
    }
    return steps;
}

// The TOML value of a Setting: its text as TOML, or a bare word as a string.
toml::table setting_value(const Setting& s) {
    try {
        return toml::parse("value = " + s.value);
    } catch (const toml::parse_error&) {
        const bool word = std::all_of(s.value.begin(), s.value.end(), [](char c) { return bare_key_char(c) || c == '.' || c == '+'; });
        if (!word)
            fail({s.origin, 0, s.key}, fmt::format("'{}' is not a TOML value (a number, true/false, \"text\", [a, b, ...] or "
                                                  "{{ key = value }})", s.value));
        toml::table t;
        t.insert("value", s.value);
        return t;
    }
}

void mark_set_by(std::map<const toml::node*, std::string>& set_by, const toml::node& n, const std::string& origin) {
    set_by[&n] = origin;
    if (const auto* t = n.as_table())
        for (const auto& [k, v] : *t) mark_set_by(set_by, v, origin);
    if (const auto* a = n.as_array())
        for (const auto& v : *a) mark_set_by(set_by, v, origin);
}

}  // namespace

void TomlDocument::apply(const Setting& s) {
    const std::vector<KeyStep> steps = key_steps(s);
    toml::table* table = &state_->root;
    std::string name;  // the messages' path of `table`
    for (std::size_t i = 0; i + 1 < steps.size(); ++i) {
        const KeyStep& step = steps[i];
        const std::string path = name.empty() ? step.key : name + "." + step.key;
        toml::node* n = table->get(step.key);
        if (!n) {
            std::vector<std::string> keys;
            for (const auto& [k, v] : *table)
                if (v.is_table() || v.is_array()) keys.emplace_back(k.str());
            fail({s.origin, 0, s.key}, fmt::format("the case has no '{}'{}", path, did_you_mean(step.key, keys)));
        }
        if (!step.has_entry) {
            if (!n->is_table()) fail({s.origin, 0, s.key}, fmt::format("'{}' is not a table", path));
            table = n->as_table();
            name = path;
            continue;
        }
        toml::array* array = n->as_array();
        if (!array || !array->is_array_of_tables())
            fail({s.origin, 0, s.key}, fmt::format("'{}' is not an array of tables ([[{}]] entries)", path, step.key));
        std::size_t index = array->size();
        const bool numeric = std::all_of(step.entry.begin(), step.entry.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
        std::vector<std::string> names;
        for (std::size_t e = 0; e < array->size(); ++e) {
            const toml::table& entry = *(*array)[e].as_table();
            const std::string entry_name = entry["name"].value_or(std::string{});
            if (!entry_name.empty()) names.push_back(entry_name);
            if (index == array->size() && (numeric ? std::to_string(e) == step.entry : entry_name == step.entry)) index = e;
        }
        if (index == array->size()) {
            if (numeric)
                fail({s.origin, 0, s.key}, fmt::format("'{}' has {} entries (0 to {}), not [{}]", path, array->size(),
                                                       array->size() - 1, step.entry));
            fail({s.origin, 0, s.key},
                 fmt::format("no [[{}]] entry has name = \"{}\"{}", path, step.entry, did_you_mean(step.entry, names)));
        }
        table = (*array)[index].as_table();
        name = fmt::format("{}[{}]", path, index);
    }
    const KeyStep& last = steps.back();
    if (last.has_entry)
        fail({s.origin, 0, s.key}, fmt::format("set a value, not an array entry: '{}[{}]' names a whole table", last.key, last.entry));
    toml::table parsed = setting_value(s);
    if (const toml::node* old = table->get(last.key); old && old->is_table() != parsed["value"].is_table())
        fail({s.origin, 0, s.key}, "replaces a table by a value or a value by a table");
    parsed["value"].node()->visit([&](auto&& v) { table->insert_or_assign(last.key, v); });
    mark_set_by(state_->set_by, *table->get(last.key), s.origin);
}

// ------------------------------------------------------------------------------------------------

std::string TomlTable::key_path(std::string_view key) const {
    return name_.empty() ? quoted_key(key) : name_ + "." + quoted_key(key);
}

Where TomlTable::where() const {
    const int line = table_ == &state_->root ? 0 : line_of(*table_);
    return state_->at(table_, line, name_);
}

Where TomlTable::where(std::string_view key) const {
    if (const toml::node* n = table_->get(key)) return state_->at(n, line_of(*n), key_path(key));
    Where at = where();
    at.key = key_path(key);
    return at;
}

void TomlTable::fail(std::string_view key, std::string_view what) const { input::fail(where(key), what); }
void TomlTable::fail(std::string_view what) const { input::fail(where(), what); }

bool TomlTable::has(std::string_view key) const {
    add_unique(state_->asked[table_], key);
    return table_->contains(key);
}

void TomlTable::allow(std::initializer_list<std::string_view> keys) const {
    auto& asked = state_->asked[table_];
    for (auto k : keys) add_unique(asked, k);
    std::vector<std::string> allowed(keys.begin(), keys.end());
    for (const auto& [k, v] : *table_)
        if (std::find(allowed.begin(), allowed.end(), k.str()) == allowed.end())
            input::fail(state_->at(&v, static_cast<int>(k.source().begin.line), name_),
                        fmt::format("unknown key '{}'{}", k.str(), did_you_mean(k.str(), allowed)));
}

std::vector<std::string> TomlTable::keys() const {
    std::vector<std::string> out;
    for (const auto& [k, v] : *table_) out.emplace_back(k.str());
    return out;
}

const toml::node* TomlTable::get(std::string_view key) const {
    add_unique(state_->asked[table_], key);
    const toml::node* n = table_->get(key);
    if (n) state_->read.insert(n);
    return n;
}

const toml::node& TomlTable::required(std::string_view key) const {
    const toml::node* n = get(key);
    if (!n) input::fail(where(), fmt::format("missing key '{}'", key));
    return *n;
}

namespace {

double real_of(const toml::node& n, const Where& at, Range range) {
    double v = 0;
    if (auto f = n.as_floating_point()) v = f->get();
    else if (auto i = n.as_integer()) v = static_cast<double>(i->get());
    else fail(at, fmt::format("must be {}, got {}", range.describe(), describe(n)));
    return check_real(v, at, range);
}

long long integer_of(const toml::node& n, const Where& at, long long min, long long max) {
    if (auto i = n.as_integer()) return check_integer(i->get(), at, min, max);
    // 3.0 or 1e3 where an integer is meant is that integer; 2.5, nan or 1e20 is refused.
    if (auto f = n.as_floating_point()) {
        const double v = f->get();
        if (std::isfinite(v) && v == std::trunc(v)) {
            if (v >= static_cast<double>(min) && v <= static_cast<double>(max) && v < 0x1p63) return static_cast<long long>(v);
            fail(at, fmt::format("must be an integer in [{}, {}], got {:.10g}", min, max, v));
        }
        fail(at, fmt::format("must be {}, got {:.10g}", describe_integer(min, max), v));
    }
    fail(at, fmt::format("must be {}, got {}", describe_integer(min, max), describe(n)));
}

std::string string_of(const toml::node& n, const Where& at) {
    if (auto s = n.as_string()) return s->get();
    fail(at, fmt::format("must be a string, got {}", describe(n)));
}

std::string checked_choice(const std::string& value, const Where& at, std::initializer_list<std::string_view> options) {
    return check_choice(value, at, std::vector<std::string>(options.begin(), options.end()));
}

const toml::array& array_of(const toml::node& n, const Where& at, std::string_view what) {
    if (auto a = n.as_array()) return *a;
    fail(at, fmt::format("must be an array of {}, got {}", what, describe(n)));
}

// An element of an array a Setting put there has no line either (its origin names it).
Where element_where(const Where& at, const toml::node& n, std::size_t i) {
    return {at.file, at.line > 0 ? line_of(n) : 0, fmt::format("{}[{}]", at.key, i)};
}

void check_count(const toml::array& a, std::size_t count, const Where& at, std::string_view what) {
    if (count > 0 && a.size() != count) fail(at, fmt::format("must be an array of {} {}, got {} values", count, what, a.size()));
    if (count == 0 && a.empty()) fail(at, fmt::format("must be an array of at least one {}, got an empty array", what));
}

}  // namespace

double TomlTable::real(std::string_view key, Range range) const { return real_of(required(key), where(key), range); }

double TomlTable::real_or(std::string_view key, double fallback, Range range) const {
    const toml::node* n = get(key);
    return n ? real_of(*n, where(key), range) : fallback;
}

std::optional<double> TomlTable::optional_real(std::string_view key, Range range) const {
    const toml::node* n = get(key);
    if (!n) return std::nullopt;
    return real_of(*n, where(key), range);
}

long long TomlTable::integer_impl(std::string_view key, const long long* fallback, long long min, long long max) const {
    const toml::node* n = fallback ? get(key) : &required(key);
    if (!n) return *fallback;
    return integer_of(*n, where(key), min, max);
}

std::string TomlTable::string(std::string_view key) const { return string_of(required(key), where(key)); }

std::string TomlTable::string_or(std::string_view key, std::string_view fallback) const {
    const toml::node* n = get(key);
    return n ? string_of(*n, where(key)) : std::string(fallback);
}

std::string TomlTable::choice(std::string_view key, std::initializer_list<std::string_view> options) const {
    return checked_choice(string(key), where(key), options);
}

std::string TomlTable::choice_or(std::string_view key, std::initializer_list<std::string_view> options,
                                 std::string_view fallback) const {
    return checked_choice(string_or(key, fallback), where(key), options);
}

bool TomlTable::boolean(std::string_view key) const {
    const toml::node& n = required(key);
    if (auto b = n.as_boolean()) return b->get();
    input::fail(where(key), fmt::format("must be true or false, got {}", describe(n)));
}

bool TomlTable::boolean_or(std::string_view key, bool fallback) const { return has(key) ? boolean(key) : fallback; }

std::filesystem::path TomlTable::path(std::string_view key) const {
    const std::string s = string(key);
    if (s.empty()) fail(key, "must name a file, got an empty string");
    const std::filesystem::path p(s);
    return p.is_absolute() ? p : state_->base / p;
}

std::vector<double> TomlTable::reals(std::string_view key, std::size_t count, Range range) const {
    const Where at = where(key);
    const toml::array& a = array_of(required(key), at, "numbers");
    check_count(a, count, at, "numbers");
    std::vector<double> out;
    for (std::size_t i = 0; i < a.size(); ++i) out.push_back(real_of(a[i], element_where(at, a[i], i), range));
    return out;
}

std::vector<long long> TomlTable::integers_impl(std::string_view key, std::size_t count, long long min, long long max) const {
    const Where at = where(key);
    const toml::array& a = array_of(required(key), at, "integers");
    check_count(a, count, at, "integers");
    std::vector<long long> out;
    for (std::size_t i = 0; i < a.size(); ++i) out.push_back(integer_of(a[i], element_where(at, a[i], i), min, max));
    return out;
}

std::vector<std::string> TomlTable::strings(std::string_view key) const {
    const Where at = where(key);
    const toml::array& a = array_of(required(key), at, "strings");
    std::vector<std::string> out;
    for (std::size_t i = 0; i < a.size(); ++i) out.push_back(string_of(a[i], element_where(at, a[i], i)));
    return out;
}

std::vector<std::string> TomlTable::choices(std::string_view key, std::initializer_list<std::string_view> options) const {
    const Where at = where(key);
    const toml::array& a = array_of(required(key), at, "strings");
    std::vector<std::string> out;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const Where e = element_where(at, a[i], i);
        out.push_back(checked_choice(string_of(a[i], e), e, options));
    }
    return out;
}

std::vector<std::vector<double>> TomlTable::matrix(std::string_view key, std::size_t columns, Range range) const {
    const Where at = where(key);
    const std::string row_kind = fmt::format("rows of {} numbers", columns);
    const toml::array& a = array_of(required(key), at, row_kind);
    if (a.empty()) fail(key, fmt::format("must be an array of {}, got an empty array", row_kind));
    std::vector<std::vector<double>> out;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const Where row_at = element_where(at, a[i], i);
        const toml::array& row = array_of(a[i], row_at, "numbers");
        check_count(row, columns, row_at, "numbers");
        std::vector<double> values;
        for (std::size_t j = 0; j < row.size(); ++j) values.push_back(real_of(row[j], element_where(row_at, row[j], j), range));
        out.push_back(std::move(values));
    }
    return out;
}

namespace {
// TOML text of a value that parses back to the same value (doubles in their shortest round-trip form).
std::string toml_text(const toml::node& n) {
    if (auto f = n.as_floating_point()) {
        const double v = f->get();
        if (std::isnan(v)) return "nan";
        if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
        char buffer[32];
        const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;  // shortest round trip
        std::string t(buffer, end);
        if (t.find_first_of(".eE") == std::string::npos) t += ".0";  // 3.0 stays a float
        return t;
    }
    if (auto i = n.as_integer()) return std::to_string(i->get());
    if (auto b = n.as_boolean()) return b->get() ? "true" : "false";
    if (auto s = n.as_string()) {
        std::string t = "\"";
        for (char c : s->get()) {
            const auto u = static_cast<unsigned char>(c);
            if (c == '"' || c == '\\') t += fmt::format("\\{}", c);
            else if ((u < 0x20 && c != '\t') || u == 0x7f) t += fmt::format("\\u{:04X}", u);  // TOML's escapes
            else t += c;
        }
        return t + "\"";
    }
    if (auto a = n.as_array()) {
        std::string t = "[";
        for (std::size_t i = 0; i < a->size(); ++i) t += fmt::format("{}{}", i ? ", " : "", toml_text((*a)[i]));
        return t + "]";
    }
    if (auto tb = n.as_table()) {
        std::string t = "{";
        bool first = true;
        for (const auto& [k, v] : *tb) {
            t += fmt::format("{}{} = {}", first ? " " : ", ", quoted_key(k.str()), toml_text(v));
            first = false;
        }
        return t + " }";
    }
    std::ostringstream os;  // dates and times as toml++ writes them
    n.visit([&](auto&& v) { os << v; });
    return os.str();
}
}  // namespace

std::vector<std::string> TomlTable::value_texts(std::string_view key) const {
    const Where at = where(key);
    const toml::array& a = array_of(required(key), at, "values");
    check_count(a, 0, at, "value");
    std::vector<std::string> out;
    for (std::size_t i = 0; i < a.size(); ++i) out.push_back(toml_text(a[i]));
    return out;
}

std::vector<std::vector<std::string>> TomlTable::string_matrix(std::string_view key, std::size_t columns) const {
    const Where at = where(key);
    const std::string row_kind = fmt::format("rows of {} strings", columns);
    const toml::array& a = array_of(required(key), at, row_kind);
    if (a.empty()) fail(key, fmt::format("must be an array of {}, got an empty array", row_kind));
    std::vector<std::vector<std::string>> out;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const Where row_at = element_where(at, a[i], i);
        const toml::array& row = array_of(a[i], row_at, "strings");
        check_count(row, columns, row_at, "strings");
        std::vector<std::string> values;
        for (std::size_t j = 0; j < row.size(); ++j) values.push_back(string_of(row[j], element_where(row_at, row[j], j)));
        out.push_back(std::move(values));
    }
    return out;
}

TomlTable TomlTable::table(std::string_view key) const {
    const toml::node& n = required(key);
    if (const auto* t = n.as_table()) return TomlTable(state_, t, key_path(key));
    input::fail(where(key), fmt::format("must be a table, got {}", describe(n)));
}

std::optional<TomlTable> TomlTable::optional_table(std::string_view key) const {
    if (!table_->contains(key)) {
        add_unique(state_->asked[table_], key);
        return std::nullopt;
    }
    return table(key);
}

std::vector<TomlTable> TomlTable::tables(std::string_view key) const {
    const toml::node* n = get(key);
    if (!n) return {};
    const auto* a = n->as_array();
    if (!a) input::fail(where(key), fmt::format("must be an array of tables ([[{}]] entries), got {}", key, describe(*n)));
    std::vector<TomlTable> out;
    for (std::size_t i = 0; i < a->size(); ++i) {
        const auto* t = (*a)[i].as_table();
        const std::string name = fmt::format("{}[{}]", key_path(key), i);
        if (!t) input::fail({state_->source, line_of((*a)[i]), name}, fmt::format("must be a table, got {}", describe((*a)[i])));
        state_->read.insert(t);
        out.push_back(TomlTable(state_, t, name));
    }
    return out;
}

std::vector<std::pair<std::string, TomlTable>> TomlTable::entries() const {
    std::vector<std::pair<std::string, TomlTable>> out;
    for (const auto& [k, v] : *table_) {
        const std::string key(k.str());
        state_->read.insert(&v);
        add_unique(state_->asked[table_], key);
        const auto* t = v.as_table();
        if (!t) input::fail(where(key), fmt::format("must be a table, got {}", describe(v)));
        out.emplace_back(key, TomlTable(state_, t, key_path(key)));
    }
    return out;
}

}  // namespace fem::input
