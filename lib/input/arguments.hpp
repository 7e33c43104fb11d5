#pragma once
// Strict reading of user input, part 3: command lines. Option values are parsed whole with the same
// rules and messages as case-file values ("--modes 3abc" and "--modes 0" are refused, not read as 3
// or the default), an unknown option gets a "did you mean", and a missing value is named.
//
//   input::Arguments args(argc, argv, {"--output", "--modes", "--help"});
//   while (args.next()) {
//       if (args.is("--help")) { ...; return 0; }
//       else if (args.is("--output")) output = args.value();
//       else if (args.is("--modes")) modes = args.integer<int>({.min = 1});
//       else if (args.is("--scale")) scale = args.real(input::Range::positive());
//       else args.positional(case_file);    // the one positional argument (a second is refused)
//   }
#include <string>
#include <string_view>
#include <vector>

#include "input/numbers.hpp"

namespace fem::input {

class Arguments {
public:
    /// `options`: every option the program knows (for "unknown option" and "did you mean").
    Arguments(int argc, char** argv, const std::vector<std::string_view>& options);

    /// Moves to the next argument; false at the end.
    bool next();
    /// The current argument.
    const std::string& current() const { return current_; }
    bool is(std::string_view option) const { return current_ == option; }

    /// The value of the current option (the next argument); InputError when there is none.
    std::string value();
    template <std::integral I>
    I integer(Limits<I> limits = {}) {
        const std::string option = current_;
        const std::string v = value();
        return parse_integer<I>(v, {"command line", 0, option}, limits);
    }
    double real(Range range = Range::any());
    /// The operands of the current option: the arguments after it up to the next option (an argument
    /// that starts with "--"), consumed; none is an empty list. "--shackle rotating 0.13 --results
    /// out" gives {"rotating", "0.13"} for --shackle. A negative number ("-30") is an operand.
    std::vector<std::string> operands();

    /// Stores the current argument as the positional argument `slot`; InputError for an unknown
    /// option (an argument starting with '-') or when the slot is already filled.
    void positional(std::string& slot);
    /// InputError "unknown option" (with "did you mean") for the current argument.
    [[noreturn]] void unknown() const;

private:
    std::vector<std::string> args_;
    std::vector<std::string> options_;
    std::size_t next_ = 0;
    std::string current_;
};

}  // namespace fem::input
