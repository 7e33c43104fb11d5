// The explicit run behind tests/outputs/check_outputs.py, which reads its files with independent
// readers (meshio for the VTU series, h5py for the HDF5 histories, xml.etree for the PVD) and checks
// them against the values this program prints from the solver's memory.
//   explicit_outputs DIR [--interrupt-at T]
// A rubber block (hex8) pressed by gravity onto a rigid plate (quad4), contact between them; VTU
// series every 2 ms, histories every 1 ms, progress on stderr. Prints "expected <key> <values>"
// lines: the final time, the final displacement and velocity of two nodes, the contact force on
// the plate, the block's largest von Mises stress, the history samples' count and last kinetic
// energy. --interrupt-at T: the observer sends this process SIGINT at t >= T, as Ctrl-C would (the
// run must stop cleanly, write partial outputs and exit with status 130).
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <string>

#include "contact/contact.hpp"
#include "contact/explicit_contact.hpp"
#include "core/error.hpp"
#include "core/program.hpp"
#include "explicit/solver.hpp"
#include "input/numbers.hpp"

using namespace fem;
using namespace fem::contact;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
    return run_program("explicit_outputs", [&]() {
        if (argc != 2 && argc != 4) throw InputError("usage: explicit_outputs DIR [--interrupt-at T]");
        const fs::path dir = argv[1];
        const double interrupt_at = argc == 4 ? input::parse_real(argv[3], {"command line", 0, "--interrupt-at"}) : -1.0;
        const auto rubber = ElasticMaterial::make("rubber", 2e6, 0.3, 1000);
        Mesh mesh = box_hex8(0.03, 0.03, 0.015, 3, 3, 2, "block");
        mesh.append(parallelogram_quad4(Vec3(0.015, 0.015, 0), Vec3(0.06, 0, 0), Vec3(0, 0.06, 0), 6, 6, "plate"));
        ExplicitModel model(mesh);
        model.add_hex8("block", rubber);
        model.set_mass_damping("block", 200.0);
        model.set_gravity(Vec3(0, 0, -49.05), Curve({{0, 0}, {0.005, 1}}, "press"));
        model.add_rigid_part("plate", RigidMotion::fixed());
        ContactInterface& contact = add_contact(
            model, ContactInterface("block on plate", ContactSurface::from_part(mesh, "block", rubber),
                                    ContactSurface::rigid_part(mesh, "plate", 5e-3)));
        fs::create_directories(dir);
        ExplicitOptions o;
        o.name = "block on plate";
        o.end_time = 0.02;
        o.history_nodes = {{"corner", 0}, {"top", 40}};
        o.history_interval = 1e-3;
        o.h5_path = dir / "run.h5";
        o.pvd_path = dir / "run.pvd";
        o.vtu_interval = 2e-3;
        o.print_summary = false;
        o.progress = true;  // stderr is a pipe in the test: one line per 10 %
        o.observer_interval = 0;
        ExplicitSolver solver(model, o);
        if (interrupt_at >= 0)
            solver.observer = [&](const ExplicitSolver& s) {
                if (s.time() >= interrupt_at) std::raise(SIGINT);
            };
        const RunSummary summary = solver.run();
        const auto& s = solver.state();
        std::printf("expected end_time %.17g\n", solver.time());
        std::printf("expected max_dt %.17g\n", summary.max_dt);
        for (int node : {0, 40}) {
            const Vec3 u = s.x[node] - s.X[node];
            std::printf("expected node %d %.17g %.17g %.17g %.17g %.17g %.17g\n", node, u.x(), u.y(), u.z(), s.v[node].x(),
                        s.v[node].y(), s.v[node].z());
        }
        std::printf("expected contact_force_z %.17g\n", contact.force_on_master().z());
        std::printf("expected block_max_von_mises %.17g\n", solver.max_von_mises("block"));
        std::printf("expected history_samples %zu\n", solver.history().time.size());
        std::printf("expected last_kinetic %.17g\n", solver.history().kinetic.back());
        return 0;
    });
}
