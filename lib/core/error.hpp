#pragma once
// Errors the library raises for bad input. Every message names the culprit (file, element, material,
// parameter) so that a user can fix the input without reading the code; programs turn them into a
// one-line message and a non-zero exit (see fem::run_program).
#include <stdexcept>
#include <string>

namespace fem {

/// Bad input from a user: a missing file, a malformed mesh, a non-physical material, a request the
/// model cannot honour. The message is meant to be printed as it is.
class InputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A computation that went wrong on valid input: a run that became unstable, a solver that did not
/// converge. The message carries the diagnosis.
class SolverError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace fem
