#include "io/gnuplot.hpp"

#include <array>
#include <cstdio>
#include <memory>
#include <sstream>

#include "core/error.hpp"

namespace fem::io {

std::string gnuplot_string(std::string_view s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("''") : std::string(1, c);
    return q + "'";
}

namespace {
// `s` as one word of a POSIX shell command: between single quotes, each quote as '\''.
std::string shell_word(std::string_view s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}
}  // namespace

void run_gnuplot(const std::filesystem::path& script, const std::map<std::string, std::string>& variables) {
    if (!std::filesystem::exists(script)) throw InputError("gnuplot script '" + script.string() + "' not found");
    std::ostringstream cmd;
    std::string assignments;
    for (const auto& [name, value] : variables) assignments += name + "=" + gnuplot_string(value) + "; ";
    cmd << "gnuplot -e " << shell_word(assignments) << " " << shell_word(script.string()) << " 2>&1";
    FILE* pipe = popen(cmd.str().c_str(), "r");
    if (!pipe) throw SolverError("cannot start gnuplot (is the Debian package gnuplot-nox installed?)");
    std::string output;
    std::array<char, 512> buffer{};
    while (fgets(buffer.data(), buffer.size(), pipe)) output += buffer.data();
    const int status = pclose(pipe);
    if (status != 0)
        throw SolverError("gnuplot failed on '" + script.string() + "' (status " + std::to_string(status) +
                          "):\n" + output);
}

}  // namespace fem::io
