#pragma once
// Strict reading of user input, part 1: where a value came from, the bounds it must respect, and
// whole-string number parsing. Every reader of user input shares this (TOML case files through
// input/toml_input.hpp, command lines through input/arguments.hpp, line-based decks directly), so a
// bad value gets the same message everywhere:
//
//   case.toml:12: materials.steel.E: must be a finite number, got nan
//   case.toml:3: modes: must be an integer >= 1, got 2.5
//   model.inp:40: *ELASTIC, field 1: must be > 0, got -2.1e11
//   command line: --modes: must be an integer >= 1, got '3abc'
//
// A line-based reader (e.g. an Abaqus/CalculiX deck) splits a line into fields and calls the parsers
// with a Where naming the file, line and field:
//
//   const input::Where at{deck.string(), line_number, "*ELASTIC, field 1 (E)"};
//   const double E = input::parse_real(fields[0], at, input::Range::positive());
//   const int node = input::parse_integer<int>(fields[0], at, {.min = 1});
//   if (!known) input::fail(at, "unknown element type 'C3D27'" + input::did_you_mean("C3D27", supported));
#include <concepts>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace fem::input {

/// The origin of a value: file (or "command line"), line (0 = unknown) and key path
/// ("materials.steel.E", "parts[2].thickness", "--modes", "*ELASTIC, field 1").
struct Where {
    std::string file;
    int line = 0;
    std::string key;

    /// "file:line: key" (parts left out when empty or 0).
    std::string str() const;
};

/// Throws fem::InputError "file:line: key: what".
[[noreturn]] void fail(const Where& where, std::string_view what);

/// Bounds of a real value. Non-finite values (nan, inf) are refused unless `finite` is false.
struct Range {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool min_open = false, max_open = false;  // strict inequality at that end
    bool finite = true;

    static Range any() { return {}; }                                     // any finite number
    static Range positive() { return {.min = 0, .min_open = true}; }      // > 0
    static Range non_negative() { return {.min = 0}; }                    // >= 0
    static Range at_least(double a) { return {.min = a}; }                // >= a
    static Range above(double a) { return {.min = a, .min_open = true}; } // > a
    static Range closed(double a, double b) { return {.min = a, .max = b}; }                           // [a, b]
    static Range open(double a, double b) { return {.min = a, .max = b, .min_open = true, .max_open = true}; }  // (a, b)
    static Range left_open(double a, double b) { return {.min = a, .max = b, .min_open = true}; }      // (a, b]

    bool contains(double x) const;
    /// "> 0", "in (0, 1)", ">= 1", "a finite number" ...
    std::string describe() const;
};

/// Bounds of an integer value of type I (default: every value of I).
template <std::integral I>
struct Limits {
    I min = std::numeric_limits<I>::min();
    I max = std::numeric_limits<I>::max();
};

/// Whole-string parsing, no exceptions: surrounding blanks are allowed, anything else that is not
/// part of the number is not ("3abc", "", "0x10" give nullopt). Reals accept nan and inf; integers
/// refuse overflow of long long.
std::optional<long long> to_integer(std::string_view text);
std::optional<double> to_real(std::string_view text);

/// Parses text as an integer of type I within limits; InputError at `where` otherwise
/// ("must be an integer >= 1, got '3abc'").
long long parse_integer(std::string_view text, const Where& where, long long min, long long max);
template <std::integral I>
I parse_integer(std::string_view text, const Where& where, Limits<I> limits = {}) {
    return static_cast<I>(parse_integer(text, where, static_cast<long long>(limits.min), static_cast<long long>(limits.max)));
}
/// Parses text as a real within range (finite unless range.finite is false); InputError otherwise.
double parse_real(std::string_view text, const Where& where, Range range = Range::any());

/// Checks an already-read real against a range; InputError at `where` naming the value.
double check_real(double value, const Where& where, Range range);
/// Checks an integer against limits; the message says "an integer >= 1" or "an integer in [a, b]".
long long check_integer(long long value, const Where& where, long long min, long long max);
/// "an integer >= 1", "an integer in [1, 2147483647]" ...
std::string describe_integer(long long min, long long max);
/// Checks that `value` is one of `options` (a keyword choice of a case file or a command line) and
/// returns it; InputError at `where` otherwise: "'lumpd' is not consistent or lumped (did you mean
/// 'lumped'?)".
std::string check_choice(std::string_view value, const Where& where, std::span<const std::string> options);

/// " (did you mean 'modes'?)" when one of `known` is close to `name` (edit distance, case
/// insensitive), else "". Appended to "unknown key/option/choice" messages.
std::string did_you_mean(std::string_view name, std::span<const std::string> known);
/// "a, b or c": the list of valid names for a message.
std::string one_of(std::span<const std::string> names);

}  // namespace fem::input
