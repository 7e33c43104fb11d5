#pragma once
// Shared by the explicit-solver and contact tests and the explicit bench: quiet run options, the
// rigid-spin check of objectivity (a body spinning freely must store no strain energy and follow the
// rigid rotation), and the Table 2-8 wire.
#include <Eigen/Geometry>
#include <algorithm>
#include <numbers>
#include <vector>

#include "core/error.hpp"
#include "explicit/solver.hpp"
#include "../test_materials.hpp"

namespace fem::test {

/// pi, for the closed-form frequencies and periods the tests compare with.
inline constexpr double kPi = std::numbers::pi;

/// The rotation by `angle` (rad) about `axis` (any length).
inline Mat3 rotation(double angle, const Vec3& axis) {
    return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

/// Times of the upward zero crossings of a sampled signal (linear interpolation between samples).
inline std::vector<double> upward_crossings(const std::vector<double>& t, const std::vector<double>& y) {
    std::vector<double> c;
    for (std::size_t i = 1; i < y.size(); ++i)
        if (y[i - 1] < 0 && y[i] >= 0) c.push_back(t[i - 1] + (t[i] - t[i - 1]) * (-y[i - 1]) / (y[i] - y[i - 1]));
    return c;
}

/// The message of the InputError that f() throws ("no error" when it throws none), for tests that
/// check that bad input is refused naming the culprit.
template <class F>
std::string input_error(F&& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

/// Options for a test run: no summary print, no progress line.
inline ExplicitOptions quiet(double end_time) {
    ExplicitOptions o;
    o.end_time = end_time;
    o.print_summary = false;
    o.progress = false;
    return o;
}

struct RigidSpin {
    double max_internal_over_kinetic = 0.0;  // over every cycle
    double position_error = 0.0;             // max |x - R(omega t) X| at the end [m]
    RunSummary summary;
};

/// Runs `model` (initial velocities omega x X already set) to t_end and measures how far it is from
/// a rigid rotation about the origin at omega.
inline RigidSpin run_rigid_spin(ExplicitModel& model, const Mesh& mesh, const Vec3& omega, double t_end) {
    ExplicitSolver solver(model, quiet(t_end));
    RigidSpin r;
    solver.observer = [&](const ExplicitSolver& s) {
        const auto& h = s.history();
        r.max_internal_over_kinetic = std::max(r.max_internal_over_kinetic, h.internal.back() / h.kinetic.back());
    };
    r.summary = solver.run();
    const Mat3 R = Eigen::AngleAxisd(omega.norm() * solver.time(), omega.normalized()).toRotationMatrix();
    for (int i = 0; i < mesh.node_count(); ++i)
        r.position_error = std::max(r.position_error, (solver.state().x[i] - R * mesh.nodes[i]).norm());
    return r;
}

/// A nodal state of `mesh` at rest in its reference configuration: no mass yet, no rotational DOFs.
inline NodalState state_at_rest(const Mesh& mesh) {
    NodalState s;
    s.X = mesh.nodes;
    s.x = mesh.nodes;
    s.v.assign(mesh.node_count(), Vec3::Zero());
    s.f.assign(mesh.node_count(), Vec3::Zero());
    s.mass.assign(mesh.node_count(), 0.0);
    s.rot_index.assign(mesh.node_count(), -1);
    return s;
}

/// The compliant wire of thesis Table 2-8 (the usage example of explicit/solver.hpp): a 0.4 m steel
/// wire of 0.6 mm radius as `mesh`'s beams (line_beam2 with node sets "start", "end"), a 0.015 g tip
/// mass, clamped at the start, a 0.003 N tip pulse for 0.2 s. Returns the tip node.
inline int add_table_2_8_wire(ExplicitModel& model, const Mesh& mesh) {
    model.add_beams("beam", kWireSteel, {beam::Section::circular(0.6e-3)});
    const int tip = mesh.node_set("end")[0];
    model.add_point_mass("tip mass", tip, 0.015e-3);
    model.fix(mesh.node_set("start"), Dofs::all());
    model.add_nodal_force({tip}, Vec3(0, -0.003, 0), Curve::pulse(0.0, 0.2));
    return tip;
}

}  // namespace fem::test
