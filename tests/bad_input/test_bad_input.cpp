// The bad-input corpus (cases.toml): every case runs the program in-process on a scratch copy of
// inputs/ and must end with its exit status and message, writing nothing when it refuses (and its
// results when it exits 1: a run that finished but failed its health check). One
// process for the whole corpus: a program start costs about 0.3 s of loading libgmsh and its
// dependencies, a case a few milliseconds.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "check/build_paths.hpp"
#include "cli/programs.hpp"
#include "input/toml_input.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kCorpus = fem::check::source_dir() / "tests" / "bad_input";

struct Case {
    std::string name, program, input;
    std::vector<std::pair<std::string, std::string>> replace;
    std::vector<std::string> args, messages;
    int exit = 2;
};

// gtest prints a parameter by its name, not as bytes.
void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

std::string fill(std::string text, const std::string& field, const std::string& value) {
    for (std::size_t pos; (pos = text.find(field)) != std::string::npos;) text.replace(pos, field.size(), value);
    return text;
}

// Reads cases.toml (with the library's own strict reader: a typo in the corpus is refused too).
std::vector<Case> load_cases() {
    const auto doc = fem::input::TomlDocument::read(kCorpus / "cases.toml");
    const auto root = doc.root();
    root.allow({"case", "sweep"});
    std::vector<Case> cases;
    for (const auto& t : root.tables("case")) {
        t.allow({"name", "program", "input", "replace", "args", "exit", "messages"});
        Case c;
        c.name = t.string("name");
        c.program = t.choice("program", {"fem-modal", "fem-topopt", "fem-explicit", "fem-sweep"});
        c.input = t.string("input");
        if (t.has("replace"))
            for (const auto& row : t.string_matrix("replace", 2)) c.replace.emplace_back(row[0], row[1]);
        c.args = t.has("args") ? t.strings("args") : std::vector<std::string>{};
        c.exit = t.integer<int>("exit", {.min = 0, .max = 4});
        c.messages = t.strings("messages");
        cases.push_back(std::move(c));
    }
    for (const auto& t : root.tables("sweep")) {
        t.allow({"name", "program", "input", "values", "messages", "fields"});
        const std::string name = t.string("name"), program = t.choice("program", {"fem-modal", "fem-topopt", "fem-explicit", "fem-sweep"});
        const std::string input = t.string("input");
        const auto values = t.strings("values");
        const auto messages = t.strings("messages");
        for (const auto& field : t.string_matrix("fields", 3))
            for (const auto& value : values) {
                Case c;
                c.name = name + "-" + field.at(2) + "-" + value;
                c.program = program;
                c.input = input;
                c.replace = {{field.at(0), fill(field.at(1), "{}", value)}};
                for (const auto& m : messages) c.messages.push_back(fill(fill(m, "{key}", field.at(2)), "{value}", value));
                cases.push_back(std::move(c));
            }
    }
    doc.finish();
    return cases;
}

const std::vector<Case>& corpus() {
    static const std::vector<Case> cases = load_cases();
    return cases;
}

// Runs program(args) in-process; returns the exit status, with stdout and stderr captured.
int run(const std::string& program, std::vector<std::string> args, std::string& printed) {
    static const std::map<std::string, std::function<int(int, char**)>> programs = {
        {"fem-modal", fem::cli::modal_program}, {"fem-topopt", fem::cli::topopt_program}, {"fem-explicit", fem::cli::explicit_program},
        {"fem-sweep", fem::cli::sweep_program}};
    args.insert(args.begin(), program);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::ostringstream out;
    auto* old_out = std::cout.rdbuf(out.rdbuf());
    auto* old_err = std::cerr.rdbuf(out.rdbuf());
    const int status = programs.at(program)(static_cast<int>(args.size()), argv.data());
    std::cout.rdbuf(old_out);
    std::cerr.rdbuf(old_err);
    printed = out.str();
    return status;
}

class BadInput : public ::testing::TestWithParam<Case> {};

TEST_P(BadInput, EndsAsExpected) {
    const Case& c = GetParam();
    const fs::path work = fs::temp_directory_path() / ("fem_bad_input_" + std::to_string(::getpid())) / c.name;
    fs::remove_all(work);
    fs::create_directories(work);
    fs::copy(kCorpus / "inputs", work, fs::copy_options::recursive);
    std::vector<std::string> args;
    if (!c.input.empty()) {
        const fs::path input = work / c.input;
        std::ifstream in(input);
        ASSERT_TRUE(in) << "no input " << input;
        std::stringstream text;
        text << in.rdbuf();
        std::string s = text.str();
        for (const auto& [from, to] : c.replace) {
            const auto pos = s.find(from);
            ASSERT_NE(pos, std::string::npos) << c.name << ": '" << from << "' is not in " << c.input;
            ASSERT_EQ(s.find(from, pos + 1), std::string::npos) << c.name << ": '" << from << "' occurs twice in " << c.input;
            s.replace(pos, from.size(), to);
        }
        std::ofstream(input) << s;
        args.push_back(input.string());
    }
    const fs::path out = work / "out";
    args.insert(args.end(), {"--output", out.string()});
    args.insert(args.end(), c.args.begin(), c.args.end());

    std::string printed;
    const int status = run(c.program, args, printed);
    EXPECT_EQ(status, c.exit) << c.name << " printed:\n" << printed;
    for (const auto& m : c.messages) EXPECT_NE(printed.find(m), std::string::npos) << c.name << ": expected '" << m << "' in:\n" << printed;
    if (status == 1) {  // a run that finished but failed a check (fem-explicit's run health, a sweep's case): its results are kept
        const auto kept = c.program == "fem-sweep" ? std::vector<const char*>{"summary.txt", "sweep.csv"}
                                                   : std::vector<const char*>{"summary.txt", "run.json"};
        for (const char* f : kept)
            EXPECT_TRUE(fs::exists(out / f)) << c.name << " failed its check but did not write " << f;
    } else if (status != 0 && fs::exists(out)) {
        for (const auto& entry : fs::recursive_directory_iterator(out))
            EXPECT_FALSE(entry.is_regular_file()) << c.name << " was refused but wrote " << entry.path();
    }
    if (!::testing::Test::HasFailure()) fs::remove_all(work);
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
    std::string s = info.param.name;
    for (char& ch : s)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
    return s;
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadInput, ::testing::ValuesIn(corpus()), case_name);

TEST(BadInputCorpus, IsLargeAndNamesAreUnique) {
    std::vector<std::string> names;
    for (const auto& c : corpus()) names.push_back(case_name({c, 0}));
    std::sort(names.begin(), names.end());
    EXPECT_EQ(std::adjacent_find(names.begin(), names.end()), names.end()) << "two cases share a name";
    EXPECT_GE(names.size(), 60u);
}

}  // namespace
