#pragma once
// Strict reading of user input, part 2: TOML case files. A thin layer over toml++ that every
// case-file reader uses (fem-modal, fem-topopt, fem-explicit, ...), so that every setting either
// takes effect as written or is refused with the file, line and key:
//   - typed getters refuse wrong types ("five" or 2.5 where an integer is meant), values outside
//     their range, nan/inf where a finite value is meant and integers that do not fit;
//   - a key the reader never read is refused by finish(): a misspelt key (`mdoes = 2`, with "did you
//     mean 'modes'?") or a key that has no effect with the other settings (`mesh` on a rectangle
//     domain); allow() refuses unknown keys of a table at once, before any work is done.
//
// Usage (a reader fills a plain struct, then calls finish()):
//
//   input::TomlDocument doc = input::TomlDocument::read(path);   // syntax errors: file:line
//   const input::TomlTable root = doc.root();
//   root.allow({"mesh", "modes", "shift_hz", "materials", "parts"});
//   c.mesh  = root.path("mesh");                                  // relative to the case file
//   c.modes = root.integer_or<int>("modes", 10, {.min = 1});
//   c.shift = root.real_or("shift_hz", 0.0);                      // finite
//   c.mass  = root.choice_or("mass", {"consistent", "lumped"}, "consistent");
//   for (const auto& [name, t] : root.table("materials").entries())    // [materials.steel] ...
//       mats[name] = {t.real("E", input::Range::positive()), t.real("nu", input::Range::open(-1, 0.5)), ...};
//   for (const input::TomlTable& p : root.tables("parts")) {      // [[parts]]: parts[0], parts[1] ...
//       p.allow({"name", "material", "thickness"});
//       if (!mats.count(p.string("material"))) p.fail("material", "is not defined under [materials]");
//   }
//   const auto xy = root.table("load").reals("at", 2);            // exactly two finite numbers
//   const auto schedule = root.matrix("speed", 2);                // [[t0, v0], [t1, v1], ...]
//   doc.finish();                                                 // unused keys are errors
//
// Messages: "case.toml:7: materials.steel.E: must be a number > 0, got -1",
// "case.toml:3: unknown key 'mdoes' (did you mean 'modes'?)", "case.toml:9: parts[1]: missing key 'material'".
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <toml++/toml.h>

#include "input/numbers.hpp"

namespace fem::input {

class TomlTable;

/// One value of a case file replaced before it is read (LS-DYNA's *PARAMETER, an ANSYS parameter):
/// `fem-explicit case.toml --set part[finger].alpha=20`, or one case of a sweep (fem-sweep). `key`
/// is in the notation of the reader's messages: tables by name, an entry of an array of tables by its
/// index or by the value of its `name` key ("control.end_time", "part[1].alpha",
/// "part[finger].alpha", "rigid_part[pallet].motion[0].speed"); `value` is TOML text ("0.5",
/// "[1.0, 0.0, 0.0]", "\"B\"", "true"; a bare word such as B is taken as the string "B"). The key's
/// table must exist; the key itself may be absent from the file (a value left at its default).
/// Messages about the value name `origin` instead of a line of the file ("--set part[1].alpha=-1:
/// part[1].alpha: must be a number >= 0, got -1"); the reader still refuses a key it does not know.
struct Setting {
    std::string key, value, origin;
    /// "key=value" (the first '='; spaces around either side dropped); InputError naming `origin`
    /// when there is no '=' or either side is empty.
    static Setting parse(std::string_view assignment, std::string origin);
};

/// A parsed TOML file and the record of which of its keys the reader has read.
class TomlDocument {
public:
    /// Reads and parses a file; InputError when it does not exist, cannot be read or is not TOML
    /// (with the line of the syntax error). Relative paths in it start from its folder.
    static TomlDocument read(const std::filesystem::path& file);
    /// Parses text; `source` names it in messages, `base` is where relative paths start.
    static TomlDocument parse(std::string_view text, std::string source, std::filesystem::path base = ".");

    /// Replaces (or adds) one value before anything is read (see Setting); InputError naming
    /// setting.origin when its table or array entry does not exist or the value is not TOML.
    void apply(const Setting& setting);

    TomlTable root() const;
    const std::string& source() const;
    const std::filesystem::path& base() const;

