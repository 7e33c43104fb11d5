// Strict typed input (lib/input): whole-string numbers, ranges, TOML getters, unused keys, command
// lines. Each refusal must name the file, line and key.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "core/error.hpp"
#include "input/arguments.hpp"
#include "input/toml_input.hpp"

using namespace fem;
using namespace fem::input;

namespace {

// The message of the InputError f throws ("no error" when it does not throw).
template <class F>
std::string error_of(F&& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

#define EXPECT_ERROR(expr, fragment)                                                       \
    do {                                                                                   \
        const std::string message_ = error_of([&] { (void)(expr); });                      \
        EXPECT_NE(message_.find(fragment), std::string::npos) << "message: " << message_;  \
    } while (0)

TEST(Numbers, WholeStringsOnly) {
    EXPECT_EQ(to_integer("42"), 42);
    EXPECT_EQ(to_integer(" -7 "), -7);
    EXPECT_EQ(to_integer("+3"), 3);
    EXPECT_FALSE(to_integer("3abc"));
    EXPECT_FALSE(to_integer(""));
    EXPECT_FALSE(to_integer("2.5"));
    EXPECT_FALSE(to_integer("99999999999999999999"));  // overflows long long
    EXPECT_EQ(to_real("2.5e3"), 2500.0);
    EXPECT_EQ(to_real("1."), 1.0);
    EXPECT_FALSE(to_real("1.5x"));
    EXPECT_FALSE(to_real("1e999"));
    EXPECT_TRUE(std::isnan(*to_real("nan")));
}

TEST(Numbers, RangesAndMessages) {
    const Where at{"model.inp", 40, "*ELASTIC, field 1"};
    EXPECT_EQ(parse_real("2.1e11", at, Range::positive()), 2.1e11);
    EXPECT_ERROR(parse_real("-2.1e11", at, Range::positive()), "model.inp:40: *ELASTIC, field 1: must be a finite number > 0, got -2.1e+11");
    EXPECT_ERROR(parse_real("nan", at), "must be a finite number, got nan");
    EXPECT_ERROR(parse_real("inf", at, Range::positive()), "got inf");
    EXPECT_ERROR(parse_real("0.5", at, Range::open(-1, 0.5)), "in (-1, 0.5), got 0.5");
    EXPECT_ERROR(parse_real("abc", at), "got 'abc'");
    EXPECT_EQ(parse_integer<int>("12", at, {.min = 1}), 12);
    EXPECT_ERROR(parse_integer<int>("0", at, {.min = 1}), "must be an integer >= 1, got 0");
    EXPECT_ERROR(parse_integer<int>("4294967298", at, {.min = 1}), "in [1, 2147483647], got 4294967298");
    EXPECT_ERROR(parse_integer<int>("3abc", at), "must be an integer, got '3abc'");
    EXPECT_ERROR(parse_integer<long long>("99999999999999999999", at), "got '99999999999999999999'");
    EXPECT_TRUE(Range::any().contains(1e300));
    EXPECT_FALSE(Range::any().contains(std::numeric_limits<double>::infinity()));
    EXPECT_TRUE(Range{.finite = false}.contains(std::numeric_limits<double>::infinity()));
}

TEST(Numbers, DidYouMean) {
    const std::vector<std::string> keys = {"modes", "shift_hz", "mass", "mesh"};
    EXPECT_EQ(did_you_mean("mdoes", keys), " (did you mean 'modes'?)");
    EXPECT_EQ(did_you_mean("shift", keys), "");  // three letters short of shift_hz: too far to guess
    EXPECT_EQ(did_you_mean("MESH", keys), " (did you mean 'mesh'?)");
    EXPECT_EQ(did_you_mean("colour", keys), "");
    EXPECT_EQ(one_of(keys), "modes, shift_hz, mass or mesh");
}

TEST(Numbers, CheckChoiceNamesTheValueTheOptionsAndTheNearest) {
    const std::vector<std::string> cases = {"rotating", "inverting"};
    const Where at{"command line", 0, "--shackle (case)"};
    EXPECT_EQ(check_choice("inverting", at, cases), "inverting");
    EXPECT_ERROR(check_choice("rotatin", at, cases),
                 "command line: --shackle (case): 'rotatin' is not rotating or inverting (did you mean 'rotating'?)");
    EXPECT_ERROR(check_choice("", at, cases), "'' is not rotating or inverting");
}

const char* kCase = R"(title = "demo"
modes = 4
shift_hz = -1.5
[materials.steel]
E = 210e9
nu = 0.3
[[parts]]
name = "a"
[[parts]]
name = "b"
at = [1.0, 2]
speed = [[0.0, 1.0], [0.5, 2.0]]
)";

TEST(TomlInput, TypedGettersAndFinish) {
    const auto doc = TomlDocument::parse(kCase, "case.toml", "/cases");
    const auto root = doc.root();
    EXPECT_EQ(root.string("title"), "demo");
    EXPECT_EQ(root.integer<int>("modes", {.min = 1}), 4);
    EXPECT_EQ(root.real_or("shift_hz", 0.0), -1.5);
    EXPECT_EQ(root.integer_or<int>("basis", 7), 7);  // absent: the fallback
    const auto mats = root.table("materials").entries();
    ASSERT_EQ(mats.size(), 1u);
    EXPECT_EQ(mats[0].first, "steel");
    EXPECT_EQ(mats[0].second.name(), "materials.steel");
    EXPECT_EQ(mats[0].second.real("E", Range::positive()), 210e9);
    EXPECT_EQ(mats[0].second.real("nu"), 0.3);
    const auto parts = root.tables("parts");
    ASSERT_EQ(parts.size(), 2u);
    EXPECT_EQ(parts[1].name(), "parts[1]");
    EXPECT_EQ(parts[0].string("name"), "a");
    EXPECT_EQ(parts[1].string("name"), "b");
    EXPECT_EQ(parts[1].reals("at", 2), (std::vector<double>{1.0, 2.0}));
    EXPECT_EQ(parts[1].matrix("speed", 2).size(), 2u);
    EXPECT_NO_THROW(doc.finish());
    EXPECT_EQ(root.path("title"), std::filesystem::path("/cases/demo"));
}

TEST(TomlInput, RefusesWrongTypesRangesAndNonFinite) {
    const auto root = [](const std::string& text) { return TomlDocument::parse(text, "case.toml").root(); };
    EXPECT_ERROR(root("modes = \"five\"").integer<int>("modes"), "case.toml:1: modes: must be an integer, got a string (\"five\")");
    EXPECT_ERROR(root("modes = 2.5").integer<int>("modes"), "must be an integer, got 2.5");
    EXPECT_EQ(root("modes = 3.0").integer<int>("modes"), 3);  // an integral float is that integer
    EXPECT_ERROR(root("modes = 4294967298").integer<int>("modes", {.min = 1}), "in [1, 2147483647], got 4294967298");
    EXPECT_ERROR(root("max_iterations = 1e20").integer<int>("max_iterations", {.min = 1}), "in [1, 2147483647], got 1e+20");
    EXPECT_ERROR(root("\n\nE = nan").real("E", Range::positive()), "case.toml:3: E: must be a finite number > 0, got nan");
    EXPECT_ERROR(root("E = inf").real("E"), "got inf");
    EXPECT_ERROR(root("E = -inf").real_or("E", 1.0), "got -inf");
    EXPECT_ERROR(root("x = true").real("x"), "got a boolean (true)");
    EXPECT_ERROR(root("mass = \"lumpd\"").choice("mass", {"consistent", "lumped"}), "'lumpd' is not consistent or lumped (did you mean 'lumped'?)");
    EXPECT_ERROR(root("at = [1.0]").reals("at", 2), "must be an array of 2 numbers, got 1 values");
    EXPECT_ERROR(root("at = [1.0, nan]").reals("at", 2), "at[1]: must be a finite number, got nan");
    EXPECT_ERROR(root("at = 1.0").reals("at", 2), "must be an array of numbers, got 1");
    EXPECT_ERROR(root("fix = [\"x\", \"z\"]").choices("fix", {"x", "y"}), "fix[1]: 'z' is not x or y");
    EXPECT_ERROR(root("s = [[0.0, 1.0], [1.0]]").matrix("s", 2), "s[1]: must be an array of 2 numbers");
    EXPECT_ERROR(root("a = 1").string("b"), "missing key 'b'");
    EXPECT_ERROR(root("[t]\nx = 1").table("t").real("y"), "case.toml:1: t: missing key 'y'");
    EXPECT_ERROR(root("p = 1").tables("p"), "must be an array of tables");
    EXPECT_ERROR(TomlDocument::parse("[domain\n", "case.toml"), "case.toml:1:");
}

TEST(TomlInput, UnknownAndUnusedKeysAreRefused) {
    {  // a misspelt key: the reader asked for "modes" and never read "mdoes"
        const auto doc = TomlDocument::parse("mesh = \"a.msh\"\nmdoes = 2\n", "case.toml");
        doc.root().string("mesh");
        doc.root().integer_or<int>("modes", 10);
        EXPECT_ERROR(doc.finish(), "case.toml:2: unknown key 'mdoes' (did you mean 'modes'?)");
    }
    {  // inside a table of an array of tables
        const auto doc = TomlDocument::parse("[[parts]]\nname = \"a\"\n[[parts]]\nname = \"b\"\nthicknes = 1.0\n", "case.toml");
        for (const auto& p : doc.root().tables("parts")) p.string("name"), p.real_or("thickness", 0.0);
        EXPECT_ERROR(doc.finish(), "case.toml:5: parts[1]: unknown key 'thicknes' (did you mean 'thickness'?)");
    }
    {  // a key the reader knows but did not use with these settings
        const auto doc = TomlDocument::parse("type = \"rectangle\"\nmesh = \"a.msh\"\n", "case.toml");
        doc.root().allow({"type", "mesh"});
        doc.root().string("type");
        EXPECT_ERROR(doc.finish(), "'mesh' has no effect with the other settings");
    }
    {  // a whole table nobody read
        const auto doc = TomlDocument::parse("a = 1\n[extra]\nb = 2\n", "case.toml");
        doc.root().integer<int>("a");
        EXPECT_ERROR(doc.finish(), "unknown key 'extra'");
    }
    // allow() refuses at once
    EXPECT_ERROR(TomlDocument::parse("modes = 1\ncolour = 3\n", "case.toml").root().allow({"modes", "color"}),
                 "case.toml:2: unknown key 'colour' (did you mean 'color'?)");
}

TEST(Arguments, WholeNumbersAndUnknownOptions) {
    auto run = [](std::vector<std::string> words) {
        std::vector<char*> argv;
        static std::string program = "fem-test";
        argv.push_back(program.data());
        for (auto& w : words) argv.push_back(w.data());
        Arguments args(static_cast<int>(argv.size()), argv.data(), {"--modes", "--output", "--scale"});
        std::string positional, output;
        int modes = 0;
        double scale = 1;
        while (args.next()) {
            if (args.is("--modes")) modes = args.integer<int>({.min = 1});
            else if (args.is("--output")) output = args.value();
            else if (args.is("--scale")) scale = args.real(Range::positive());
            else args.positional(positional);
        }
        return std::to_string(modes) + " " + output + " " + positional + " " + std::to_string(scale);
    };
    EXPECT_EQ(run({"case.toml", "--modes", "5", "--output", "out"}), "5 out case.toml 1.000000");
    EXPECT_ERROR(run({"--modes", "3abc"}), "command line: --modes: must be an integer >= 1, got '3abc'");
    EXPECT_ERROR(run({"--modes", "0"}), "must be an integer >= 1, got 0");
    EXPECT_ERROR(run({"--modes", "-1"}), "got -1");
    EXPECT_ERROR(run({"--modes"}), "option '--modes' needs a value");
    EXPECT_ERROR(run({"--scale", "nan"}), "--scale: must be a finite number > 0, got nan");
    EXPECT_ERROR(run({"--mdoes", "3"}), "unknown option '--mdoes' (did you mean '--modes'?)");
    EXPECT_ERROR(run({"a.toml", "b.toml"}), "unexpected argument 'b.toml'");

    // An option with a variable number of operands: those up to the next option.
    std::vector<std::string> words = {"prog", "--shackle", "rotating", "-0.5", "--results", "out", "--grasp"};
    std::vector<char*> argv;
    for (auto& w : words) argv.push_back(w.data());
    Arguments args(static_cast<int>(argv.size()), argv.data(), {"--shackle", "--results", "--grasp"});
    ASSERT_TRUE(args.next() && args.is("--shackle"));
    EXPECT_EQ(args.operands(), (std::vector<std::string>{"rotating", "-0.5"}));
    ASSERT_TRUE(args.next() && args.is("--results"));
    EXPECT_EQ(args.value(), "out");
    ASSERT_TRUE(args.next() && args.is("--grasp"));
    EXPECT_TRUE(args.operands().empty());
    EXPECT_FALSE(args.next());
}

}  // namespace

