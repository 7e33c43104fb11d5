// The MPI backend of fem::check::Ranks (check/cases.hpp). It is compiled into the MPI builds of the
// studies only (build/bin/mpi/<study>, see fem_study in CMakeLists.txt), as an object of the program
// itself, so that the installation below runs before main; the serial programs need no MPI at run
// time.
#include <mpi.h>

#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "check/cases.hpp"

namespace {

void check_mpi(int rc, const char* what) {
    if (rc != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}

// Returns when every rank has arrived here, sleeping in between instead of polling at full speed.
// A rank that finished its cases first waits in a collective for the others, and MPI implementations
// wait by polling: OpenMPI's rank then burns a whole core (measured: the two-rank CTest test of
// compliant_beam_damping took 2.8 x the serial study's CPU time), which on a machine running other
// jobs (ctest -j) is taken from them. A barrier that checks every 2 ms costs at most 2 ms per
// collective.
void wait_for_every_rank() {
    MPI_Request request;
    check_mpi(MPI_Ibarrier(MPI_COMM_WORLD, &request), "MPI_Ibarrier");
    for (int done = 0;;) {
        check_mpi(MPI_Test(&request, &done, MPI_STATUS_IGNORE), "MPI_Test");
        if (done) return;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
}

class MpiRanks final : public fem::check::Ranks {
public:
    MpiRanks() {
        int initialized = 0;
        MPI_Initialized(&initialized);
        if (!initialized) {
            // Only the main thread talks to MPI (run_cases gathers after its worker threads ended).
            int provided = 0;
            check_mpi(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
            owner_ = true;
        }
        MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
        MPI_Comm_size(MPI_COMM_WORLD, &size_);
        MPI_Comm local;  // the ranks on this machine, which share its cores
        check_mpi(MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &local),
                  "MPI_Comm_split_type");
        MPI_Comm_size(local, &local_size_);
        MPI_Comm_free(&local);
    }
    ~MpiRanks() override {
        int finalized = 0;
        MPI_Finalized(&finalized);
        if (owner_ && !finalized) {
            try {
                wait_for_every_rank();  // MPI_Finalize synchronizes too: the rank that ends first sleeps here
            } catch (const std::exception&) {  // (no throwing from a destructor; MPI_Finalize reports it)
            }
            MPI_Finalize();
        }
    }
    int rank() const override { return rank_; }
    int size() const override { return size_; }
    int local_size() const override { return local_size_; }
    std::vector<std::string> all_gather(const std::string& mine) const override {
        const int n = static_cast<int>(mine.size());
        wait_for_every_rank();
        std::vector<int> sizes(size_), offsets(size_ + 1, 0);
        check_mpi(MPI_Allgather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, MPI_COMM_WORLD), "MPI_Allgather");
        for (int r = 0; r < size_; ++r) offsets[r + 1] = offsets[r] + sizes[r];
        std::string all(offsets[size_], '\0');
        check_mpi(MPI_Allgatherv(mine.data(), n, MPI_CHAR, all.data(), sizes.data(), offsets.data(), MPI_CHAR,
                                 MPI_COMM_WORLD),
                  "MPI_Allgatherv");
        std::vector<std::string> parts(size_);
        for (int r = 0; r < size_; ++r) parts[r] = all.substr(offsets[r], sizes[r]);
        return parts;
    }

private:
    int rank_ = 0, size_ = 1, local_size_ = 1;
    bool owner_ = false;
};

const bool installed = [] {
    fem::check::set_ranks(std::make_unique<MpiRanks>());
    return true;
}();

}  // namespace
