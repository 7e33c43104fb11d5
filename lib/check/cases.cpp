#include "check/cases.hpp"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <string>
#include <thread>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "check/study.hpp"
#include "core/error.hpp"

namespace fem::check {

namespace {
class SerialRanks final : public Ranks {
public:
    int rank() const override { return 0; }
    int size() const override { return 1; }
    std::vector<std::string> all_gather(const std::string& mine) const override { return {mine}; }
};

std::unique_ptr<Ranks>& backend() {
    static std::unique_ptr<Ranks> b = std::make_unique<SerialRanks>();
    return b;
}

int hardware_threads() { return std::max(1, static_cast<int>(std::thread::hardware_concurrency())); }
}  // namespace

const Ranks& ranks() { return *backend(); }

void set_ranks(std::unique_ptr<Ranks> b) { backend() = b ? std::move(b) : std::make_unique<SerialRanks>(); }

int case_jobs(const Study& study) { return case_jobs(study.jobs()); }

int case_jobs(int requested) {
    if (requested > 0) return requested;
    if (const char* env = std::getenv("FEM_JOBS")) {
        char* end = nullptr;
        const long j = std::strtol(env, &end, 10);
        if (end == env || *end != '\0' || j < 1)
            throw InputError(std::string("FEM_JOBS='") + env + "': a positive number of cases at once expected");
        return static_cast<int>(j);
    }
    return std::max(1, hardware_threads() / ranks().local_size());
}

namespace detail {

std::vector<int> deal_cases(int n, int size, const CaseOptions& options) {
    std::vector<int> owner(n, 0);
    int next = 0;
    for (int k = 0; k < n; ++k)
        if (std::find(options.writes_files.begin(), options.writes_files.end(), k) == options.writes_files.end())
            owner[k] = next++ % size;
    return owner;
}

void share_cores_among_local_ranks() {
#ifdef _OPENMP
    if (ranks().local_size() > 1 && !std::getenv("OMP_NUM_THREADS"))
        omp_set_num_threads(std::max(1, omp_get_max_threads() / ranks().local_size()));
#endif
}

void run_local(const std::vector<int>& cases, int jobs, const std::function<void(int)>& run) {
    const int n = static_cast<int>(cases.size());
    std::vector<std::exception_ptr> failure(n);
    const int workers = std::min(n, std::max(1, jobs));
    if (workers <= 1) {  // one after another on this thread, with its OpenMP threads
        for (int i = 0; i < n; ++i) {
            try {
                run(cases[i]);
            } catch (...) {
                failure[i] = std::current_exception();
            }
        }
    } else {
        // Cases claimed in order by the workers; each worker's OpenMP threads share the cores.
        std::atomic<int> next{0};
#ifdef _OPENMP
        const int omp_threads = std::max(1, omp_get_max_threads() / workers);
#endif
        auto work = [&]() {
#ifdef _OPENMP
            omp_set_num_threads(omp_threads);
#endif
            for (int i = next++; i < n; i = next++) {
                try {
                    run(cases[i]);
                } catch (...) {
                    failure[i] = std::current_exception();
                }
            }
        };
        std::vector<std::thread> pool;
        for (int w = 0; w < workers; ++w) pool.emplace_back(work);
        for (auto& t : pool) t.join();
    }
    for (const auto& f : failure)
        if (f) std::rethrow_exception(f);
}

}  // namespace detail
}  // namespace fem::check