namespace {
// A case file in text, with the settings applied, read back through the strict getters.
TomlDocument with_settings(const char* text, std::initializer_list<Setting> settings) {
    TomlDocument doc = TomlDocument::parse(text, "case.toml");
    for (const Setting& s : settings) doc.apply(s);
    return doc;
}

constexpr const char* kSettingsCase = R"(
[control]
end_time = 1.0
[[material]]
name = "steel"
E = 210e9
[[material]]
name = "rubber"
E = 6.1e6
[[part]]
name = "bar"
size = [1.0, 0.02, 0.02]
)";
}  // namespace

TEST(Settings, ReplaceValuesByTablePathIndexOrEntryName) {
    const TomlDocument doc = with_settings(kSettingsCase, {Setting::parse("control.end_time=0.5", "--set 1"),
                                                   Setting::parse("material[rubber].E = 2e6", "--set 2"),
                                                   Setting::parse("material[0].E=7e10", "--set 3"),
                                                   Setting::parse("part[bar].size=[2.0, 0.1, 0.1]", "--set 4"),
                                                   Setting::parse("part[0].mesh=box", "--set 5"),  // a bare word: a string
                                                   Setting::parse("control.threads=2", "--set 6")});  // absent from the file
    const TomlTable root = doc.root();
    EXPECT_EQ(root.table("control").real("end_time"), 0.5);
    EXPECT_EQ(root.table("control").integer<int>("threads"), 2);
    const auto materials = root.tables("material");
    EXPECT_EQ(materials[0].real("E"), 7e10);
    EXPECT_EQ(materials[1].real("E"), 2e6);
    const auto part = root.tables("part")[0];
    EXPECT_EQ(part.reals("size", 3), (std::vector<double>{2.0, 0.1, 0.1}));
    EXPECT_EQ(part.string("mesh"), "box");
}