    /// Refuses the first key (in file order) that the reader never read, with a "did you mean"
    /// among the keys it asked for in that table. Call it when everything has been read.
    void finish() const;

private:
    struct State;
    explicit TomlDocument(std::shared_ptr<State> state) : state_(std::move(state)) {}
    std::shared_ptr<State> state_;
    friend class TomlTable;
};

/// One table of a TomlDocument (the root, [domain], one [[parts]] entry, ...). Cheap to copy; valid
/// while its document lives. Getters without a fallback require the key; the *_or getters return
/// the fallback when the key is absent, and refuse a present key of the wrong type or range.
class TomlTable {
public:
    /// Its path in messages: "" (root), "domain", "parts[2]", "materials.steel".
    const std::string& name() const { return name_; }
    bool has(std::string_view key) const;
    /// Refuses any key not in `keys` now (with a "did you mean"); finish() still refuses allowed keys
    /// that were never read.
    void allow(std::initializer_list<std::string_view> keys) const;
    /// The keys present, in file order.
    std::vector<std::string> keys() const;

    // --- scalars ---
    double real(std::string_view key, Range range = Range::any()) const;
    double real_or(std::string_view key, double fallback, Range range = Range::any()) const;
    std::optional<double> optional_real(std::string_view key, Range range = Range::any()) const;
    template <std::integral I>
    I integer(std::string_view key, Limits<I> limits = {}) const {
        return static_cast<I>(integer_impl(key, nullptr, limits.min, limits.max));
    }
    template <std::integral I>
    I integer_or(std::string_view key, I fallback, Limits<I> limits = {}) const {
        const long long f = fallback;
        return static_cast<I>(integer_impl(key, &f, limits.min, limits.max));
    }
    std::string string(std::string_view key) const;
    std::string string_or(std::string_view key, std::string_view fallback) const;
    /// A string that must be one of `options` ("did you mean" otherwise).
    std::string choice(std::string_view key, std::initializer_list<std::string_view> options) const;
    std::string choice_or(std::string_view key, std::initializer_list<std::string_view> options, std::string_view fallback) const;
    bool boolean(std::string_view key) const;
    bool boolean_or(std::string_view key, bool fallback) const;
    /// A file path, relative to the document's folder unless absolute.
    std::filesystem::path path(std::string_view key) const;

    // --- arrays ---
    /// An array of `count` reals (any length >= 1 when count is 0), each within range.
    std::vector<double> reals(std::string_view key, std::size_t count = 0, Range range = Range::any()) const;
    template <std::integral I>
    std::vector<I> integers(std::string_view key, std::size_t count = 0, Limits<I> limits = {}) const {
        std::vector<I> out;
        for (long long v : integers_impl(key, count, limits.min, limits.max)) out.push_back(static_cast<I>(v));
        return out;
    }
    /// An array of strings (may be empty).
    std::vector<std::string> strings(std::string_view key) const;
    /// An array of strings, each one of `options`.
    std::vector<std::string> choices(std::string_view key, std::initializer_list<std::string_view> options) const;
    /// An array of rows, each an array of `columns` reals within range (a table of values, a time
    /// schedule [[t0, v0], [t1, v1], ...]); at least one row.
    std::vector<std::vector<double>> matrix(std::string_view key, std::size_t columns, Range range = Range::any()) const;
    /// An array of any TOML values (at least one), each as TOML text that parses back to it: numbers
    /// with every digit (shortest round trip), strings quoted. The values of a sweep's parameter
    /// (Setting::value).
    std::vector<std::string> value_texts(std::string_view key) const;
    /// An array of rows of `columns` strings (a table of names); at least one row.
    std::vector<std::vector<std::string>> string_matrix(std::string_view key, std::size_t columns) const;

    // --- tables ---
    TomlTable table(std::string_view key) const;
    std::optional<TomlTable> optional_table(std::string_view key) const;
    /// An array of tables ([[key]] entries), named "key[0]", "key[1]" ...; empty when absent.
    std::vector<TomlTable> tables(std::string_view key) const;
    /// Every member of this table, each of which must be a table ([materials.steel], ...).
    std::vector<std::pair<std::string, TomlTable>> entries() const;

    // --- errors ---
    /// Where the key is (its line, or the table's when it is absent).
    Where where(std::string_view key) const;
    Where where() const;
    [[noreturn]] void fail(std::string_view key, std::string_view what) const;
    [[noreturn]] void fail(std::string_view what) const;

private:
    TomlTable(std::shared_ptr<TomlDocument::State> state, const toml::table* table, std::string name)
        : state_(std::move(state)), table_(table), name_(std::move(name)) {}
    const toml::node* get(std::string_view key) const;       // records the key as asked for, marks it read
    const toml::node& required(std::string_view key) const;  // get(); "missing key" when absent
    std::string key_path(std::string_view key) const;
    long long integer_impl(std::string_view key, const long long* fallback, long long min, long long max) const;
    std::vector<long long> integers_impl(std::string_view key, std::size_t count, long long min, long long max) const;

    std::shared_ptr<TomlDocument::State> state_;
    const toml::table* table_;
    std::string name_;
    friend class TomlDocument;
};

}  // namespace fem::input
