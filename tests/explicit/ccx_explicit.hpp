#pragma once
// CalculiX (ccx 2.20) as the peer of the explicit solver: the same model in both codes, for the peer
// test (peer_ccx_explicit, CTest label "peer": agreement) and the peer benchmark (bench_peer_ccx,
// make bench: wall times and their ratio).
//
// The two models (issue 17 section 3):
//  * bar_impact: two identical steel bars meeting head-on at v0 each, the classic stress-wave check.
//    By symmetry the contact plane stays at rest, so each code models one bar (nu = 0: the 1D wave
//    speed c = sqrt(E / rho)) with v0 towards a face whose axial motion is fixed, until the bars
//    would separate (t = 2 L / c). Exact: the mid-length node moves at -v0 until L / 2c, rests until
//    3 L / 2c, then moves at +v0; the free end moves at -v0 until L / c, then at +v0.
//  * finger: the clamped rubber finger of Table 3-2 Case A (hexahedral mesh, Table 3-1 rubber, no
//    damping), pushed at the tip by finger_damping's impulse (a pulse one second-mode period long,
//    sized for a ~10 mm swing), 20 ms of its tip-centre deflection.
// Elements: our one-point hexahedron with Flanagan-Belytschko hourglass control against ccx's
// reduced-integration C3D8R (one point, its own hourglass control); our neo-Hookean rubber against
// ccx's linear elastic law with NLGEOM (the same at these small strains); both with their default
// bulk viscosity. Both lump the mass and choose their own stable step.
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "ccx_deck.hpp"  // run_ccx (tests/modal)
#include "explicit/solver.hpp"
#include "mesh/finger.hpp"

