// Study rotating_finger_contact: a rubber finger on a turning drum sweeps into a fixed elliptical
// aluminium object (thesis Sec 3.5, Tables 3-4..3-7, Figs 3-18..3-36; experiment of Lee et al. 2001,
// whose measured curves the thesis text does not print).
//
// Model (Tables 3-4..3-6; reconstruction choices in README.md):
//   - finger: 8-inch elliptic cylinder (12 x 8.45 mm semi-axes, 203.2 mm), rubber E 6.1 MPa,
//     nu 0.49, rho 1000, coarse hex8 O-grid (target element length 6 mm), mass damping alpha;
//     its root face is tied to the drum (radius 82.55 mm) turning at 2.095 rad/s about z;
//     finger axis radial, minor axis tangential (bending about the major axis, in the plane of
//     rotation);
//   - object: elliptic cylinder 99.1 x 67.3 mm, 25 mm thick, centre (101.6, 184.15) mm; deformable
//     hex8 O-grid (AL6061 69 GPa, or 6.1 MPa), fixed on a 20 mm radius disc of its back face (the
//     F/T sensor of Table 3-4), reaction = support reaction there. A rigid object (e_object = 0) is
//     still supported by run_case but chattered badly (README);
//   - contact: finger surface nodes on the object's faces, penalty (SLSFAC 0.1), Coulomb mu 0.6.
//   - the drum starts at angle 0 (finger along +x) from rest-undeformed, i.e. ~0.3 s before the
//     first contact; a run ends 50 ms after the finger has left the object (at most at the thesis's
//     3 s, Table 3-6);
//   - reaction force: the sensor reaction filtered with SAE J211 CFC 60 (README: why);
//   - object stress also as a patch mean around the contact point, which converges with the object
//     mesh (issue 13 item 3).
//
// Side runs (README, "Side runs"; each writes under build/results/rotating_finger_contact/<run>/, never
// over the study run's judged files):
//   --case <name> [end time]     one case of Table 3-7 alone, no checks; with --finger-h, --mapped,
//                                --object-h, --perturb, --two-way for the mesh and robustness studies
//   --static-convergence [k]     the static mesh convergence of the finger's root stress and the
//                                object's stress (--finger-only: the finger's alone)
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "assembly/model.hpp"
#include "assembly/static_solve.hpp"
#include "check/cases.hpp"
#include "check/side_run.hpp"
#include "check/study.hpp"
#include "contact/contact.hpp"
#include "contact/explicit_contact.hpp"
#include "core/error.hpp"
#include "core/program.hpp"
#include "core/units.hpp"
#include "damping/signal.hpp"
#include "element/hex8_explicit.hpp"
#include "explicit/solver.hpp"
#include "input/arguments.hpp"
#include "input/numbers.hpp"
#include "io/atomic_file.hpp"
#include "io/run_folder.hpp"
#include "io/table.hpp"
#include "mesh/finger.hpp"

using namespace fem;
using namespace fem::contact;
using std::numbers::pi;

