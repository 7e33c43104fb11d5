#pragma once
// A design study over a fem-explicit case: one case file run many times with some of its values
// swept (`fem-sweep sweep.toml`), as a user's gripper study crosses drum speeds, finger damping and
// conveyor timings. Each case is the case file with input::Settings applied (the values of
// `fem-explicit --set`), run by run_case into a folder of its own; the sweep tabulates every case's
// status, the solver's numbers and the user's [[result]]s in one table. The cases run at once on the
// cores of this machine and, in the MPI build (build/bin/mpi/fem-sweep under mpirun), across machines
// (check/cases.hpp). The format, with every key: lib/explicit_case/CASE_FILE.md, "Sweeps".
//
//   case = "finger.toml"                  # the case every run starts from (relative to this file)
//   combine = "grid"                      # grid: every combination | list: the k-th values together
//   [[parameter]]
//   key = "part[finger].alpha"            # input::Setting's notation
//   values = [10.0, 20.0, 40.0]
//   [[parameter]]
//   key = "load[0].force"
//   values = [[0.0, -1.0, 0.0], [0.0, -2.0, 0.0]]
//   [[result]]
//   name = "peak tip deflection"          # its column in the table
//   column = "tip_uy_m"                   # a column of the run's histories.dat (or energies.dat)
//   reduce = "max_abs"                    # max | min | max_abs | final
//
// Outputs in the sweep's folder (default <stem>_results beside the sweep file): case-<k>/ (the run's
// files, as fem-explicit writes them, and sweep-case.json: the case's settings and status),
// sweep.csv and sweep.dat (one row per case), sweep.json (the same with the settings as TOML text and
// each case's message), summary.txt (the table as printed) and a figure per [[result]],
// sweep-<name>.svg (against the first numeric parameter, a line per combination of the others),
// drawn by gnuplot from sweep.gp. Reading is strict: every case's
// settings are applied and the case read before anything runs, so a key that does not exist, a
// value the case refuses or a result column the runs do not write stops the sweep at once
// (InputError naming the parameter or result), nothing written.
// A case that goes unstable, fails its health check or cannot be built is a row of the table with
// its status and message; the other cases go on.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "input/toml_input.hpp"

namespace fem::explicit_case {

/// One [[parameter]]: a case-file key and the values it takes (TOML text, as input::Setting::value).
struct SweepParameter {
    std::string key;
    std::vector<std::string> values;
    int line = 0;  // in the sweep file
};

/// One [[result]]: a number per case, reduced from a column of one of the run's .dat files.
struct SweepResult {
    std::string name;    // its column in the table (default "<reduce> <column>")
    std::string file;    // histories | energies (histories.dat, energies.dat)
    std::string column;  // e.g. "tip_uy_m" (an [[output.node]]'s name + quantity + unit), "kinetic_J"
    std::string reduce;  // max | min | max_abs | final
    std::string phase;   // a case with [[phase]]s: the phase whose files (empty: the last)
    int line = 0;
};

struct Sweep {
    std::string source;                 // the sweep file (messages)
    std::filesystem::path case_file;    // relative paths start at the sweep file's folder
    std::filesystem::path folder;       // outputs
    bool grid = true;                   // combine = "grid" (true) or "list"
    std::vector<SweepParameter> parameters;
    std::vector<SweepResult> results;

    /// The number of cases (grid: the product of the value counts; list: the common count).
    int size() const;
    /// The settings of case k (grid: the last parameter varies fastest, as nested loops).
    std::vector<input::Setting> settings(int k) const;
    /// Case k's value of each parameter as a table shows it (a string without its quotes).
    std::vector<std::string> shown_values(int k) const;
    /// Case k's folder: folder / "case-<k>" (k zero-padded to the digits of size() - 1).
    std::filesystem::path case_folder(int k) const;
};

/// Reads a sweep file (InputError "file:line: key: problem"; strict as every case file).
Sweep read_sweep(const std::filesystem::path& file);

/// The solver's numbers in every row, from run.json of the case's (last phase's) run.
const std::vector<std::string>& sweep_solver_columns();

/// One case's row of the table.
struct SweepRow {
    std::string status;           // ok | unhealthy | unstable | error
    std::string message;          // for a case that is not ok: why (the health verdict, the error)
    std::vector<double> numbers;  // sweep_solver_columns() then the [[result]]s; NaN where there is none
    double seconds = 0.0;         // wall time of the case
};
void to_json(nlohmann::json& j, const SweepRow& r);
void from_json(const nlohmann::json& j, SweepRow& r);

struct SweepOptions {
    int jobs = 0;         // cases at once in this process (0: check::case_jobs's default)
    bool quiet = false;   // no line per case on stderr
    bool resume = false;  // keep the cases a previous run of the same sweep completed (sweep-case.json)
    bool list = false;    // read every case and list them (values, folder), run nothing, write nothing
};

struct SweepOutcome {
    std::vector<SweepRow> rows;
    std::string table;  // summary.txt: the table as printed
    /// Every case ran and passed its health check.
    bool all_ok() const;
};

/// Reads every case (nothing runs unless all can be read), runs them into their folders and writes
/// the sweep's files (see the top); with options.list only the first step, the table listing the
/// cases (rows empty). resume: a case whose folder holds the sweep-case.json of a
/// completed run with the same settings is not run again; its row is read from its files (so a
/// changed [[result]] list re-tabulates without running anything). Ctrl-C: fem::Interrupted after
/// the running cases stopped; the completed cases are kept for a resume.
SweepOutcome run_sweep(const Sweep& sweep, const SweepOptions& options = {});

}  // namespace fem::explicit_case