namespace fem::test {

/// One explicit model for both codes.
struct PeerModel {
    std::string name;
    Mesh mesh;
    ElasticMaterial material;
    std::vector<int> fixed;      // all translations fixed
    std::vector<int> fixed_x;    // x fixed only
    Vec3 initial_velocity = Vec3::Zero();  // of every node
    std::vector<int> loaded;     // nodes with `load` (per node) for t < pulse
    Vec3 load = Vec3::Zero();
    double pulse = 0.0;
    double end_time = 0.0;
    int probe = -1;              // the node whose history is compared
    double interval = 0.0;       // its sampling interval
};

struct PeerHistory {
    std::vector<double> time;
    std::vector<Vec3> displacement, velocity;
    double wall_s = 0.0;  // the solve alone (ccx: the whole process)
    long steps = 0;
};

inline PeerModel bar_impact() {
    PeerModel m;
    m.name = "bar_impact";
    const double L = 0.1;
    m.mesh = box_hex8(L, 0.01, 0.01, 40, 4, 4, "bar");
    m.material = ElasticMaterial::make("steel", 210e9, 0.0, 7800.0);
    m.fixed_x = m.mesh.node_set("x0");
    m.initial_velocity = Vec3(-1.0, 0, 0);
    const double c = std::sqrt(m.material.youngs_modulus / m.material.density);
    m.end_time = 1.9 * L / c;
    for (int i = 0; i < m.mesh.node_count(); ++i)  // the node at mid-length on the axis
        if ((m.mesh.nodes[i] - Vec3(L / 2, 0.005, 0.005)).norm() < 1e-9) m.probe = i;
    m.interval = m.end_time / 400;
    return m;
}

inline PeerModel finger_case_a() {
    using std::numbers::pi;
    PeerModel m;
    m.name = "finger_case_a";
    const auto cases = finger::table_3_2_cases();
    m.mesh = finger::mesh_case(cases.at(0));
    m.material = finger::rubber();
    m.fixed = m.mesh.node_set("root");
    m.loaded = m.mesh.node_set("tip");
    // finger_damping's impulse (impulse_run): Euler-Bernoulli modes of the soft plane, I / A = b^2 / 4.
    const double L = cases.at(0).finger_length, a = finger::semi_major_axis, b = finger::semi_minor_axis;
    const double rc = (b / 2) * std::sqrt(m.material.youngs_modulus / m.material.density);
    const double w1 = 1.8751040687 * 1.8751040687 / (L * L) * rc, w2 = 4.6940911330 * 4.6940911330 / (L * L) * rc;
    m.pulse = 2 * pi / w2;
    const double force = 0.25 * m.material.density * pi * a * b * L * w1 * 0.01 / m.pulse;
    m.load = Vec3(0, force / m.loaded.size(), 0);
    m.end_time = 0.02;
    m.probe = m.mesh.node_set("tip_center").at(0);
    m.interval = 0.02 / 400;
    return m;
}

/// Our explicit solver on the model (one thread).
inline PeerHistory run_ours(const PeerModel& m) {
    ExplicitModel model(m.mesh);
    model.add_hex8(m.mesh.blocks.front().part, m.material);
    if (!m.fixed.empty()) model.fix(m.fixed, Dofs::translations());
    if (!m.fixed_x.empty()) model.fix(m.fixed_x, Dofs::of(Dofs::x));
    if (m.initial_velocity.squaredNorm() > 0) model.set_initial_velocity([&](const Vec3&) { return m.initial_velocity; });
    if (!m.loaded.empty()) model.add_nodal_force(m.loaded, m.load, Curve::pulse(0.0, m.pulse));
    ExplicitOptions o;
    o.end_time = m.end_time;
    o.history_nodes = {{"probe", m.probe}};
    o.history_interval = m.interval;
    o.print_summary = false;
    o.progress = false;
    o.name = m.name;
    ExplicitSolver solver(model, o);
    const RunSummary s = solver.run();
    PeerHistory h;
    h.time = solver.history().time;
    h.displacement = solver.history().nodes[0].displacement;
    h.velocity = solver.history().nodes[0].velocity;
    h.wall_s = s.wall_s;
    h.steps = s.steps;
    return h;
}

/// Writes <dir>/<job>.inp: C3D8R elements (our hex8 node order is ccx's), *DYNAMIC, EXPLICIT with
/// NLGEOM, the probe node's displacement and velocity printed about every `interval`.
inline void write_ccx_explicit_deck(const std::filesystem::path& dir, const std::string& job, const PeerModel& m,
                                    double ccx_step_estimate) {
    std::filesystem::create_directories(dir);
    std::ofstream out(dir / (job + ".inp"));
    out << "*HEADING\nfem explicit peer: " << m.name << "\n*NODE, NSET=NALL\n";
    for (int i = 0; i < m.mesh.node_count(); ++i)
        out << fmt::format("{}, {:.14g}, {:.14g}, {:.14g}\n", i + 1, m.mesh.nodes[i].x(), m.mesh.nodes[i].y(),
                           m.mesh.nodes[i].z());  // ccx reads fields of at most 20 characters
    out << "*ELEMENT, TYPE=C3D8R, ELSET=EALL\n";
    int id = 1;
    for (const auto& b : m.mesh.blocks) {
        if (b.shape != ElementShape::Hex8) throw std::invalid_argument("ccx explicit deck: only hex8 blocks");
        for (int e = 0; e < b.size(); ++e) {
            out << id++;
            for (int a = 0; a < 8; ++a) out << ", " << b.element(e)[a] + 1;
            out << '\n';
        }
    }
    auto nset = [&](const char* name, const std::vector<int>& nodes) {
        out << "*NSET, NSET=" << name << "\n";
        for (std::size_t i = 0; i < nodes.size(); ++i) out << nodes[i] + 1 << (i % 8 == 7 || i + 1 == nodes.size() ? "\n" : ", ");
    };
    if (!m.fixed.empty()) nset("FIXED", m.fixed);
    if (!m.fixed_x.empty()) nset("FIXEDX", m.fixed_x);
    if (!m.loaded.empty()) nset("LOADED", m.loaded);
    nset("PROBE", {m.probe});
    out << fmt::format("*MATERIAL, NAME=M\n*ELASTIC\n{:.14g}, {:.14g}\n*DENSITY\n{:.14g}\n", m.material.youngs_modulus,
                       m.material.poissons_ratio, m.material.density);
    out << "*SOLID SECTION, ELSET=EALL, MATERIAL=M\n";
    if (m.initial_velocity.squaredNorm() > 0) {
        out << "*INITIAL CONDITIONS, TYPE=VELOCITY\n";
        for (int d = 0; d < 3; ++d)
            if (m.initial_velocity[d] != 0) out << fmt::format("NALL, {}, {:.12g}\n", d + 1, m.initial_velocity[d]);
    }
    out << "*BOUNDARY\n";
    if (!m.fixed.empty()) out << "FIXED, 1, 3\n";
    if (!m.fixed_x.empty()) out << "FIXEDX, 1, 1\n";
    if (!m.loaded.empty())  // a rectangular pulse (ccx interpolates linearly between the points)
        out << fmt::format("*AMPLITUDE, NAME=PULSE\n0, 1, {:.12g}, 1, {:.12g}, 0, {:.12g}, 0\n", m.pulse,
                           m.pulse * (1 + 1e-9), 10 * m.end_time);
    const int every = std::max(1, static_cast<int>(std::lround(m.interval / ccx_step_estimate)));
    out << "*STEP, NLGEOM, INC=100000000\n*DYNAMIC, EXPLICIT\n"
        << fmt::format("{:.6g}, {:.12g}\n", ccx_step_estimate, m.end_time);
    if (!m.loaded.empty()) {
        out << "*CLOAD, AMPLITUDE=PULSE\n";
        for (int d = 0; d < 3; ++d)
            if (m.load[d] != 0) out << fmt::format("LOADED, {}, {:.12g}\n", d + 1, m.load[d]);
    }
    out << fmt::format("*NODE PRINT, NSET=PROBE, FREQUENCY={}\nU, V\n*END STEP\n", every);
    if (!out) throw std::runtime_error("cannot write the ccx deck in " + dir.string());
}

/// The probe's history from <job>.dat: blocks "displacements (vx,vy,vz) for set PROBE and time t"
/// and "velocities (vx,vy,vz) ..." followed by "node ux uy uz".
inline PeerHistory read_ccx_history(const std::filesystem::path& dat) {
    std::ifstream in(dat);
    if (!in) throw std::runtime_error("no ccx output " + dat.string());
    const std::regex head(R"(^\s*(displacements|velocities) \(vx,vy,vz\) for set PROBE and time\s+(\S+))");
    const std::regex row(R"(^\s*\d+\s+(\S+)\s+(\S+)\s+(\S+)\s*$)");
    std::map<double, Vec3> u, v;
    std::string line, kind;
    double t = 0;
    while (std::getline(in, line)) {
        std::smatch mt;
        if (std::regex_search(line, mt, head)) {
            kind = mt[1].str();
            t = std::stod(mt[2].str());
        } else if (!kind.empty() && std::regex_match(line, mt, row)) {
            const Vec3 x(std::stod(mt[1].str()), std::stod(mt[2].str()), std::stod(mt[3].str()));
            (kind == "displacements" ? u : v)[t] = x;
            kind.clear();
        }
    }
    PeerHistory h;
    for (const auto& [time, x] : u) {
        if (!v.count(time)) continue;
        h.time.push_back(time);
        h.displacement.push_back(x);
        h.velocity.push_back(v.at(time));
    }
    if (h.time.empty()) throw std::runtime_error("no probe history in " + dat.string());
    return h;
}

/// ccx on the model in `dir` (one thread); wall_s is the whole ccx process.
inline PeerHistory run_ccx_explicit(const PeerModel& m, const std::filesystem::path& dir, double ccx_step_estimate) {
    write_ccx_explicit_deck(dir, m.name, m, ccx_step_estimate);
    const double wall = run_ccx(dir, m.name);
    PeerHistory h = read_ccx_history(dir / (m.name + ".dat"));
    h.wall_s = wall;
    std::ifstream log(dir / (m.name + ".log"));
    std::string line;
    const std::regex inc(R"(SELECTED time increment:\s*(\S+))");
    while (std::getline(log, line)) {
        std::smatch mt;
        if (std::regex_search(line, mt, inc)) h.steps = std::lround(m.end_time / std::stod(mt[1].str()));
    }
    return h;
}

/// Linear interpolation of component `d` of a history (displacement or velocity) at time t.
inline double sample(const std::vector<double>& time, const std::vector<Vec3>& x, int d, double t) {
    if (t <= time.front()) return x.front()[d];
    for (std::size_t i = 1; i < time.size(); ++i)
        if (time[i] >= t) return x[i - 1][d] + (x[i][d] - x[i - 1][d]) * (t - time[i - 1]) / (time[i] - time[i - 1]);
    return x.back()[d];
}

}  // namespace fem::test