namespace {

constexpr double kDrumRadius = 82.55e-3;         // Table 3-4
constexpr double kOmega = 2.095;                 // Table 3-6 [rad/s]
constexpr double kFingerLength = 203.2e-3;       // 8 inch
const Vec3 kObjectCentre(101.6e-3, 184.15e-3, 0.0);  // Sec 3.5
constexpr double kObjA = 99.1e-3, kObjB = 67.3e-3, kObjT = 25e-3;  // Table 3-4
constexpr double kSensorRadius = 20e-3;          // Table 3-4
// The object stress that converges with the object mesh (issue 13 item 3, README): the volume mean of
// the element von Mises stress over the elements whose centroids lie within this distance of the
// contact point (half the object's thickness; about the size of the thesis's object elements).
constexpr double kPatchRadius = 12.5e-3;

// Volume mean of `von_mises` over the elements whose centroid lies within kPatchRadius of `p` (0 when
// there is none).
double patch_mean(const std::vector<double>& von_mises, const std::vector<double>& volume,
                  const std::vector<Vec3>& centroid, const Vec3& p) {
    double sv = 0, v = 0;
    for (std::size_t e = 0; e < von_mises.size(); ++e)
        if ((centroid[e] - p).norm() < kPatchRadius) sv += von_mises[e] * volume[e], v += volume[e];
    return v > 0 ? sv / v : 0.0;
}

struct Case {
    std::string name;
    double alpha = 7.5;       // 1/s
    double e_finger = 6.1e6;  // Pa
    double e_object = 0;      // 0: rigid
    double end_time = 3.0;    // at most (Table 3-6); the run stops once contact is over
    bool snapshots = false;   // finger outlines (Figs 3-20, 3-26..3-29)
    bool vtu = false;         // deformed states for ParaView
    bool full_rotation = false;  // --full: go on to end_time (the free vibration after release)
    double object_alpha = 0;     // 1/s, mass damping on the object (Table 3-6 damps the finger only)
};

/// The model's meshes and contact: the study run's, or a --case side run's variant of them (its
/// options; the convergence and robustness studies of the README).
struct Variant {
    double finger_h = 6e-3;   // --finger-h: the finger's target element length [m]
    int mapped = 0;           // --mapped n: the finger's section as one mapped n x n block (the thesis's
                              // Case A layout for n = 5: Table 3-5's 1275 elements are 5 x 5 x 51),
                              // round(L / h) layers, instead of the O-grid
    double object_h = 12e-3;  // --object-h: the aluminium object's element length [m]
    double perturb = 0;       // --perturb eps: the drum speed x (1 + eps), a round-off-sized change
                              // that shows which outputs are robust (README: the raw stress maxima are not)
    bool two_way = false;     // --two-way: symmetric contact (the object's nodes on the finger's faces too)
};

/// Table 3-7's cases, the general case first, each run to at most `end` [s].
std::vector<Case> table_3_7_cases(double end) {
    // Every case with the deformable object on its sensor (Table 3-5: the object is a solid); the
    // rigid object (e_object 0) chattered (README).
    return {
        {"alpha-7.5", 7.5, 6.1e6, 69e9, end, true, true},
        {"alpha-1", 1, 6.1e6, 69e9, end, true},
        {"alpha-20", 20, 6.1e6, 69e9, end},
        {"alpha-50", 50, 6.1e6, 69e9, end},
        {"alpha-180", 180, 6.1e6, 69e9, end, true},
        {"alpha-600", 600, 6.1e6, 69e9, end, true},
        {"E-finger-4.2", 7.5, 4.2e6, 69e9, end},
        {"E-object-6.1MPa", 7.5, 6.1e6, 6.1e6, end},
        // Not a thesis case: the soft object with its own motion damped (50 1/s), to test whether
        // its sway on the sensor disc is what lifts the sensor force above the contact force.
        {"E-object-6.1MPa-damped", 7.5, 6.1e6, 6.1e6, end, false, false, false, 50},
    };
}

struct Result {
    Case c;
    // Rows every 2 ms: CFC 60 reaction |F|, Fx, Fy and CFC 60 stress maxima at the row time; the raw
    // reaction's 2 ms mean and the raw stress maxima over the 2 ms; the contact force (2 ms mean of
    // |sum of contact forces|); the contact point.
    std::vector<double> t, f, fx, fy, f_mean2ms, f_contact, s_finger, s_object, s_finger_raw, s_object_raw, cx, cy;
    std::vector<double> s_patch;  // the object's patch-mean stress (CFC 60) at the row time
    double f_max = 0, f_mean2ms_max = 0, s_finger_max = 0, s_object_max = 0, t_first = -1, t_last = -1;
    double s_finger_raw_max = 0, s_object_raw_max = 0, f_contact_max = 0;
    double s_patch_max = 0, s_patch_raw_max = 0;  // the object's patch-mean stress (kPatchRadius): CFC 60, raw
    double wall = 0;
    long steps = 0;
    // finger outline snapshots (leading and trailing edge polylines) every 0.05 s (c.snapshots)
    std::vector<double> snap_t;
    std::vector<std::vector<Vec3>> snap_lead, snap_trail;
    RunSummary summary;
};

// Every reported history goes through the same SAE J211 CFC 60 filter (README: why), on 0.1 ms bins
// (10 kHz, above J211's 10 x CFC sampling rule): the reaction as bin means, the stress maxima as bin
// maxima. Returns the filtered record.
damping::SampledSignal cfc60(std::vector<double> bins, double bin) {
    return damping::cfc_filter(damping::SampledSignal{0.5 * bin, bin, std::move(bins)}, 60.0);
}


// --- Static mesh convergence (issue 13 items 2 and 3; the --static-convergence side run, README) ---
//
// The dynamic runs report element-centre stresses of one-point hexahedra, as LS-DYNA does: the
// value of the element's mean strain, i.e. at its centre. How that value depends on the mesh is a
// question of statics (the drum turns slowly: the finger's peak is quasi-static), so it is measured
// here on linear static solutions of the SAME element: the one-point hexahedron with its
// Flanagan-Belytschko hourglass stiffness (QM 0.1), linearized about the undeformed state.

// Stiffness of the explicit one-point hexahedron (element/hex8_explicit) at the undeformed state,
// by central differences of its internal forces (neo-Hookean -> the linear material at small
// strain; the differences are exact to ~1e-9 relative for a step of 1e-7 of the element size).
ElementMatrices one_point_hex8_stiffness(std::span<const Vec3> x, const hex8::Hex8Material& mat) {
    std::array<Vec3, 8> X;
    std::copy(x.begin(), x.end(), X.begin());
    const hex8::Hex8Reference ref = hex8::make_reference(X, "static convergence hex8");
    const double eps = 1e-7 * std::cbrt(ref.volume);
    std::array<Vec3, 8> u, v;  // (Eigen vectors are not zeroed by {})
    v.fill(Vec3::Zero());
    hex8::Hex8Result plus, minus;
    Eigen::MatrixXd K(24, 24);
    for (int j = 0; j < 24; ++j) {
        u.fill(Vec3::Zero());
        u[j / 3][j % 3] = eps;
        hex8::internal_force(ref, mat, u, v, -1, plus);
        u[j / 3][j % 3] = -eps;
        hex8::internal_force(ref, mat, u, v, -1, minus);
        for (int a = 0; a < 8; ++a)
            for (int i = 0; i < 3; ++i) K(3 * a + i, j) = (plus.force[a][i] - minus.force[a][i]) / (2 * eps);
    }
    return {0.5 * (K + K.transpose()), Eigen::MatrixXd::Zero(24, 24)};
}

// Linear static solution of `mesh` (every block one-point hexahedra of material m) under nodal
// forces `f`, nodes `fixed` clamped; returns each element's centre von Mises stress and centroid.
struct ElementField {
    std::vector<double> von_mises, volume;
    std::vector<Vec3> centroid;
};
ElementField solve_one_point_static(const Mesh& mesh, const ElasticMaterial& m, const std::vector<int>& fixed,
                                    const std::vector<Vec3>& f) {
    const hex8::Hex8Material mat = hex8::Hex8Material::from(m);
    Model model(mesh);
    for (int b = 0; b < static_cast<int>(mesh.blocks.size()); ++b)
        model.add_block(b, 3, [&](std::span<const Vec3> x, int) { return one_point_hex8_stiffness(x, mat); });
    model.fix_nodes(fixed);
    const std::vector<Vec3> u = solve_linear_static(model.assemble(), f);
    ElementField out;
    for (int b = 0; b < static_cast<int>(mesh.blocks.size()); ++b)
        for (int e = 0; e < mesh.blocks[b].size(); ++e) {
            std::array<Vec3, 8> X, ue, ve;
            ve.fill(Vec3::Zero());
            const auto nodes = mesh.blocks[b].element(e);
            Vec3 c = Vec3::Zero();
            for (int a = 0; a < 8; ++a) X[a] = mesh.nodes[nodes[a]], ue[a] = u[nodes[a]], c += X[a] / 8;
            const hex8::Hex8Reference ref = hex8::make_reference(X, "static convergence hex8");
            hex8::Hex8Result r;
            hex8::internal_force(ref, mat, ue, ve, -1, r);
            out.von_mises.push_back(r.von_mises), out.volume.push_back(ref.volume), out.centroid.push_back(c);
        }
    return out;
}

// Item 2: the finger's root stress. At the peak of the general case (thesis mesh, t = 0.71-0.80 s)
// the root carries a bending moment of 1.23-1.37 N m about the section's major axis, with a
// transverse force of only 3-8 N (lever M / V = 170-480 mm) and an axial force whose stress is 2 %
// of the bending stress: the root is in nearly pure bending. So: a stub of the finger's section,
// 8 x 3.984 mm long (whole layers for every mapped mesh), clamped at its root, loaded at its tip face
// by a pure couple M about the major axis (axial nodal forces linear in y: no net force).
// Meshes: the study's O-grid (6 mm) and its half (3 mm); the thesis's mapped 5 x 5 (Table 3-5;
// layer 3.984 mm) and its halves h/2, h/4 (10 x 10, 20 x 20 sections, layers halved).
// Reported per mesh: the largest element-centre stress (the root's: what Table 3-7's "max stress in
// the finger" is on that mesh) over Euler-Bernoulli's surface stress M b / I, and the largest
// centre stress of the layer nearest mid-stub over beam theory at that element's centroid, M y_c / I
// (how well the element represents the bending field away from the clamp).
// `finest`: the mapped meshes down to h / 2^(finest - 1) (1..3).
void finger_root_convergence(const std::filesystem::path& out, int finest) {
    // M small enough that the linear solution's rotations (kappa z ~ 1e-5 rad) add no spurious
    // stretch when the element's (large-deformation) kernel evaluates its stress; stresses per N m.
    const double layer = 3.984e-3, length = 8 * layer, M = 1e-6;
    const fem::finger::EllipticCylinder stub{12e-3, 8.45e-3, length};
    const auto rubber = ElasticMaterial::make("rubber", 6.1e6, 0.49, 1000);
    const double I = pi * stub.a * std::pow(stub.b, 3) / 4, beam_surface = M * stub.b / I;
    struct Level {
        std::string name;
        Mesh mesh;
    };
    std::vector<Level> levels;
    levels.push_back({"O-grid 6 mm (study)", fem::finger::hex_finger(stub, 6e-3)});
    levels.push_back({"O-grid 3 mm", fem::finger::hex_finger(stub, 3e-3)});
    for (int k = 1; k <= finest; ++k)
        levels.push_back({fmt::format("mapped {0} x {0}, layer {1:.3f} mm", 5 << (k - 1), 1e3 * layer / (1 << (k - 1))),
                          fem::finger::hex_finger(stub, fem::finger::mapped_cross_section(5 << (k - 1)), 8 << (k - 1))});
    io::Table t;
    std::vector<double> elements, peak, peak_ratio, mid_ratio, z_peak, y_peak;
    fmt::print("finger stub {:.1f} mm, tip couple about the major axis: beam theory M b / I = {:.4g} Pa per N m\n",
               1e3 * length, beam_surface / M);
    for (auto& level : levels) {
        const std::string& name = level.name;
        const Mesh& mesh = level.mesh;  // (a named reference, not a structured binding: lambdas below capture it)
        // The couple as the consistent nodal forces of the linear traction sigma_zz = M y / I_h on the
        // tip faces (2 x 2 Gauss on each face; I_h is the meshed polygon's, so that the couple is M).
        // The tip face of a hexahedron of the last layer is nodes 4..7 (lib/mesh/finger.cpp).
        const ElementBlock& block = mesh.blocks.front();
        std::vector<std::array<int, 4>> faces;
        for (int e = block.size(); e-- > 0;) {
            const auto n = block.element(e);
            if (std::abs(mesh.nodes[n[4]].z() - length) > 1e-9) break;
            faces.push_back({n[4], n[5], n[6], n[7]});
        }
        const double g = 1 / std::sqrt(3.0);
        const auto face_integral = [&](const std::array<int, 4>& q, auto&& add) {  // add(N, y, dA) per Gauss point
            for (double xi : {-g, g})
                for (double eta : {-g, g}) {
                    const std::array<double, 4> N = {(1 - xi) * (1 - eta) / 4, (1 + xi) * (1 - eta) / 4,
                                                     (1 + xi) * (1 + eta) / 4, (1 - xi) * (1 + eta) / 4};
                    const std::array<double, 4> dxi = {-(1 - eta) / 4, (1 - eta) / 4, (1 + eta) / 4, -(1 + eta) / 4};
                    const std::array<double, 4> deta = {-(1 - xi) / 4, -(1 + xi) / 4, (1 + xi) / 4, (1 - xi) / 4};
                    double y = 0, xx = 0, xe = 0, yx = 0, ye = 0;
                    for (int a = 0; a < 4; ++a) {
                        const Vec3& p = mesh.nodes[q[a]];
                        y += N[a] * p.y(), xx += dxi[a] * p.x(), xe += deta[a] * p.x(), yx += dxi[a] * p.y(), ye += deta[a] * p.y();
                    }
                    add(N, y, std::abs(xx * ye - xe * yx));
                }
        };
        double I_h = 0;
        for (const auto& q : faces) face_integral(q, [&](auto&, double y, double dA) { I_h += y * y * dA; });
        std::vector<Vec3> f(mesh.node_count(), Vec3::Zero());
        for (const auto& q : faces)
            face_integral(q, [&](const std::array<double, 4>& N, double y, double dA) {
                for (int a = 0; a < 4; ++a) f[q[a]].z() += N[a] * M * y / I_h * dA;
            });
        const ElementField s = solve_one_point_static(mesh, rubber, mesh.node_set("root"), f);
        // The peak over the root half (the tip half carries the load introduction).
        std::size_t k_peak = 0;
        double to_mid = length;
        for (std::size_t e = 0; e < s.von_mises.size(); ++e) {
            if (s.centroid[e].z() < 0.5 * length && s.von_mises[e] > s.von_mises[k_peak]) k_peak = e;
            to_mid = std::min(to_mid, std::abs(s.centroid[e].z() - 0.5 * length));
        }
        double s_mid = 0, beam_mid = 0;
        for (std::size_t e = 0; e < s.von_mises.size(); ++e)
            if (std::abs(s.centroid[e].z() - 0.5 * length) < to_mid + 1e-9 && s.von_mises[e] > s_mid)
                s_mid = s.von_mises[e], beam_mid = M * std::abs(s.centroid[e].y()) / I;
        fmt::print("  {:34s} {:6d} elements: largest centre stress {:.4g} Pa per N m = {:.3f} M b/I (centroid z {:.2f} mm, "
                   "y {:.2f} mm); mid-stub {:.3f} of M y_c/I\n",
                   name, static_cast<int>(s.von_mises.size()), s.von_mises[k_peak] / M, s.von_mises[k_peak] / beam_surface,
                   1e3 * s.centroid[k_peak].z(), 1e3 * s.centroid[k_peak].y(), s_mid / beam_mid);
        std::fflush(stdout);
        elements.push_back(static_cast<double>(s.von_mises.size()));
        peak.push_back(s.von_mises[k_peak] / M), peak_ratio.push_back(s.von_mises[k_peak] / beam_surface);
        z_peak.push_back(1e3 * s.centroid[k_peak].z()), y_peak.push_back(1e3 * s.centroid[k_peak].y());
        mid_ratio.push_back(s_mid / beam_mid);
    }
    t.add("elements", elements).add("peak_Pa_per_Nm", peak).add("peak_over_Mb_I", peak_ratio)
        .add("peak_centroid_z_mm", z_peak).add("peak_centroid_y_mm", y_peak).add("mid_stub_over_My_I", mid_ratio);
    io::write_dat(out / "static-finger-root.dat", t);
}

// Item 3: the object stress. The aluminium object alone (its O-grid at 12 mm as in the study, 6 mm,
// 3 mm), fixed on its sensor disc, loaded by a unit line force through its thickness at the contact
// point of the general case's force peak (thesis mesh, t = 0.712 s: (77.8, 119.0) mm in the drum
// frame, sensor reaction direction (6.37, -15.88) N), spread over the rim's node column nearest to
// it (trapezoidal weights through the thickness): the finger's 24 mm wide flank spans the 25 mm thick
// rim. Reported per mesh: the largest element-centre stress (Table 3-7's measure) and the patch mean.
void object_stress_convergence(const std::filesystem::path& out) {
    const auto al = ElasticMaterial::make("object", 69e9, 0.33, 2700);
    const Vec3 contact = Vec3(77.8e-3, 119.0e-3, 0.0) - kObjectCentre, direction = Vec3(6.37, -15.88, 0).normalized();
    io::Table t;
    std::vector<double> sizes, elements, peak, patch;
    fmt::print("object, unit line force at the contact point of the general case's force peak\n");
    for (double h : {12e-3, 6e-3, 3e-3}) {
        Mesh object = fem::finger::hex_finger({kObjA, kObjB, kObjT}, h, "object");
        object.translate(Vec3(0, 0, -0.5 * kObjT));  // centred on z = 0, as in the study (relative to its centre)
        std::vector<int> sensor;
        int nearest = 0;
        for (int i = 0; i < object.node_count(); ++i) {
            const Vec3& p = object.nodes[i];
            if (std::abs(p.z() + 0.5 * kObjT) < 1e-9 && std::hypot(p.x(), p.y()) <= kSensorRadius + 1e-9) sensor.push_back(i);
            if ((p - contact).head<2>().norm() < (object.nodes[nearest] - contact).head<2>().norm()) nearest = i;
        }
        std::vector<int> column;
        for (int i = 0; i < object.node_count(); ++i)
            if ((object.nodes[i] - object.nodes[nearest]).head<2>().norm() < 1e-9) column.push_back(i);
        std::vector<Vec3> f(object.node_count(), Vec3::Zero());
        const double share = 1.0 / (column.size() - 1);  // trapezoidal over the equal layers
        for (int i : column)
            f[i] = direction * share * ((std::abs(std::abs(object.nodes[i].z()) - 0.5 * kObjT) < 1e-9) ? 0.5 : 1.0);
        const ElementField s = solve_one_point_static(object, al, sensor, f);
        const double pk = *std::max_element(s.von_mises.begin(), s.von_mises.end());
        const double pm = patch_mean(s.von_mises, s.volume, s.centroid, Vec3(object.nodes[nearest].x(), object.nodes[nearest].y(), 0));
        fmt::print("  h {:4.1f} mm, {:5d} elements: largest element stress {:.4g} Pa/N, patch mean ({} mm) {:.4g} Pa/N\n", 1e3 * h,
                   static_cast<int>(s.von_mises.size()), pk, 1e3 * kPatchRadius, pm);
        std::fflush(stdout);
        sizes.push_back(1e3 * h), elements.push_back(static_cast<double>(s.von_mises.size())), peak.push_back(pk), patch.push_back(pm);
    }
    t.add("h_mm", sizes).add("elements", elements).add("largest_element_Pa_per_N", peak).add("patch_mean_Pa_per_N", patch);
    io::write_dat(out / "static-object.dat", t);
}

Result run_case(const Case& c, const Variant& v, const std::filesystem::path& out) {
    Result r;
    r.c = c;
    const auto rubber = ElasticMaterial::make("rubber", c.e_finger, 0.49, 1000);
    const fem::finger::EllipticCylinder shape{12e-3, 8.45e-3, kFingerLength};
    Mesh finger = v.mapped > 0 ? fem::finger::hex_finger(shape, fem::finger::mapped_cross_section(v.mapped),
                                                         static_cast<int>(std::lround(kFingerLength / v.finger_h)), "finger")
                               : fem::finger::hex_finger(shape, v.finger_h, "finger");
    // Leading (+y local: minor axis, becomes +tangential) and trailing edges: per layer the nodes
    // with the largest and smallest local y.
    std::map<long, std::pair<int, int>> edges;  // layer key -> (max x node, min x node)
    for (int i = 0; i < finger.node_count(); ++i) {
        const Vec3& p = finger.nodes[i];
        const long key = std::lround(p.z() * 1e6);
        auto [it, fresh] = edges.try_emplace(key, i, i);
        if (p.y() > finger.nodes[it->second.first].y()) it->second.first = i;
        if (p.y() < finger.nodes[it->second.second].y()) it->second.second = i;
    }
    // Finger frame -> drum frame, a proper rotation: axis z -> radial x, minor axis y -> tangential
    // y, major axis x -> out of plane -z (README: the mounting is reconstructed).
    for (auto& p : finger.nodes) p = Vec3(kDrumRadius + p.z(), p.y(), -p.x());
    const int n_finger = finger.node_count();
    Mesh object = fem::finger::hex_finger({kObjA, kObjB, kObjT}, c.e_object > 0 ? v.object_h : 6e-3, "object");
    object.translate(kObjectCentre + Vec3(0, 0, -0.5 * kObjT));
    Mesh mesh = finger;
    mesh.append(object);
    ExplicitModel model(mesh);
    model.add_hex8("finger", rubber);
    model.set_mass_damping("finger", c.alpha);
    model.prescribe_motion(finger.node_set("root"),
                           RigidMotion::rotation(Vec3::Zero(), Vec3::UnitZ(), Curve::constant(kOmega * (1 + v.perturb))));
    ContactOptions co;
    co.friction = {0.6, 0.6, 0.0};  // Table 3-6
    co.two_way = v.two_way;
    std::vector<int> sensor;
    ElasticMaterial al = ElasticMaterial::make("object", c.e_object > 0 ? c.e_object : 69e9, 0.33, 2700);
    ContactInterface* ci = nullptr;
    if (c.e_object > 0) {
        model.add_hex8("object", al);
        // Mass damping on the object: only the sway test below (Table 3-6 damps the finger only).
        if (c.object_alpha > 0) model.set_mass_damping("object", c.object_alpha);
        // The F/T sensor: the object's back face (z = -T/2) inside the sensor radius, fixed.
        for (int i = n_finger; i < mesh.node_count(); ++i) {
            const Vec3& p = mesh.nodes[i];
            if (std::abs(p.z() + 0.5 * kObjT) < 1e-9 && std::hypot(p.x() - kObjectCentre.x(), p.y() - kObjectCentre.y()) <= kSensorRadius + 1e-9)
                sensor.push_back(i);
        }
        if (sensor.size() < 3) throw InputError(fmt::format("rotating_finger_contact: only {} sensor nodes", sensor.size()));
        model.fix(sensor);
        ci = &add_contact(model, ContactInterface("finger on object", ContactSurface::from_part(mesh, "finger", rubber),
                                                  ContactSurface::from_part(mesh, "object", al), co));
    } else {
        model.add_rigid_part("object", RigidMotion::fixed());
        ci = &add_contact(model, ContactInterface("finger on object", ContactSurface::from_part(mesh, "finger", rubber),
                                                  ContactSurface::rigid_part(mesh, "object", 0.02), co));
    }
    ExplicitOptions opt;
    opt.end_time = c.end_time;
    opt.print_summary = false;
    opt.progress = false;
    opt.history_interval = 1e-3;  // energies every ms; the observer below watches every cycle
    opt.observer_interval = 0.0;
    opt.name = c.name;
    if (c.vtu) {
        opt.pvd_path = out / fmt::format("case-{}.pvd", c.name);
        opt.vtu_interval = 0.05;
    }
    if (c.e_object > 0) {
        // Selective mass scaling of the object only: a stiff object's own step (aluminium, c ~ 5 km/s)
        // would be ~20 x below the rubber's; the object is held by the sensor and loaded slowly
        // (contact lasts ~0.5 s vs its ~ms periods), so its added inertia does not matter.
        opt.mass_scaling_dt = 4e-6;
    }
    ExplicitSolver solver(model, opt);
    // The observer runs every cycle (observer_interval 0). The reaction is binned (0.1 ms means of the
    // per-cycle value) and filtered after the run (cfc60); instantaneous samples would alias the
    // penalty contact's cycle-scale noise. Stresses are element maxima over 2 ms rows, as an output
    // interval of 2 ms would report them.
    constexpr double row = 2e-3, bin = 1e-4;
    constexpr double after_contact = 0.05;  // run on this long after the finger has left the object
    std::vector<double> bins_fx, bins_fy, bins_sf, bins_so, bins_sp;
    // The object's patch-mean stress (kPatchRadius around the contact point), sampled at each bin's end.
    const ElementGroup* object_group = nullptr;
    for (const auto& g : model.groups())
        if (g->part == "object") object_group = g.get();
    std::vector<double> object_volume;
    if (object_group)
        for (int e = 0; e < mesh.blocks[object_group->block].size(); ++e) {
            std::array<Vec3, 8> X;
            const auto n = mesh.blocks[object_group->block].element(e);
            for (int a = 0; a < 8; ++a) X[a] = mesh.nodes[n[a]];
            object_volume.push_back(hex8::make_reference(X, "object").volume);
        }
    const auto object_patch = [&](const ExplicitSolver& s) {
        double w = 0;
        Vec3 p = Vec3::Zero();
        for (const auto& cp : ci->contacts()) p += cp.normal_force * cp.point, w += cp.normal_force;
        if (!object_group || w <= 0) return 0.0;
        const ElementBlock& block = mesh.blocks[object_group->block];
        std::vector<Vec3> centroid(block.size(), Vec3::Zero());
        for (int e = 0; e < block.size(); ++e)
            for (int n : block.element(e)) centroid[e] += s.state().x[n] / 8;
        return patch_mean(object_group->element_stress(), object_volume, centroid, p / w);
    };
    double t_prev = 0, next_snap = 0, bin_start = 0, row_start = 0, s_f = 0, s_o = 0, cw = 0, fc_row = 0;
    double bin_sf = 0, bin_so = 0;
    std::size_t window_bins = 0, window_rows = 0;  // bins and rows up to the end of the checked window
    double t_contact_seen = -1;  // last time any contact force acted
    Vec3 bin_impulse = Vec3::Zero(), row_impulse = Vec3::Zero(), cp_acc = Vec3::Zero();
    solver.observer = [&](const ExplicitSolver& s) {
        const double dt = s.time() - t_prev;
        t_prev = s.time();
        const Vec3 F = c.e_object > 0 ? support_reaction(s, sensor, kObjectCentre).force : ci->force_on_master();
        bin_impulse += F * dt;
        row_impulse += F * dt;
        // This cycle's element maxima, looked up once per part.
        const double vm_finger = s.max_von_mises("finger"), vm_object = s.max_von_mises("object");
        s_f = std::max(s_f, vm_finger);
        s_o = std::max(s_o, vm_object);
        bin_sf = std::max(bin_sf, vm_finger);
        bin_so = std::max(bin_so, vm_object);
        // Bin k ends at the first cycle at or after (k + 1) x 0.1 ms: fixed boundaries, so the bins'
        // times do not drift by the cycles' overshoot.
        if (s.time() >= (bins_fx.size() + 1) * bin - 1e-12) {
            const Vec3 Fm = bin_impulse / (s.time() - bin_start);
            bins_fx.push_back(Fm.x()), bins_fy.push_back(Fm.y()), bins_sf.push_back(bin_sf), bins_so.push_back(bin_so);
            bins_sp.push_back(object_patch(s));
            bin_start = s.time(), bin_impulse.setZero(), bin_sf = 0, bin_so = 0;
        }
        // Contact force (the interface's resultant) and location: force- and time-weighted centroid of
        // the contact points on the object.
        for (const auto& p : ci->contacts()) cp_acc += p.normal_force * dt * p.point, cw += p.normal_force * dt;
        fc_row += ci->force_on_master().norm() * dt;
        if (!ci->contacts().empty()) t_contact_seen = s.time();
        if (s.time() >= row_start + row - 1e-12) {
            const double len = s.time() - row_start;
            r.t.push_back(0.5 * (row_start + s.time()));
            r.f_mean2ms.push_back((row_impulse / len).head<2>().norm());
            r.f_contact.push_back(fc_row / len);
            r.s_finger_raw.push_back(s_f), r.s_object_raw.push_back(s_o);
            r.cx.push_back(cw > 0 ? cp_acc.x() / cw : NAN), r.cy.push_back(cw > 0 ? cp_acc.y() / cw : NAN);
            row_start = s.time(), row_impulse.setZero(), cp_acc.setZero(), cw = 0, s_f = 0, s_o = 0, fc_row = 0;
        }
        if (c.snapshots && s.time() >= next_snap - 1e-12) {
            next_snap += 0.05;
            r.snap_t.push_back(s.time());
            std::vector<Vec3> lead, trail;
            for (const auto& [k, e] : edges) lead.push_back(s.state().x[e.first]), trail.push_back(s.state().x[e.second]);
            r.snap_lead.push_back(lead), r.snap_trail.push_back(trail);
        }
        // The checked window ends 50 ms after the last contact force; --full runs on to end_time
        // (the thesis's whole turn) for the figures, the checks still use the window.
        if (t_contact_seen > 0 && s.time() > t_contact_seen + after_contact && window_bins == 0) {
            window_bins = bins_fx.size(), window_rows = r.t.size();
            if (!c.full_rotation) s.request_stop();
        }
    };
    r.summary = solver.run();
    r.wall = r.summary.wall_s;
    r.steps = r.summary.steps;
    if (window_bins == 0) window_bins = bins_fx.size(), window_rows = r.t.size();  // contact never ended
    // The plotted histories: the whole record.
    const damping::SampledSignal fx = cfc60(bins_fx, bin), fy = cfc60(bins_fy, bin), sf = cfc60(bins_sf, bin),
                                 so = cfc60(bins_so, bin), sp = cfc60(bins_sp, bin);
    auto at = [&](const damping::SampledSignal& sig, double t) {  // linear interpolation in the record
        const double u = std::clamp((t - sig.t0) / sig.dt, 0.0, static_cast<double>(sig.size() - 1));
        const std::size_t i = std::min(static_cast<std::size_t>(u), sig.size() - 2);
        return sig.x[i] + (u - i) * (sig.x[i + 1] - sig.x[i]);
    };
    for (double t : r.t) {
        r.fx.push_back(at(fx, t)), r.fy.push_back(at(fy, t));
        r.f.push_back(std::hypot(r.fx.back(), r.fy.back()));
        r.s_finger.push_back(at(sf, t)), r.s_object.push_back(at(so, t)), r.s_patch.push_back(at(sp, t));
    }
    // The checked maxima: the window's record alone, filtered as a run that stopped there would
    // filter it (same bits with and without --full).
    const auto head = [&](const std::vector<double>& v) { return std::vector<double>(v.begin(), v.begin() + window_bins); };
    const damping::SampledSignal wfx = cfc60(head(bins_fx), bin), wfy = cfc60(head(bins_fy), bin),
                                 wsf = cfc60(head(bins_sf), bin), wso = cfc60(head(bins_so), bin),
                                 wsp = cfc60(head(bins_sp), bin);
    for (std::size_t i = 0; i < wfx.size(); ++i) {
        r.f_max = std::max(r.f_max, std::hypot(wfx.x[i], wfy.x[i]));
        r.s_finger_max = std::max(r.s_finger_max, wsf.x[i]);
        r.s_object_max = std::max(r.s_object_max, wso.x[i]);
        r.s_patch_max = std::max(r.s_patch_max, wsp.x[i]);
    }
    for (std::size_t i = 0; i < window_bins; ++i) r.s_patch_raw_max = std::max(r.s_patch_raw_max, bins_sp[i]);
    double& fc_max = r.f_contact_max;
    for (std::size_t i = 0; i < window_rows; ++i) {
        r.f_mean2ms_max = std::max(r.f_mean2ms_max, r.f_mean2ms[i]);
        r.s_finger_raw_max = std::max(r.s_finger_raw_max, r.s_finger_raw[i]);
        r.s_object_raw_max = std::max(r.s_object_raw_max, r.s_object_raw[i]);
        fc_max = std::max(fc_max, r.f_contact[i]);
    }
    // Contact duration: the contact force (not the sensor, which rings on after the finger has left)
    // above 2 % of its maximum, excluding single grazing touches.
    for (std::size_t i = 0; i < window_rows; ++i)
        if (r.f_contact[i] > 0.02 * fc_max) {
            if (r.t_first < 0) r.t_first = r.t[i];
            r.t_last = r.t[i];
        }
    fmt::print("[ {} ] CFC 60 maxima: F {:.3f} N, sigma_finger {:.3f} MPa, sigma_object {:.3f} MPa, object patch {:.3f} MPa; "
               "raw: F (2 ms means) {:.3f} N, sigma_finger {:.3f} MPa, sigma_object {:.3f} MPa, object patch {:.3f} MPa; "
               "contact {:.3f}..{:.3f} s, {} steps, dt {:.3g} us, energy error {:.3g}, {:.1f} s\n",
               c.name, r.f_max, r.s_finger_max / 1e6, r.s_object_max / 1e6, r.s_patch_max / 1e6, r.f_mean2ms_max,
               r.s_finger_raw_max / 1e6, r.s_object_raw_max / 1e6, r.s_patch_raw_max / 1e6, r.t_first, r.t_last, r.steps,
               1e6 * r.summary.min_dt, r.summary.energy.relative_error(), r.wall);
    return r;
}

void write_series(const std::filesystem::path& path, const Result& r) {
    io::Table t;
    const auto mpa = [](const std::vector<double>& v) {
        std::vector<double> m;
        for (double x : v) m.push_back(x / 1e6);
        return m;
    };
    std::vector<double> cx, cy;
    for (double v : r.cx) cx.push_back(1e3 * v);
    for (double v : r.cy) cy.push_back(1e3 * v);
    t.add("t_s", r.t).add("F_cfc60_N", r.f).add("Fx_cfc60_N", r.fx).add("Fy_cfc60_N", r.fy)
        .add("sigma_finger_cfc60_MPa", mpa(r.s_finger)).add("sigma_object_cfc60_MPa", mpa(r.s_object))
        .add("contact_x_mm", cx).add("contact_y_mm", cy).add("F_mean_2ms_N", r.f_mean2ms).add("F_contact_N", r.f_contact)
        .add("sigma_finger_raw_MPa", mpa(r.s_finger_raw)).add("sigma_object_raw_MPa", mpa(r.s_object_raw))
        .add("sigma_object_patch_cfc60_MPa", mpa(r.s_patch));
    io::write_dat(path, t);
}

void write_outlines(const std::filesystem::path& path, const Result& r) {
    std::ofstream f(path);
    f << "# blocks (gnuplot index): finger outline every 0.05 s, leading edge then trailing edge reversed [mm]\n";
    for (std::size_t k = 0; k < r.snap_t.size(); ++k) {
        f << "# t = " << r.snap_t[k] << " s\n";
        for (const auto& p : r.snap_lead[k]) f << 1e3 * p.x() << ' ' << 1e3 * p.y() << '\n';
        for (auto it = r.snap_trail[k].rbegin(); it != r.snap_trail[k].rend(); ++it)
            f << 1e3 * it->x() << ' ' << 1e3 * it->y() << '\n';
        f << 1e3 * r.snap_lead[k].front().x() << ' ' << 1e3 * r.snap_lead[k].front().y() << "\n\n\n";
    }
}

// A case's own files in `dir` (the study run's folder or a --case side run's): case-<name>.dat and,
// for the cases with snapshots, outline-<name>.dat.
void write_case_files(const std::filesystem::path& dir, const Case& c, const Result& r) {
    write_series(dir / fmt::format("case-{}.dat", c.name), r);
    if (c.snapshots) write_outlines(dir / fmt::format("outline-{}.dat", c.name), r);
}

// --- Side runs (README, "Side runs") ------------------------------------------------------------

// The side runs' usage; the case names come from table_3_7_cases (one list).
std::string side_run_usage() {
    std::string names;
    for (const Case& c : table_3_7_cases(3.0)) names += (names.empty() ? "" : ", ") + c.name;
    return "side runs (each writes under build/results/rotating_finger_contact/<run>/, or --results DIR):\n"
           "  --case <name> [end time]      one case of Table 3-7 alone, no checks (folder case-<name>); end time\n"
           "                                in s (default 3, the run stops 50 ms after contact); the cases:\n"
           "                                " + names + "\n"
           "      --finger-h M              the finger's target element length [m] (default 6e-3)\n"
           "      --mapped N                the finger's section as one mapped N x N block, round(L / h) layers\n"
           "                                (the thesis's mesh: --mapped 5 --finger-h 3.984e-3)\n"
           "      --object-h M              the aluminium object's element length [m] (default 12e-3)\n"
           "      --perturb EPS             the drum speed x (1 + EPS) (|EPS| <= 1e-3: a robustness test)\n"
           "      --two-way                 symmetric contact (the object's nodes on the finger's faces too)\n"
           "  --static-convergence [k]      the static mesh convergence of the object's stress (12, 6, 3 mm) and of\n"
           "                                the finger's root stress (O-grids 6 and 3 mm, the thesis's mapped mesh\n"
           "                                and its halves down to h / 2^(k-1); k 1..3, default 1)\n"
           "      --finger-only             the finger's root stress alone\n"
           "  --quiet                       no progress lines on stderr\n";
}

/// A side run's command line (check::read_side_run) with its options read.
struct SideRunCommand : check::SideRun {
    Variant variant;
    bool finger_only = false;
};

SideRunCommand parse_side_run(int argc, char** argv) {
    SideRunCommand c;
    static_cast<check::SideRun&>(c) = check::read_side_run(
        argc, argv, "rotating_finger_contact", side_run_usage(), {"--case", "--static-convergence"},
        {{"--finger-h", "--case"},
         {"--mapped", "--case"},
         {"--object-h", "--case"},
         {"--perturb", "--case"},
         {"--two-way", "--case"},
         {"--finger-only", "--static-convergence"}},
        [&](input::Arguments& args) {
            // Bounds: an element longer than the finger's thickness or the object's, or a mapped
            // section finer than the finger runs can afford, is a typo, not a study.
            if (args.is("--finger-h")) c.variant.finger_h = args.real(input::Range::closed(0.5e-3, 17e-3));
            else if (args.is("--mapped")) c.variant.mapped = args.integer<int>({.min = 1, .max = 40});
            else if (args.is("--object-h")) c.variant.object_h = args.real(input::Range::closed(1e-3, 50e-3));
            else if (args.is("--perturb")) c.variant.perturb = args.real(input::Range::closed(-1e-3, 1e-3));
            else if (args.is("--two-way")) c.variant.two_way = true;
            else if (args.is("--finger-only")) c.finger_only = true;
        });
    return c;
}

// --case <name> [end time]: one case alone, no checks; its files as the study run's for the case.
int case_side_run(const SideRunCommand& c) {
    const std::vector<std::string>& op = c.operands;
    c.at_most_operands(2, "case, end time");
    if (op.empty()) throw InputError("--case: name the case (rotating_finger_contact --help lists them)");
    const double end = op.size() > 1 ? input::parse_real(op[1], {"command line", 0, "--case (end time)"}, input::Range::positive()) : 3.0;
    const std::vector<Case> cases = table_3_7_cases(end);
    std::vector<std::string> names;
    for (const Case& k : cases) names.push_back(k.name);
    const std::string name = input::check_choice(op[0], {"command line", 0, "--case (Table 3-7 case)"}, names);
    const Case& which = *std::find_if(cases.begin(), cases.end(), [&](const Case& k) { return k.name == name; });
    io::RunFolder out(check::side_run_folder("rotating_finger_contact", "case-" + name, c.results), "rotating_finger_contact --case");
    const Result r = run_case(which, c.variant, out.staging());
    write_case_files(out.staging(), which, r);
    io::write_text_file(out.staging() / "run.json", r.summary.to_json().dump(2) + "\n");
    fmt::print("{}\n", r.summary.text());
    fmt::print("{}: F max {:.3f} N (CFC 60; 2 ms-mean maximum {:.3f} N), contact force max {:.3f} N, sigma finger max {:.3f} MPa, "
               "sigma object max {:.3f} MPa (patch mean {:.3f} MPa), contact {:.3f}..{:.3f} s\n",
               name, r.f_max, r.f_mean2ms_max, r.f_contact_max, r.s_finger_max / 1e6, r.s_object_max / 1e6, r.s_patch_max / 1e6,
               r.t_first, r.t_last);
    out.commit();
    fmt::print("results: {}\n", out.path().string());
    return 0;
}

// --static-convergence [k]: the static mesh convergence studies alone (README), no checks.
int static_convergence_side_run(const SideRunCommand& c) {
    c.at_most_operands(1, "finest level");
    const int finest = c.operands.empty() ? 1
                                          : input::parse_integer<int>(c.operands[0], {"command line", 0, "--static-convergence (finest level)"},
                                                                      {.min = 1, .max = 3});
    io::RunFolder out(check::side_run_folder("rotating_finger_contact", "static-convergence", c.results),
                      "rotating_finger_contact --static-convergence");
    if (!c.finger_only) object_stress_convergence(out.staging());
    finger_root_convergence(out.staging(), finest);
    out.commit();
    fmt::print("results: {}\n", out.path().string());
    return 0;
}

// The study run: Table 3-7's nine cases at once, their checks and figures.
void run(check::Study& study) {
    const auto& out = study.results_dir();
    std::vector<Case> cases = table_3_7_cases(3.0);
    for (auto& c : cases) c.full_rotation = study.full();
    // The eight runs are independent: check::run_cases runs them at once on the machine's cores
    // (about 35 s of CPU each; their results, and so every check, are a serial run's bits).
    check::CaseOptions options;
    for (std::size_t k = 0; k < cases.size(); ++k)
        if (cases[k].vtu) options.writes_files.push_back(static_cast<int>(k));
    std::vector<Result> runs = check::run_cases<Result>(
        study, static_cast<int>(cases.size()), [&](int k) { return run_case(cases[k], Variant{}, out); }, options);
    std::map<std::string, Result> res;
    io::Table instants;  // Fig 3-30
    std::vector<double> alphas, firsts, lasts;
    for (std::size_t k = 0; k < cases.size(); ++k) {
        const Case& c = cases[k];
        Result& r = res[c.name] = std::move(runs[k]);
        study.record_run({c.name, r.summary.to_json()});
        write_case_files(out, c, r);
        if (c.e_finger == 6.1e6 && c.e_object == 69e9)
            alphas.push_back(c.alpha), firsts.push_back(r.t_first), lasts.push_back(r.t_last);
    }
    instants.add("alpha_per_s", alphas).add("contact_start_s", firsts).add("contact_end_s", lasts);
    io::write_dat(out / "contact-instants.dat", instants);

    const Result& b = res.at("alpha-7.5");
    const auto note = [](const Result& r) {
        return fmt::format("2 ms-mean maximum {:.2f} N; contact {:.3f}..{:.3f} s", r.f_mean2ms_max, r.t_first,
                           r.t_last);
    };
    study.check("table-3-7/base/F-reaction-max", b.f_max, note(b));
    study.check("table-3-7/base/sigma-finger-max", b.s_finger_max / 1e6);
    study.check("table-3-7/E-object-69GPa/sigma-object-max", b.s_object_max / 1e6);
    const std::vector<std::string> others = {"alpha-1",   "alpha-20",     "alpha-50",       "alpha-180",
                                             "alpha-600", "E-finger-4.2", "E-object-6.1MPa"};
    std::vector<double> F, sf;
    for (const auto& name : others) {
        if (name != "E-object-6.1MPa") F.push_back(res.at(name).f_max);
        sf.push_back(res.at(name).s_finger_max / 1e6);
    }
    study.check("table-3-7/cases/F-reaction-max", F);
    study.check("table-3-7/cases/sigma-finger-max", sf);
    const Result& soft = res.at("E-object-6.1MPa");
    study.check("table-3-7/E-object-6.1MPa/F-reaction-max", soft.f_max, note(soft));
    study.check("table-3-7/E-object-6.1MPa/F-contact-max", soft.f_contact_max);
    const Result& damped = res.at("E-object-6.1MPa-damped");
    study.check("table-3-7/E-object-6.1MPa/sway-test", damped.f_max / damped.f_contact_max,
                fmt::format("object damped at 50 1/s: sensor {:.2f} N, contact {:.2f} N; undamped (the judged case): "
                            "sensor {:.2f} N, contact {:.2f} N",
                            damped.f_max, damped.f_contact_max, soft.f_max, soft.f_contact_max));
    std::vector<double> so_al, so_other;
    for (const char* name : {"alpha-1", "alpha-20", "alpha-50", "E-finger-4.2"})
        so_al.push_back(res.at(name).s_object_max / 1e6);
    for (const char* name : {"alpha-180", "alpha-600", "E-object-6.1MPa"})
        so_other.push_back(res.at(name).s_object_max / 1e6);
    study.check("table-3-7/cases/sigma-object-max", so_al);
    study.check("table-3-7/cases/sigma-object-max-not-reproduced", so_other);
    std::vector<double> patch;
    for (const char* name : {"alpha-7.5", "alpha-1", "alpha-20", "alpha-50", "alpha-180", "alpha-600", "E-finger-4.2", "E-object-6.1MPa"})
        patch.push_back(res.at(name).s_patch_max / 1e6);
    study.check("table-3-7/cases/sigma-object-patch", patch);

    const Result& a180 = res.at("alpha-180");
    const Result& a600 = res.at("alpha-600");
    const Result& ef = res.at("E-finger-4.2");
    const Result& so = res.at("E-object-6.1MPa");
    bool same = true;
    std::string low;
    for (const char* name : {"alpha-1", "alpha-20", "alpha-50"}) {
        const double ratio = res.at(name).f_max / b.f_max;
        same = same && std::abs(ratio - 1) < 0.08;
        low += fmt::format("{}F_{}/F_7.5 = {:.3f}", low.empty() ? "" : ", ", name, ratio);
    }
    study.trend_holds("table-3-7/alpha/F-independent-1-to-50", same, low);
    study.trend_holds("table-3-7/alpha/F-independent-up-to-180", std::abs(a180.f_max / b.f_max - 1) < 0.08,
                      fmt::format("F180 / F7.5 = {:.3f} / {:.3f} = {:.3f}", a180.f_max, b.f_max, a180.f_max / b.f_max),
                      fmt::format("2 ms means: {:.3f} / {:.3f}", a180.f_mean2ms_max, b.f_mean2ms_max));
    study.trend_holds("table-3-7/alpha/F-lower-at-600", a600.f_max < 0.95 * b.f_max,
                      fmt::format("F600 / F7.5 = {:.3f} / {:.3f} = {:.3f}", a600.f_max, b.f_max, a600.f_max / b.f_max));
    const double s50 = res.at("alpha-50").s_finger_max, s180 = a180.s_finger_max, s600 = a600.s_finger_max;
    study.trend_holds("table-3-7/alpha/sigma-finger-rises-above-50", s50 < s180 && s180 < s600,
                      fmt::format("sigma_finger {:.3f}, {:.3f}, {:.3f} MPa at alpha 50, 180, 600", s50 / 1e6,
                                  s180 / 1e6, s600 / 1e6));
    const double d_b = b.t_last - b.t_first, d_600 = a600.t_last - a600.t_first;
    study.trend_holds("fig-3-30/contact-shorter-at-high-alpha", d_600 < d_b,
                      fmt::format("contact {:.3f}..{:.3f} s ({:.3f} s) at alpha 600 vs {:.3f}..{:.3f} s ({:.3f} s) at 7.5",
                                  a600.t_first, a600.t_last, d_600, b.t_first, b.t_last, d_b),
                      "contact = the contact force above 2 % of its maximum (2 ms means)");
    study.trend_holds("table-3-7/E-finger/F-rises", ef.f_max < 0.9 * b.f_max,
                      fmt::format("F(4.2 MPa) / F(6.1 MPa) = {:.3f} / {:.3f} = {:.3f}", ef.f_max, b.f_max, ef.f_max / b.f_max));
    study.trend_holds("table-3-7/E-object/stress-collapses", so.s_object_max < 0.2 * b.s_object_max,
                      fmt::format("sigma_object {:.3f} vs {:.3f} MPa", so.s_object_max / 1e6, b.s_object_max / 1e6));
    study.trend_holds("table-3-7/E-object/force-stays", std::abs(so.f_max / b.f_max - 1) < 0.1,
                      fmt::format("F {:.3f} vs {:.3f} N (sensor, CFC 60)", so.f_max, b.f_max),
                      fmt::format("contact force {:.3f} vs {:.3f} N; 2 ms means of the sensor {:.3f} vs {:.3f} N",
                                  so.f_contact_max, b.f_contact_max, so.f_mean2ms_max, b.f_mean2ms_max));
    study.plot();
}

}  // namespace

int main(int argc, char** argv) {
    // The side runs' command line is read first (strictly); without a side run the study reads its own.
    SideRunCommand c;
    if (const int status = run_program("rotating_finger_contact", [&] {
            c = parse_side_run(argc, argv);
            return 0;
        });
        status != 0)
        return status;
    if (c.mode.empty()) return check::run_study("rotating_finger_contact", argc, argv, run);
    const std::string program = "rotating_finger_contact " + c.mode;
    return run_program(program.c_str(), [&] {
        if (c.mode == "--case") return case_side_run(c);
        return static_convergence_side_run(c);
    });
}
