#include "input/numbers.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fem::input {

std::string Where::str() const {
    std::string s = file;
    if (line > 0) s += (s.empty() ? "line " : ":") + std::to_string(line);
    if (!key.empty()) s += (s.empty() ? "" : ": ") + key;
    return s;
}

void fail(const Where& where, std::string_view what) {
    const std::string w = where.str();
    throw InputError(w.empty() ? std::string(what) : w + ": " + std::string(what));
}

bool Range::contains(double x) const {
    if (std::isnan(x)) return false;
    if (finite && !std::isfinite(x)) return false;
    if (min_open ? !(x > min) : !(x >= min)) return false;
    if (max_open ? !(x < max) : !(x <= max)) return false;
    return true;
}

std::string Range::describe() const {
    const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
    const std::string kind = finite ? "a finite number" : "a number";
    if (!has_min && !has_max) return kind;
    if (has_min && has_max)
        return fmt::format("{} in {}{:.10g}, {:.10g}{}", kind, min_open ? '(' : '[', min, max, max_open ? ')' : ']');
    if (has_min) return fmt::format("{} {} {:.10g}", kind, min_open ? ">" : ">=", min);
    return fmt::format("{} {} {:.10g}", kind, max_open ? "<" : "<=", max);
}

namespace {

std::string_view trim(std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    return s;
}

std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

// Edit distance with transpositions (optimal string alignment): "mdoes" is one edit from "modes".
std::size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
    for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
        for (std::size_t j = 1; j <= b.size(); ++j) {
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

}  // namespace

std::optional<long long> to_integer(std::string_view text) {
    text = trim(text);
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    if (text.empty()) return std::nullopt;
    long long v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return v;
}

std::optional<double> to_real(std::string_view text) {
    text = trim(text);
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    if (text.empty()) return std::nullopt;
    double v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    // errc::result_out_of_range: 1e999 (overflow) is refused; an underflow (1e-999) reads as 0 in
    // from_chars' contract but is out of range too: refused the same way, since it is not the number
    // written.
    if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return v;
}

std::string describe_integer(long long min, long long max) {
    // The largest int or long long is a limit of the type, not of the setting: not worth a mention
    // unless a value exceeds it (check_integer then shows the full range).
    const bool has_min = min != std::numeric_limits<long long>::min() && min != std::numeric_limits<int>::min();
    const bool has_max = max != std::numeric_limits<long long>::max() && max != std::numeric_limits<int>::max();
    if (has_min && has_max) return fmt::format("an integer in [{}, {}]", min, max);
    if (has_min) return fmt::format("an integer >= {}", min);
    if (has_max) return fmt::format("an integer <= {}", max);
    return "an integer";
}

long long check_integer(long long value, const Where& where, long long min, long long max) {
    if (value > max) fail(where, fmt::format("must be an integer in [{}, {}], got {}", min, max, value));
    if (value < min) fail(where, fmt::format("must be {}, got {}", describe_integer(min, max), value));
    return value;
}

long long parse_integer(std::string_view text, const Where& where, long long min, long long max) {
    const auto v = to_integer(text);
    if (!v) {
        // Say why: a real number where an integer is meant, an integer too large, or no number.
        const auto r = to_real(text);
        if (r && std::isfinite(*r) && *r == std::trunc(*r))
            fail(where, fmt::format("must be an integer in [{}, {}], got '{}'", min, max, trim(text)));
        fail(where, fmt::format("must be {}, got '{}'", describe_integer(min, max), trim(text)));
    }
    return check_integer(*v, where, min, max);
}

double check_real(double value, const Where& where, Range range) {
    if (!range.contains(value)) fail(where, fmt::format("must be {}, got {:.10g}", range.describe(), value));
    return value;
}

double parse_real(std::string_view text, const Where& where, Range range) {
    const auto v = to_real(text);
    if (!v) fail(where, fmt::format("must be {}, got '{}'", range.describe(), trim(text)));
    return check_real(*v, where, range);
}

std::string check_choice(std::string_view value, const Where& where, std::span<const std::string> options) {
    if (std::find(options.begin(), options.end(), value) == options.end())
        fail(where, fmt::format("'{}' is not {}{}", value, one_of(options), did_you_mean(value, options)));
    return std::string(value);
}

std::string did_you_mean(std::string_view name, std::span<const std::string> known) {
    const std::string n = lower(name);
    std::size_t best = std::string::npos;
    std::string best_name;
    for (const auto& k : known) {
        const std::size_t d = edit_distance(n, lower(k));
        if (d < best) best = d, best_name = k;
    }
    // A close name: a typo or two (longer names tolerate more), or the same letters in another case.
    const std::size_t allowed = std::clamp<std::size_t>(n.size() / 3, 1, 3);
    if (best_name.empty() || best > allowed) return "";
    return " (did you mean '" + best_name + "'?)";
}

std::string one_of(std::span<const std::string> names) {
    std::string s;
    for (std::size_t i = 0; i < names.size(); ++i) s += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    return s;
}

}  // namespace fem::input
