// Peer test (CTest label "peer"): our explicit solver against CalculiX's *DYNAMIC, EXPLICIT on the
// same models (ccx_explicit.hpp): the bar impact against the exact stress-wave solution and against
// ccx, and the Case A rubber finger's tip history against ccx. Prints both wall times and their ratio
// (make bench times them again: bench_peer_ccx).
//   peer_ccx_explicit <work dir>
//
// Tolerances (set before running, from what the models justify):
//  * bar: the mid-length velocity averaged over the middle of each plateau of the exact solution
//    (-v0, 0, +v0) within 0.05 v0 in both codes (one-point hexahedra on 40 cells along the bar: the
//    front is a few cells wide and rings behind; bulk viscosity damps the ringing differently in each
//    code); its displacement at 0.9 and 1.8 L/c within 3 % of v0 L / c of the exact value. (The first
//    version compared single samples at 0.25, 1.0 and 1.75 L/c: ccx's velocity at 1.75 L/c, 1.059 v0,
//    is a crest of its ringing, which ours damps more; a sample measures the ringing's phase, the mean
//    over the plateau the wave solution.)
//  * finger: ccx's C3D8R and our hexahedron are both one-point elements on the same 725-element mesh
//    but with different hourglass controls and bulk viscosities, and our law is neo-Hookean (ccx:
//    linear with NLGEOM); at ~1 % strain these differ by well under the mesh error. Peak tip deflection
//    within 3 %, the RMS difference of the 20 ms histories within 5 % of the peak. (The first version
//    also compared the time of the peak: in 20 ms the tip is still rising in both codes, ~20 ms being
//    the first peak, so both peaks fell on the last sample and that check compared nothing; the
//    deflection at 10 ms, within 3 %, replaces it.)
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "ccx_explicit.hpp"
#include "core/program.hpp"

namespace {
int failures = 0;
void expect_within(const char* what, double ours, double expected, double tol) {
    const bool ok = std::abs(ours - expected) <= tol;
    failures += !ok;
    std::printf("  %-58s %12.5g  expected %12.5g +- %.3g %s\n", what, ours, expected, tol, ok ? "" : "FAIL");
}
}  // namespace

int main(int argc, char** argv) {
    return fem::run_program("peer_ccx_explicit", [&]() {
        using namespace fem;
        using namespace fem::test;
        const std::filesystem::path dir = argc > 1 ? argv[1] : "peer_ccx_explicit";

        // --- bar impact --------------------------------------------------------------------------
        const PeerModel bar = bar_impact();
        const PeerHistory bo = run_ours(bar);
        const PeerHistory bc = run_ccx_explicit(bar, dir, 0.4 * bar.end_time / bo.steps);
        const double L = 0.1, c = std::sqrt(bar.material.youngs_modulus / bar.material.density), T = L / c;
        std::printf("bar impact: %d nodes, ours %ld steps %.3f s, ccx ~%ld steps %.3f s (ccx / ours %.1f)\n",
                    bar.mesh.node_count(), bo.steps, bo.wall_s, bc.steps, bc.wall_s, bc.wall_s / bo.wall_s);
        struct Plateau {
            double from, to, v;  // [L/c], exact velocity
        };
        for (const auto& [name, h] : {std::pair{"ours", &bo}, std::pair{"ccx", &bc}}) {
            for (const Plateau& p : {Plateau{0.1, 0.4, -1.0}, Plateau{0.75, 1.25, 0.0}, Plateau{1.65, 1.9, 1.0}}) {
                double mean = 0;
                const int n = 50;
                for (int k = 0; k < n; ++k) mean += sample(h->time, h->velocity, 0, (p.from + (p.to - p.from) * (k + 0.5) / n) * T) / n;
                expect_within(fmt::format("{} mid-length velocity over {:.2f}-{:.2f} L/c [m/s]", name, p.from, p.to).c_str(),
                              mean, p.v, 0.05);
            }
        }
        // Mid-length displacement: -v0 t until L/2c, constant until 3L/2c, then back at +v0.
        for (const auto& [name, h] : {std::pair{"ours", &bo}, std::pair{"ccx", &bc}})
            for (const auto& [t, u] : {std::pair{0.9 * T, -0.5 * T}, std::pair{1.8 * T, -0.5 * T + 0.3 * T}})
                expect_within(fmt::format("{} mid-length displacement at {:.1f} L/c [L/c v0]", name, t / T).c_str(),
                              sample(h->time, h->displacement, 0, t) / T, u / T, 0.03);

        // --- Case A finger ----------------------------------------------------------------------
        const PeerModel finger = finger_case_a();
        const PeerHistory fo = run_ours(finger);
        const PeerHistory fc = run_ccx_explicit(finger, dir, 0.4 * finger.end_time / fo.steps);
        std::printf("Case A finger: %d nodes, ours %ld steps %.3f s, ccx ~%ld steps %.3f s (ccx / ours %.1f)\n",
                    finger.mesh.node_count(), fo.steps, fo.wall_s, fc.steps, fc.wall_s, fc.wall_s / fo.wall_s);
        double peak_o = 0, t_o = 0, peak_c = 0, t_c = 0, rms = 0;
        const int n = 400;
        for (int k = 1; k <= n; ++k) {
            const double t = finger.end_time * k / n;
            const double yo = sample(fo.time, fo.displacement, 1, t), yc = sample(fc.time, fc.displacement, 1, t);
            if (std::abs(yo) > peak_o) peak_o = std::abs(yo), t_o = t;
            if (std::abs(yc) > peak_c) peak_c = std::abs(yc), t_c = t;
            rms += (yo - yc) * (yo - yc) / n;
        }
        rms = std::sqrt(rms);
        expect_within("finger peak tip deflection, ours / ccx", peak_o / peak_c, 1.0, 0.03);
        expect_within("finger tip deflection at 10 ms, ours / ccx",
                      sample(fo.time, fo.displacement, 1, 0.01) / sample(fc.time, fc.displacement, 1, 0.01), 1.0, 0.03);
        expect_within("finger RMS difference of the histories / peak", rms / peak_c, 0.0, 0.05);
        std::printf("finger: peak ours %.4f mm at %.2f ms, ccx %.4f mm at %.2f ms\n", 1e3 * peak_o, 1e3 * t_o,
                    1e3 * peak_c, 1e3 * t_c);
        std::printf("%s\n", failures ? "peer comparison FAILED" : "peer comparison passed");
        return failures ? 1 : 0;
    });
}
