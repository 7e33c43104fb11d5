// fem-topopt: minimum-compliance topology optimization (SIMP + optimality criteria, thesis Sec 2.6)
// of a plane-stress domain described by a TOML case file (format: lib/topopt/case_file.hpp).
//
//   fem-topopt case.toml [--output DIR] [--quiet]
//
// Writes DIR/history.dat (iteration, compliance, volume fraction, max change), DIR/density.dat
// (element centroid x, y and pseudo-density) and DIR/design.vtu (cell field "density", for ParaView).
#include <chrono>
#include <cstdio>
#include <iostream>
#include <string>
#include <unistd.h>

#include <fmt/format.h>

#include "cli/case_command_line.hpp"
#include "cli/programs.hpp"
#include "core/error.hpp"
#include "core/program.hpp"
#include "core/progress.hpp"
#include "io/atomic_file.hpp"
#include "io/run_folder.hpp"
#include "io/table.hpp"
#include "io/vtu.hpp"
#include "topopt/case_file.hpp"

namespace fem::cli {

int topopt_program(int argc, char** argv) {
    return fem::run_program("fem-topopt", [&]() {
        const auto line = read_case_command_line(
            argc, argv, "fem-topopt CASE.toml [--output DIR] [--quiet]",
            "Minimum-compliance topology optimization (SIMP, OC). Case file format: see\n"
            "lib/topopt/case_file.hpp. Writes history.dat, density.dat and design.vtu to DIR.\n");
        if (!line) return 0;  // --help
        const bool quiet = line->quiet;
        auto c = fem::topopt::read_case(line->case_path);
        if (!line->output.empty()) c.output_directory = line->output;
        // The output folder is checked (writable, not in use by another run) before optimizing; the
        // files replace the previous run's set only when they are all written (manifest.txt).
        fem::io::RunFolder out(c.output_directory, "fem-topopt");
        std::cout << c.summary << "\n";

        // Progress on stderr (core/progress.hpp): an updating line on a terminal, a line per 10 % of
        // max_iterations otherwise (the run usually converges before). Ctrl-C stops after the current
        // iteration; the design reached is written, marked partial, and the exit status is 130.
        fem::Progress progress("fem-topopt", c.settings.max_iterations,
                               quiet ? fem::Progress::Mode::Quiet : fem::Progress::Mode::Auto);
        c.settings.on_iteration = [&progress](int it, double comp, double vol, double change) {
            if (progress.due(it))
                progress.show(it, fmt::format("iteration {}, compliance {:.6g} J, volume {:.4f}, change {:.4f}", it, comp,
                                              vol, change));
        };
        const fem::InterruptGuard interrupt_guard;
        const auto r = fem::topopt::optimize(c.model, c.settings);
        progress.finish();

        const auto output_t0 = std::chrono::steady_clock::now();
        const auto& dir = out.staging();
        std::vector<double> it(r.iterations);
        for (int k = 0; k < r.iterations; ++k) it[k] = k + 1;
        const std::string partial =
            r.interrupted ? fmt::format("partial: interrupted (Ctrl-C) after iteration {} of at most {}", r.iterations,
                                        c.settings.max_iterations)
                          : "";
        if (r.interrupted) fem::io::write_text_file(dir / "PARTIAL.txt", partial + "\n");
        fem::io::Table h;
        h.add("iteration", it).add("compliance_J", r.compliance).add("volume_fraction", r.volume).add("max_change", r.change);
        fem::io::write_dat(dir / "history.dat", h);
        std::vector<double> x, y;
        for (const auto& p : c.model.centroid) x.push_back(p.x()), y.push_back(p.y());
        fem::io::Table d;
        d.add("x", x).add("y", y).add("density", r.density);
        fem::io::write_dat(dir / "density.dat", d);
        fem::io::VtuData vtu;
        vtu.cell_fields.push_back({"density", 1, r.density});
        fem::io::write_vtu(dir / "design.vtu", c.mesh, vtu);

        // Run summary: result, then where the time went (per iteration, the one-off setup apart).
        const auto& T = r.timing;
        const double n = std::max(r.iterations, 1), loop = std::max(r.seconds - r.seconds_setup, 1e-12);
        std::cout << fmt::format("stiffness solver: {}\n", r.solver);
        std::cout << fmt::format("{} after {} iterations: compliance {:.6g} J (first {:.6g} J), volume fraction {:.6f}\n",
                                 r.converged     ? "converged"
                                 : r.interrupted ? "INTERRUPTED (Ctrl-C)"
                                                 : "NOT CONVERGED (max_iterations reached)",
                                 r.iterations,
                                 r.compliance.back(), r.compliance.front(), r.final_volume);
        std::cout << fmt::format("time: {:.2f} s = setup {:.2f} s + {:.4f} s per iteration: assembly {:.4f}, solve {:.4f}, "
                                 "sensitivities {:.4f}, filter {:.4f}, OC update {:.4f}, other {:.4f}",
                                 r.seconds, r.seconds_setup, loop / n, T.assembly / n, T.solve / n, T.sensitivities / n,
                                 T.filter / n, T.update / n,
                                 (loop - T.assembly - T.solve - T.sensitivities - T.filter - T.update) / n);
        if (r.solver_iterations > 0) std::cout << fmt::format("; {:.1f} CG iterations per design", r.solver_iterations / n);
        std::cout << "\n";
        if (!r.converged && !r.interrupted)
            std::cerr << fmt::format("fem-topopt: warning: not converged: the max density change was {:.4g} (tolerance {:g}) "
                                     "when max_iterations = {} stopped the loop\n",
                                     r.change.back(), c.settings.change_tolerance, c.settings.max_iterations);
        out.commit();
        std::cout << fmt::format("wrote {}, density.dat, design.vtu{} ({:.2f} s)\n", (out.path() / "history.dat").string(),
                                 r.interrupted ? ", PARTIAL.txt" : "",
                                 std::chrono::duration<double>(std::chrono::steady_clock::now() - output_t0).count());
        if (r.interrupted) {
            throw fem::Interrupted(fmt::format("stopped after iteration {} of at most {}; the design reached (marked partial "
                                               "in PARTIAL.txt) is in {}",
                                               r.iterations, c.settings.max_iterations, out.path().string()));
        }
        return 0;
    });
}

}  // namespace fem::cli
