// A fem-modal run killed with SIGKILL at moments spread over its whole length (reading, solving,
// writing 80 mode files) must leave no half-written file under a final name: every file in the
// output folder is then byte-identical to the one a complete run writes (runs are deterministic,
// so any partial file would differ). The next run cleans up what the killed one left and gives the
// complete run's folder byte for byte (HDF5 included: no time stamps).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "check/build_paths.hpp"
#include "mesh/mesh.hpp"

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

const fs::path kWork = fs::temp_directory_path() / ("fem_test_killed_run_" + std::to_string(::getpid()));

// A 20 x 4 x 4 hexahedral beam as a Gmsh 2.2 file: physical volume "beam", the x = 0 face "root".
void write_beam(const fs::path& msh) {
    const fem::Mesh m = fem::box_hex8(1.0, 0.05, 0.05, 20, 4, 4, "beam");
    const auto& block = m.blocks.front();
    std::vector<std::string> elements;
    for (int e = 0; e < block.size(); ++e) {
        const auto n = block.element(e);
        if (m.nodes[n[0]].x() == 0.0)  // the face x = 0 of a hexahedron: its nodes 0 4 7 3
            elements.push_back("3 2 2 2 " + std::to_string(n[0] + 1) + ' ' + std::to_string(n[4] + 1) + ' ' +
                               std::to_string(n[7] + 1) + ' ' + std::to_string(n[3] + 1));
    }
    for (int e = 0; e < block.size(); ++e) {
        std::string line = "5 2 1 1";
        for (int k : block.element(e)) line += ' ' + std::to_string(k + 1);
        elements.push_back(line);
    }
    std::ofstream out(msh);
    out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n2 2 \"root\"\n3 1 \"beam\"\n$EndPhysicalNames\n";
    out << "$Nodes\n" << m.node_count() << "\n";
    for (int i = 0; i < m.node_count(); ++i) out << i + 1 << ' ' << m.nodes[i].x() << ' ' << m.nodes[i].y() << ' ' << m.nodes[i].z() << '\n';
    out << "$EndNodes\n$Elements\n" << elements.size() << "\n";
    for (std::size_t i = 0; i < elements.size(); ++i) out << i + 1 << ' ' << elements[i] << '\n';
    out << "$EndElements\n";
}

// Starts fem-modal on the case into `out` (stdout and stderr to out.log); returns its pid.
pid_t start(const fs::path& out) {
    const std::string program = (fem::check::bin_dir() / "fem-modal").string();
    const std::string case_file = (kWork / "beam.toml").string(), dir = out.string(), log = out.string() + ".log";
    const pid_t pid = ::fork();
    if (pid == 0) {
        std::freopen(log.c_str(), "w", stdout);
        std::freopen(log.c_str(), "a", stderr);
        ::execl(program.c_str(), program.c_str(), case_file.c_str(), "--output", dir.c_str(), static_cast<char*>(nullptr));
        std::_Exit(127);
    }
    return pid;
}

int wait_for(pid_t pid) {
    int status = 0;
    ::waitpid(pid, &status, 0);
    return status;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// The visible files under dir (not the lock, pending list, staging folders or temporaries of a run), relative.
std::vector<std::string> visible_files(const fs::path& dir) {
    std::vector<std::string> files;
    if (!fs::exists(dir)) return files;
    for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator(); ++it) {
        const std::string name = it->path().filename().string();
        if (name.rfind(".run-", 0) == 0 && it->is_directory()) {
            it.disable_recursion_pending();
            continue;
        }
        if (it->is_regular_file() && name != ".lock" && name != ".manifest-pending")  // RunFolder's bookkeeping
            files.push_back(fs::relative(it->path(), dir).generic_string());
    }
    std::sort(files.begin(), files.end());
    return files;
}

std::vector<std::string> everything(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::recursive_directory_iterator(dir)) names.push_back(fs::relative(e.path(), dir).generic_string());
    std::sort(names.begin(), names.end());
    return names;
}

}  // namespace

TEST(KilledRun, LeavesNoHalfWrittenFileUnderAFinalName) {
    fs::remove_all(kWork);
    fs::create_directories(kWork);
    write_beam(kWork / "beam.msh");
    std::ofstream(kWork / "beam.toml") << "mesh = \"beam.msh\"\nmodes = 80\n[materials.steel]\nE = 210e9\nnu = 0.3\n"
                                          "rho = 7800.0\n[[parts]]\nname = \"beam\"\nmaterial = \"steel\"\n"
                                          "[[supports]]\nset = \"root\"\n";
    // The complete run: the reference every file must match.
    const fs::path ref = kWork / "reference";
    const auto t0 = Clock::now();
    ASSERT_EQ(wait_for(start(ref)), 0) << slurp(ref.string() + ".log");
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    const auto ref_files = visible_files(ref);
    ASSERT_GT(ref_files.size(), 80u);  // frequencies.csv, modes.h5, modes.pvd, 80 VTUs, manifest.txt

    // Kills spread over the run's length (a first complete run in `out` makes the kills also hit a
    // folder that already holds a set, as a rerun would).
    const fs::path out = kWork / "out";
    ASSERT_EQ(wait_for(start(out)), 0);
    int killed = 0;
    for (int k = 0; k < 8; ++k) {
        const pid_t pid = start(out);
        std::this_thread::sleep_for(std::chrono::duration<double>(seconds * k / 8.0));
        ::kill(pid, SIGKILL);
        const int status = wait_for(pid);
        killed += WIFSIGNALED(status);
        for (const auto& f : visible_files(out))
            EXPECT_EQ(slurp(out / f), slurp(ref / f)) << "after a kill at " << seconds * k / 8.0 << " s: " << f
                                                      << " is not the complete run's file";
    }
    EXPECT_GT(killed, 4) << "the runs ended before they could be killed: the test no longer tests anything";

    // The next run cleans up after the killed ones and gives the reference folder byte for byte.
    ASSERT_EQ(wait_for(start(out)), 0) << slurp(out.string() + ".log");
    EXPECT_EQ(everything(out), everything(ref));  // no lock, staging folder or temporary left
    for (const auto& f : ref_files) EXPECT_EQ(slurp(out / f), slurp(ref / f)) << f << " differs between identical runs";
    if (!::testing::Test::HasFailure()) fs::remove_all(kWork);
}
