// Peer test (CTest label "peer"): the first ten natural frequencies of a small folded-plate portal frame
// (two clamped columns and a beam of one thin steel strip, corners shared), our MITC4 shells against
// CalculiX S4 shells (*FREQUENCY) on the same mesh.
//   peer_ccx_shell <work dir>
// CalculiX expands each S4 shell into a layer of C3D8I bricks and joins the folds with "knots"; ours is
// a degenerated-solid MITC4 with a drilling penalty: different formulations, both converged on this
// mesh (6 x 154 elements, about 10 mm). Tolerance (set before running): 2 % per mode. Measured: at
// most 0.6 % (mode 7), most modes within 0.15 %.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "assembly/model.hpp"
#include "ccx_deck.hpp"
#include "core/program.hpp"
#include "element/shell_mitc4.hpp"
#include "modal/modal.hpp"

using namespace fem;

int main(int argc, char** argv) {
    return run_program("peer_ccx_shell", [&]() {
        const std::filesystem::path dir = argc > 1 ? argv[1] : "peer_ccx_shell";
        const auto steel = ElasticMaterial::make("steel", 210e9, 0.28, 7700.0);
        constexpr int kModes = 10;
        constexpr double kTol = 0.02;
        const double H = 0.4, L = 0.7, W = 0.06, t = 0.002;
        const int nc = 41, nb = 72, m = 6;  // element size ~9.8 mm along, 10 mm across

        // The strip: left column up, beam, right column down; rows of m + 1 nodes across y.
        Mesh mesh;
        std::vector<Vec3> path;
        for (int i = 0; i <= nc; ++i) path.emplace_back(0, 0, H * i / nc);
        for (int i = 1; i <= nb; ++i) path.emplace_back(L * i / nb, 0, H);
        for (int i = 1; i <= nc; ++i) path.emplace_back(L, 0, H * (nc - i) / nc);
        std::vector<std::vector<int>> id;
        for (const Vec3& p : path) {
            id.emplace_back();
            for (int k = 0; k <= m; ++k) id.back().push_back(mesh.add_node(p + Vec3(0, W * k / m, 0)));
        }
        ElementBlock blk{"frame", ElementShape::Quad4, {}};
        for (std::size_t i = 0; i + 1 < id.size(); ++i)
            for (int k = 0; k < m; ++k) {
                const int q[4] = {id[i][k], id[i + 1][k], id[i + 1][k + 1], id[i][k + 1]};
                blk.add(q);
            }
        mesh.blocks.push_back(blk);
        std::vector<int> base(id.front());
        base.insert(base.end(), id.back().begin(), id.back().end());

        // CalculiX deck: S4 shells, clamped base (all six DOFs of the shell nodes).
        std::filesystem::create_directories(dir);
        {
            std::ofstream out(dir / "frame.inp");
            out << "*HEADING\nMITC4 peer test: folded-plate portal frame\n*NODE, NSET=NALL\n";
            for (int i = 0; i < mesh.node_count(); ++i)
                out << fmt::format("{}, {:.12g}, {:.12g}, {:.12g}\n", i + 1, mesh.nodes[i].x(), mesh.nodes[i].y(), mesh.nodes[i].z());
            out << "*ELEMENT, TYPE=S4, ELSET=EALL\n";
            for (int e = 0; e < blk.size(); ++e) {
                const auto c = blk.element(e);
                out << fmt::format("{}, {}, {}, {}, {}\n", e + 1, c[0] + 1, c[1] + 1, c[2] + 1, c[3] + 1);
            }
            out << "*NSET, NSET=FIXED\n";
            for (std::size_t i = 0; i < base.size(); ++i) out << base[i] + 1 << (i % 8 == 7 ? ",\n" : ", ");
            out << "\n*BOUNDARY\nFIXED, 1, 6\n";
            out << fmt::format("*MATERIAL, NAME=M\n*ELASTIC\n{:.17g}, {:.17g}\n*DENSITY\n{:.17g}\n", steel.youngs_modulus,
                               steel.poissons_ratio, steel.density);
            out << fmt::format("*SHELL SECTION, ELSET=EALL, MATERIAL=M\n{:.17g}\n", t);
            out << "*STEP\n*FREQUENCY\n" << kModes << "\n*END STEP\n";
        }
        const double t_ccx = test::run_ccx(dir, "frame");
        const auto f_ccx = test::read_ccx_frequencies(dir / "frame.dat");
        if (static_cast<int>(f_ccx.size()) < kModes) {
            std::fprintf(stderr, "ccx gave %zu frequencies, expected %d\n", f_ccx.size(), kModes);
            return 1;
        }

        Model model(mesh);
        model.add_block(0, 6, [&](std::span<const Vec3> x, int) {
            const auto s = shell::mitc4_matrices({x[0], x[1], x[2], x[3]}, t, steel);
            return ElementMatrices{s.stiffness, s.consistent_mass};
        });
        model.fix_nodes(base);
        const auto sys = model.assemble();
        const auto r = modal::solve_modes(sys, {.modes = kModes});
        std::printf("%d nodes, %d elements; ccx %.3f s, ours %.3f s\n", mesh.node_count(), blk.size(), t_ccx,
                    r.factor_seconds + r.solve_seconds);
        std::vector<double> ours(kModes);
        for (int k = 0; k < kModes; ++k) ours[k] = r.frequencies_hz(k);
        const int failed = test::compare_with_ccx(f_ccx, ours, kModes, kTol, "ccx S4 [Hz]", "MITC4 [Hz]");
        return failed ? 1 : 0;
    });
}