TEST(Settings, ABadSettingNamesItsOriginAndThePath) {
    EXPECT_ERROR(Setting::parse("control.end_time", "--set control.end_time"),
                 "--set control.end_time: expected KEY=VALUE (e.g. part[finger].alpha=20), got no '='");
    EXPECT_ERROR(Setting::parse("=1", "--set =1"), "no key before '='");
    EXPECT_ERROR(Setting::parse("a=", "--set a="), "no value after '='");
    EXPECT_ERROR(with_settings(kSettingsCase, {{"material[rubbr].E", "1", "--set x"}}),
                 "--set x: material[rubbr].E: no [[material]] entry has name = \"rubbr\" (did you mean 'rubber'?)");
    EXPECT_ERROR(with_settings(kSettingsCase, {{"material[2].E", "1", "--set x"}}), "'material' has 2 entries (0 to 1), not [2]");
    EXPECT_ERROR(with_settings(kSettingsCase, {{"materials[0].E", "1", "--set x"}}), "the case has no 'materials' (did you mean 'material'?)");
    EXPECT_ERROR(with_settings(kSettingsCase, {{"control[0].end_time", "1", "--set x"}}), "'control' is not an array of tables");
    EXPECT_ERROR(with_settings(kSettingsCase, {{"control.end_time.x", "1", "--set x"}}), "'control.end_time' is not a table");
    EXPECT_ERROR(with_settings(kSettingsCase, {{"material[0]", "1", "--set x"}}), "names a whole table");
    EXPECT_ERROR(with_settings(kSettingsCase, {{"control", "1", "--set x"}}), "replaces a table by a value");
    EXPECT_ERROR(with_settings(kSettingsCase, {{"control.end_time", "[1, ", "--set x"}}), "'[1, ' is not a TOML value");
    EXPECT_ERROR(with_settings(kSettingsCase, {{"control..end_time", "1", "--set x"}}), "is not of the form");
    EXPECT_ERROR(with_settings(kSettingsCase, {{"material[.E", "1", "--set x"}}), "'[' without ']'");
}

