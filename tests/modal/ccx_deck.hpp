#pragma once
// CalculiX (ccx) as the peer solver of the modal tests: writes a *FREQUENCY deck of a tet10 model
// (C3D10), runs ccx, and reads the eigenvalues back from the .dat file.
//
// Node order: C3D10 numbers the mid-edge nodes 01, 12, 02, 03, 13, 23, ours (Gmsh) 01, 12, 02, 03,
// 23, 13: the last two are swapped on the way out.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "material/elastic.hpp"
#include "mesh/mesh.hpp"

namespace fem::test {

/// Writes <dir>/<job>.inp: every tet10 block as C3D10 of material m, the nodes of `clamped` fixed,
/// `modes` eigenmodes by *FREQUENCY (ccx's default: Lanczos on the consistent mass).
inline void write_ccx_frequency_deck(const std::filesystem::path& dir, const std::string& job, const Mesh& mesh,
                                     const ElasticMaterial& m, const std::vector<int>& clamped, int modes) {
    std::filesystem::create_directories(dir);
    std::ofstream out(dir / (job + ".inp"));
    out << "*HEADING\nfem modal peer test\n*NODE, NSET=NALL\n";
    for (int i = 0; i < mesh.node_count(); ++i)
        out << fmt::format("{}, {:.17g}, {:.17g}, {:.17g}\n", i + 1, mesh.nodes[i].x(), mesh.nodes[i].y(), mesh.nodes[i].z());
    out << "*ELEMENT, TYPE=C3D10, ELSET=EALL\n";
    int id = 1;
    const int to_ccx[10] = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};
    for (const auto& b : mesh.blocks) {
        if (b.shape != ElementShape::Tet10) throw std::invalid_argument("ccx deck: only tet10 blocks");
        for (int e = 0; e < b.size(); ++e) {
            const auto c = b.element(e);
            out << id++;
            for (int k = 0; k < 10; ++k) out << (k == 8 ? ",\n" : ", ") << c[to_ccx[k]] + 1;
            out << '\n';
        }
    }
    out << "*NSET, NSET=FIXED\n";
    for (std::size_t i = 0; i < clamped.size(); ++i) out << clamped[i] + 1 << (i % 8 == 7 ? ",\n" : ", ");
    out << "\n*BOUNDARY\nFIXED, 1, 3\n";
    out << fmt::format("*MATERIAL, NAME=M\n*ELASTIC\n{:.17g}, {:.17g}\n*DENSITY\n{:.17g}\n", m.youngs_modulus, m.poissons_ratio,
                       m.density);
    out << "*SOLID SECTION, ELSET=EALL, MATERIAL=M\n*STEP\n*FREQUENCY\n" << modes << "\n*END STEP\n";
    if (!out) throw std::runtime_error("cannot write the ccx deck in " + dir.string());
}

/// Runs `ccx <job>` in `dir` (output to <job>.log); returns the wall time [s]. Throws when ccx
/// fails.
inline double run_ccx(const std::filesystem::path& dir, const std::string& job) {
    const std::string cmd = "cd '" + dir.string() + "' && OMP_NUM_THREADS=1 ccx " + job + " > " + job + ".log 2>&1";
    const auto t0 = std::chrono::steady_clock::now();
    const int rc = std::system(cmd.c_str());
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (rc != 0) throw std::runtime_error("ccx failed (exit " + std::to_string(rc) + "); see " + (dir / (job + ".log")).string());
    return t;
}

/// Frequencies [Hz] from the "E I G E N V A L U E   O U T P U T" table of <job>.dat (the
/// cycles/time column).
inline std::vector<double> read_ccx_frequencies(const std::filesystem::path& dat) {
    std::ifstream in(dat);
    if (!in) throw std::runtime_error("no ccx output " + dat.string());
    std::string line;
    bool table = false;
    std::vector<double> f;
    const std::regex row(R"(^\s*(\d+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s*$)");
    while (std::getline(in, line)) {
        if (line.find("E I G E N V A L U E   O U T P U T") != std::string::npos) table = true, f.clear();
        else if (table && line.find("P A R T I C I P A T I O N") != std::string::npos) break;
        std::smatch mt;
        if (table && std::regex_match(line, mt, row)) f.push_back(std::stod(mt[4].str()));
    }
    return f;
}

/// Prints ours beside ccx's frequencies for the first `modes` modes and returns the number of modes
/// whose relative difference exceeds `tolerance` (the exit status of a peer test). With rigid > 0,
/// a mode whose |f| is below rigid times the largest frequency compared is a rigid-body mode: it
/// must be one in both (round-off values, not compared).
inline int compare_with_ccx(const std::vector<double>& f_ccx, const std::vector<double>& f_ours, int modes,
                            double tolerance, const char* ccx_label, const char* ours_label, double rigid = 0.0) {
    std::printf("mode   %-14s  %-14s  rel. diff\n", ccx_label, ours_label);
    int failed = 0;
    double scale = 0.0;
    for (int k = 0; k < modes; ++k) scale = std::max(scale, std::abs(f_ccx[k]));
    for (int k = 0; k < modes; ++k) {
        const bool rigid_ccx = std::abs(f_ccx[k]) < rigid * scale, rigid_ours = std::abs(f_ours[k]) < rigid * scale;
        if (rigid_ccx || rigid_ours) {
            const bool ok = rigid_ccx && rigid_ours;
            failed += !ok;
            std::printf("%4d  %14.7g  %14.7g  rigid-body mode%s\n", k + 1, f_ccx[k], f_ours[k], ok ? " in both" : " in one only: FAIL");
            continue;
        }
        const double d = f_ours[k] / f_ccx[k] - 1.0;
        const bool ok = std::abs(d) <= tolerance;
        failed += !ok;
        std::printf("%4d  %14.7g  %14.7g  %+.2e %s\n", k + 1, f_ccx[k], f_ours[k], d, ok ? "" : "FAIL");
    }
    std::printf("%s (|rel. diff| <= %g)\n", failed ? "peer comparison FAILED" : "peer comparison passed", tolerance);
    return failed;
}

}  // namespace fem::test
