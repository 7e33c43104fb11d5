#include "input/arguments.hpp"

#include <fmt/format.h>

#include "core/error.hpp"

namespace fem::input {

Arguments::Arguments(int argc, char** argv, const std::vector<std::string_view>& options)
    : options_(options.begin(), options.end()) {
    for (int i = 1; i < argc; ++i) args_.emplace_back(argv[i]);
}

bool Arguments::next() {
    if (next_ >= args_.size()) return false;
    current_ = args_[next_++];
    return true;
}

std::string Arguments::value() {
    const std::string option = current_;
    if (next_ >= args_.size()) throw InputError(fmt::format("command line: option '{}' needs a value", option));
    current_ = args_[next_++];
    return current_;
}

double Arguments::real(Range range) {
    const std::string option = current_;
    const std::string v = value();
    return parse_real(v, {"command line", 0, option}, range);
}

std::vector<std::string> Arguments::operands() {
    std::vector<std::string> out;
    while (next_ < args_.size() && args_[next_].rfind("--", 0) != 0) out.push_back(args_[next_++]);
    return out;
}

void Arguments::positional(std::string& slot) {
    if (current_.size() > 1 && current_[0] == '-' && !to_real(current_)) unknown();
    if (!slot.empty())
        throw InputError(fmt::format("command line: unexpected argument '{}' ('{}' was given already; see --help)", current_, slot));
    slot = current_;
}

void Arguments::unknown() const {
    throw InputError(fmt::format("command line: unknown option '{}'{} (see --help)", current_, did_you_mean(current_, options_)));
}

}  // namespace fem::input
