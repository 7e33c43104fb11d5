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

#include "cli/programs.hpp"
#include "core/error.hpp"
#include "core/program.hpp"
#include "input/arguments.hpp"
#include "io/run_folder.hpp"
#include "io/table.hpp"
#include "io/vtu.hpp"
#include "topopt/case_file.hpp"

namespace fem::cli {

int topopt_program(int argc, char** argv) {
    return fem::run_program("fem-topopt", [&]() {
        std::string case_path, output;
        bool quiet = false;
        fem::input::Arguments args(argc, argv, {"--help", "--output", "--quiet"});
        while (args.next()) {
            if (args.is("--help") || args.is("-h")) {
                std::cout << "usage: fem-topopt CASE.toml [--output DIR] [--quiet]\n"
                             "Minimum-compliance topology optimization (SIMP, OC). Case file format: see\n"
                             "lib/topopt/case_file.hpp. Writes history.dat, density.dat and design.vtu to DIR.\n";
                return 0;
            } else if (args.is("--output")) {
                output = args.value();
            } else if (args.is("--quiet")) {
                quiet = true;
            } else {
                args.positional(case_path);
            }
        }
        if (case_path.empty()) throw fem::InputError("no case file given (usage: fem-topopt CASE.toml [--output DIR])");
        auto c = fem::topopt::read_case(case_path);
        if (!output.empty()) c.output_directory = output;
        // The output folder is checked (writable, not in use by another run) before optimizing; the
        // files replace the previous run's set only when they are all written (manifest.txt).
        fem::io::RunFolder out(c.output_directory, "fem-topopt");
        std::cout << c.summary << "\n";

        // Progress: one updating line on a terminal, a line every 10 iterations otherwise.
        const bool tty = isatty(fileno(stdout));
        if (!quiet)
            c.settings.on_iteration = [tty](int it, double comp, double vol, double change) {
                if (it == 1) std::cout << fmt::format("{}iteration    1  compliance {:.6g} J (the uniform start)\n", tty ? "\r" : "", comp);
                else if (tty) std::cout << fmt::format("\riteration {:4d}  compliance {:.6g} J  volume {:.4f}  change {:.4f}", it, comp, vol, change) << std::flush;
                else if (it % 10 == 0) std::cout << fmt::format("iteration {:4d}  compliance {:.6g} J  volume {:.4f}  change {:.4f}\n", it, comp, vol, change);
            };
        const auto r = fem::topopt::optimize(c.model, c.settings);
        if (!quiet && tty) std::cout << "\n";

        const auto output_t0 = std::chrono::steady_clock::now();
        const auto& dir = out.staging();
        std::vector<double> it(r.iterations);
        for (int k = 0; k < r.iterations; ++k) it[k] = k + 1;
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
                                 r.converged ? "converged" : "NOT CONVERGED (max_iterations reached)", r.iterations,
                                 r.compliance.back(), r.compliance.front(), r.final_volume);
        std::cout << fmt::format("time: {:.2f} s = setup {:.2f} s + {:.4f} s per iteration: assembly {:.4f}, solve {:.4f}, "
                                 "sensitivities {:.4f}, filter {:.4f}, OC update {:.4f}, other {:.4f}",
                                 r.seconds, r.seconds_setup, loop / n, T.assembly / n, T.solve / n, T.sensitivities / n,
                                 T.filter / n, T.update / n,
                                 (loop - T.assembly - T.solve - T.sensitivities - T.filter - T.update) / n);
        if (r.solver_iterations > 0) std::cout << fmt::format("; {:.1f} CG iterations per design", r.solver_iterations / n);
        std::cout << "\n";
        if (!r.converged)
            std::cerr << fmt::format("fem-topopt: warning: not converged: the max density change was {:.4g} (tolerance {:g}) "
                                     "when max_iterations = {} stopped the loop\n",
                                     r.change.back(), c.settings.change_tolerance, c.settings.max_iterations);
        out.commit();
        std::cout << fmt::format("wrote {}, density.dat, design.vtu ({:.2f} s)\n", (out.path() / "history.dat").string(),
                                 std::chrono::duration<double>(std::chrono::steady_clock::now() - output_t0).count());
        return 0;
    });
}

}  // namespace fem::cli