TEST(Settings, TheReaderNamesTheSettingNotALineOfTheFile) {
    // A value the reader refuses, and a key it does not know, are reported at the setting.
    TomlDocument doc = with_settings(kSettingsCase, {{"material[rubber].E", "-1.0", "--set material[rubber].E=-1.0"},
                                             {"control.end_tme", "2.0", "--set control.end_tme=2.0"}});
    const TomlTable root = doc.root();
    EXPECT_ERROR(root.tables("material")[1].real("E", Range::positive()),
                 "--set material[rubber].E=-1.0: material[1].E: must be a finite number > 0, got -1");
    root.table("control").real("end_time");
    (void)root.tables("material")[0].real("E");
    (void)root.tables("part")[0].reals("size");
    (void)root.tables("material")[0].string("name");
    (void)root.tables("material")[1].string("name");
    (void)root.tables("part")[0].string("name");
    EXPECT_ERROR(doc.finish(), "--set control.end_tme=2.0: control: unknown key 'end_tme' (did you mean 'end_time'?)");
    // An array element of a set array has no line either.
    const TomlDocument arrays = with_settings(kSettingsCase, {{"part[bar].size", "[1.0, -2.0, 0.1]", "--set S"}});
    EXPECT_ERROR(arrays.root().tables("part")[0].reals("size", 3, Range::positive()), "--set S: part[0].size[1]: must be a finite number > 0");
}

