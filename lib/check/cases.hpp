#pragma once
// Independent cases of a study, run concurrently: on the cores of this machine (threads), and across
// the ranks of an MPI run when the study is started with mpirun from its MPI build
// (build/bin/mpi/<study>; README.md "Sweeps on a cluster").
//
//   // Table 3-7's eight contact cases, each a full explicit run:
//   const std::vector<CaseRun> runs = check::run_cases<CaseRun>(study, 8, [&](int k) { return run_case(k); });
//   for (int k = 0; k < 8; ++k) { study.record_run(...); study.check(...); }   // afterwards, in case order
//
// The results come back in case order with the bits of a serial run (each case computes what it
// would alone: the explicit solver gives the same bits on any number of threads), so checks.json,
// figures and report rows are those of a serial run; only wall times differ.
//
// A case function must be independent of the others and of the order they run in: it may read
// what the study prepared, it must not touch the Study (record runs and checks after run_cases
// returns), Gmsh (one global model) or shared state it writes; files it writes must have names of
// their own (HDF5 writes are serialized by io::H5Writer), and a case that writes files must be
// named in CaseOptions::writes_files (under MPI only rank 0's files are kept, so it runs there).
// Exceptions: the first failing case (in case order) is rethrown after every case has ended.
//
// How the cases are dealt:
//  * One process: up to `jobs` cases at once, each on its own thread; when more than one case runs at
//    once each gets cores / jobs OpenMP threads (at least one). jobs = the study's --jobs N, else the
//    environment variable FEM_JOBS, else the hardware threads (shared out among the MPI ranks on the
//    machine); 1 runs them one after another on the calling thread, as before this facility.
//  * MPI (the study's MPI build under mpirun): the cases are dealt to the ranks in turn (the cases
//    that write files to rank 0), each rank runs its cases as above, and every rank receives every result (serialized as JSON: Result needs to_json and
//    from_json for nlohmann::json; without them every rank runs every case). Every rank then goes on
//    through the study alike; only rank 0 writes results and figures (the others write to a scratch
//    folder that is removed) and prints.
#include <concepts>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace fem::check {

class Study;

/// Where this process stands among the processes of an MPI run: rank 0 of 1 unless the program was
/// linked with the MPI backend (lib/check/mpi) and started by mpirun.
class Ranks {
public:
    virtual ~Ranks() = default;
    virtual int rank() const = 0;
    virtual int size() const = 0;
    /// Ranks on this machine (they share its cores).
    virtual int local_size() const { return 1; }
    /// Every rank's string, in rank order, on every rank (collective: every rank must call it).
    virtual std::vector<std::string> all_gather(const std::string& mine) const = 0;
};
/// The ranks of this process (serial by default).
const Ranks& ranks();
/// Installs another backend (the MPI one does so before main; lib/check/mpi/mpi_ranks.cpp); null:
/// serial again.
void set_ranks(std::unique_ptr<Ranks> backend);

/// Cases run at once in this process for `study` (see the top).
int case_jobs(const Study& study);
/// The same for a program without a Study (fem-sweep): `requested` when > 0 (its --jobs), else
/// FEM_JOBS, else the hardware threads shared among the MPI ranks on this machine.
int case_jobs(int requested);

namespace detail {
/// Under MPI with several ranks on this machine: each rank's OpenMP threads get their share of the
/// cores (unless OMP_NUM_THREADS says otherwise). Called by run_study.
void share_cores_among_local_ranks();
/// Runs run(k) for every k in `cases` on up to `jobs` threads (see the top); rethrows the first
/// failure in the order of `cases`.
void run_local(const std::vector<int>& cases, int jobs, const std::function<void(int)>& run);
template <class R>
concept JsonExchangeable = requires(const R& r, const nlohmann::json& j) {
    nlohmann::json(r);
    j.get<R>();
};
}  // namespace detail

struct CaseOptions {
    /// Cases that write files beside what they return (e.g. a VTU series): under MPI they run on rank
    /// 0, whose files are the study's.
    std::vector<int> writes_files;
};

namespace detail {
/// The rank that runs each of n cases: the cases in turn to ranks 0, 1, ..., those that write files
/// to rank 0.
std::vector<int> deal_cases(int n, int size, const CaseOptions& options);
}  // namespace detail

/// Runs fn(0), ..., fn(n - 1) (independent cases, see the top), up to `jobs` at once in this
/// process, and returns their results in case order, on every rank.
template <class Result, class F>
    requires std::invocable<F&, int> && std::convertible_to<std::invoke_result_t<F&, int>, Result>
std::vector<Result> run_cases(int jobs, int n, F&& fn, const CaseOptions& options = {}) {
    std::vector<std::unique_ptr<Result>> slots(n);
    const int size = ranks().size(), rank = ranks().rank();
    const bool deal = size > 1 && detail::JsonExchangeable<Result>;
    const std::vector<int> owner = detail::deal_cases(n, deal ? size : 1, options);
    std::vector<int> mine;
    for (int k = 0; k < n; ++k)
        if (!deal || owner[k] == rank) mine.push_back(k);
    detail::run_local(mine, jobs, [&](int k) { slots[k] = std::make_unique<Result>(fn(k)); });
    if constexpr (detail::JsonExchangeable<Result>) {
        if (deal) {
            // Every rank's results as one JSON array of [case, result], gathered on every rank.
            nlohmann::json out = nlohmann::json::array();
            for (int k : mine) out.push_back(nlohmann::json::array({k, nlohmann::json(*slots[k])}));
            for (const std::string& part : ranks().all_gather(out.dump()))
                for (const auto& item : nlohmann::json::parse(part)) {
                    const int k = item.at(0).get<int>();
                    slots[k] = std::make_unique<Result>(item.at(1).get<Result>());
                }
        }
    }
    std::vector<Result> results;
    results.reserve(n);
    for (auto& s : slots) results.push_back(std::move(*s));
    return results;
}

/// run_cases for a study: as many at once as case_jobs(study).
template <class Result, class F>
    requires std::invocable<F&, int> && std::convertible_to<std::invoke_result_t<F&, int>, Result>
std::vector<Result> run_cases(const Study& study, int n, F&& fn, const CaseOptions& options = {}) {
    return run_cases<Result>(case_jobs(study), n, std::forward<F>(fn), options);
}

}  // namespace fem::check
