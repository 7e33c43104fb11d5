#pragma once
// The common entry point of every command-line program of the project: it turns the library's
// exceptions into a one-line message on stderr and a non-zero exit status.
#include <functional>

namespace fem {

/// Runs body(); returns its exit status, or 2 for an InputError (bad input, named in the message),
/// 3 for a SolverError (a run that failed, with its diagnosis), 130 for a run stopped by Ctrl-C
/// (fem::Interrupted, core/progress.hpp: partial results written) and 4 for anything else.
int run_program(const char* program_name, const std::function<int()>& body);

}  // namespace fem