TEST(Settings, ValueTextsParseBackToTheSameValues) {
    const std::vector<std::string> literals{"0.1",  "7e10",          "3.0",        "-2",   "true", "\"a \\\"b\\\"\"",
                                            "[1.0, 2.5]", "{ x = 1.5e-300 }", "1e-5", "\"tab\\there\\r\\n\\u0001\""};
    std::string array = "v = [";
    for (std::size_t i = 0; i < literals.size(); ++i) array += (i ? ", " : "") + literals[i];
    const std::vector<std::string> texts = TomlDocument::parse(array + "]", "sweep.toml").root().value_texts("v");
    ASSERT_EQ(texts.size(), literals.size());
    EXPECT_EQ(texts[0], "0.1");
    EXPECT_EQ(texts[1], "7e+10");
    EXPECT_EQ(texts[2], "3.0");
    EXPECT_EQ(texts[3], "-2");
    EXPECT_EQ(texts[4], "true");
    EXPECT_EQ(texts[5], literals[5]);
    EXPECT_EQ(texts[6], "[1.0, 2.5]");
    // Each text parses back to the original value, to the bit (and type: 3.0 stays a float).
    for (std::size_t i = 0; i < texts.size(); ++i)
        EXPECT_TRUE(toml::parse("w = " + texts[i]) == toml::parse("w = " + literals[i])) << texts[i] << " vs " << literals[i];
    EXPECT_ERROR(TomlDocument::parse("v = []", "s.toml").root().value_texts("v"), "at least one value");
}
