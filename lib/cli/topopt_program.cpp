// fem-topopt: minimum-compliance topology optimization (SIMP + optimality criteria, thesis Sec 2.6)
// of a plane-stress domain described by a TOML case file (format: lib/topopt/case_file.hpp).
//
//   fem-topopt case.toml [--output DIR] [--quiet]
//
// Writes DIR/history.dat (iteration, compliance, volume fraction, max change), DIR/density.dat
// (element centroid x, y and pseudo-density) and DIR/design.vtu (cell field "density", for ParaView).
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
        std::cout << c.summary << "\nsparse Cholesky: " << fem::topopt::cholesky_backend() << "\n";

        // Progress: one updating line on a terminal, a line every 10 iterations otherwise.
        const bool tty = isatty(fileno(stdout));
        if (!quiet)
            c.settings.on_iteration = [tty](int it, double comp, double vol, double change) {
                if (tty) std::cout << fmt::format("\riteration {:4d}  compliance {:.6g} J  volume {:.4f}  change {:.4f}", it, comp, vol, change) << std::flush;
                else if (it % 10 == 0) std::cout << fmt::format("iteration {:4d}  compliance {:.6g} J  volume {:.4f}  change {:.4f}\n", it, comp, vol, change);
            };
        const auto r = fem::topopt::optimize(c.model, c.settings);
        if (!quiet && tty) std::cout << "\n";

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

        std::cout << fmt::format("{} after {} iterations: compliance {:.6g} J, volume fraction {:.6f}; {:.2f} s "
                                 "({:.4f} s per iteration, {:.0f} % in assembly and factorization)\n",
                                 r.converged ? "converged" : "NOT converged (max_iterations reached)", r.iterations,
                                 r.compliance.back(), r.final_volume, r.seconds, r.seconds_per_iteration(),
                                 100 * r.seconds_factorizing / std::max(r.seconds - r.seconds_setup, 1e-12));
        out.commit();
        std::cout << "wrote " << (out.path() / "history.dat").string() << ", density.dat, design.vtu\n";
        return 0;
    });
}

}  // namespace fem::cli
