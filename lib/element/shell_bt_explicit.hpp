#pragma once
// Explicit internal-force kernel of the 4-node Belytschko-Tsay shell (Belytschko, Lin and Tsay
// 1984; LS-DYNA shell formulation 2, ANSYS SHELL163, the thesis's "Shell 163" of App. A and Tables
// 3-5, 5-5, 5-7) for the thin steel and aluminium parts of thesis Ch 3-5 (drum, perch, shackle,
// track, arm). Elastic material only. Used every cycle by ShellGroup (lib/explicit/shell_group.hpp).
//
// Formulation (Mindlin plate kinematics in a corotational frame, one point in the plane):
//  * Corotational frame of the element at a configuration x: e3 along the cross product of the
//    diagonals r31 x r42 (0-based: (x2 - x0) x (x3 - x1)), e1 along side 1-2 projected onto the
//    plane normal to e3, e2 = e3 x e1. The frame is embedded (it turns with the element), so stress
//    components stored in it are corotational: a rigid rotation leaves them unchanged. The nodes
//    are projected onto the frame's plane (local x^, y^ about the centroid). A = |r31 x r42| / 2.
//    Both diagonals are normal to e3, so a warped element's out-of-plane offsets are z^_I = z_w h_I
//    (h below).
//  * One in-plane point (the centre): B_1I = dN_I/dx^, B_2I = dN_I/dy^ there,
//    B_1 = [y^1 - y^3, y^2 - y^0, y^3 - y^1, y^0 - y^2] / 2A, B_2 = [x^3 - x^1, x^0 - x^2,
//    x^1 - x^3, x^2 - x^0] / 2A. A B_I is the exact integral of grad N_I over the flat element, so
//    any linear field gives its exact constant strain and the forces of a constant stress balance at
//    interior nodes of a distorted flat patch: the membrane patch test is passed exactly.
//  * Kinematics: u(z) = u_mid + z theta x e3, i.e. u^_x = u^_x,mid + z theta^_y, u^_y =
//    u^_y,mid - z theta^_x, u^_z = w. Strain increments over a step, from the nodal displacement
//    increments du_I and rotation increments dtheta_I (local components):
//      membrane   d eps_xx = B_1I du^x_I, d eps_yy = B_2I du^y_I, d gamma_xy = B_2I du^x_I + B_1I du^y_I
//      curvature  d k_xx = B_1I dth^y_I, d k_yy = -B_2I dth^x_I, d k_xy = B_2I dth^y_I - B_1I dth^x_I
//      tr. shear  d g_xz = B_1I dw_I + sum_I dth^y_I / 4,  d g_yz = B_2I dw_I - sum_I dth^x_I / 4
//    (one-point shear: no shear locking on rectangles, the reason BT uses one point).
//  * Warped elements: a rigid rotation about an in-plane axis moves the offset nodes in the plane
//    (du^x_I = dphi_y z^_I): formulation 2 as published takes that for membrane strain and, above
//    all, membrane hourglass (a 2.5 % warped element turned by 120 degrees built up hourglass
//    forces of the order of its elastic forces, test LargeRigidRotation...). The membrane part of
//    Belytschko-Wong-Chiang's warping correction removes it: the element's own rotation about
//    the in-plane axes from its normal displacements, dphi_x = B_2I dw_I, dphi_y = -B_1I dw_I, and
//    du^x_I -= z^_I dphi_y, du^y_I += z^_I dphi_x before the membrane increments; its dual on the
//    forces, f^z_J += B_1J sum_I z^_I f^x_I + B_2J sum_I z^_I f^y_I, keeps the nodal forces
//    power-conjugate and restores moment equilibrium. Nothing changes for flat elements.
//  * Incremental objectivity: the increments are taken on the mid-step configuration x(n+1/2) =
//    (x(n) + x(n+1)) / 2 (frame and B there, Hughes-Winget). For a rigid rotation by phi of the
//    nodes, grad du on the mid-step geometry is exactly skew (2 tan(phi/2) [n]x, the Cayley form),
//    and the nodal rotation increments are taken in the same Cayley form (rotation_increment()),
//    so a rigid motion of any size gives exactly zero strain increment. (On x(n+1) or x(n) the
//    increment would be (1 - cos phi) of stretch per step: pi phi per revolution.)
//  * Through the thickness: 3-point Lobatto (Simpson) at z = -t/2, 0, +t/2, weights t/6, 2t/3, t/6,
//    each point storing its plane-stress sigma_xx, sigma_yy, sigma_xy (hypoelastic update
//    sigma += C d eps, C the plane-stress matrix); the transverse shear stresses tau = kappa G
//    gamma (kappa = 5/6) are constant through the thickness. Why Lobatto 3: the material is
//    elastic, so the stress is linear in z and any rule exact for quadratics integrates the
//    resultants N = int sigma dz, M = int z sigma dz exactly (LS-DYNA's default 2-point Gauss
//    would give the same forces); Lobatto puts points ON the surfaces, so the top and bottom von
//    Mises stresses (the thesis's stress results, e.g. the shackle's 25 and 78.5 MPa) are
//    integration-point values, not extrapolations.
//  * Nodal forces (conjugate to the rates above; resultants N, M, Q = t tau, all local):
//      f^x_I = A (B_1I N_xx + B_2I N_xy),  f^y_I = A (B_2I N_yy + B_1I N_xy),  f^z_I = A (B_1I Q_x + B_2I Q_y)
//      m^x_I = -A (B_2I M_yy + B_1I M_xy + Q_y / 4),  m^y_I = A (B_1I M_xx + B_2I M_xy + Q_x / 4),  m^z_I = 0
//    evaluated on the end-of-step geometry x(n+1) and rotated to global axes. They are exactly
//    self-equilibrated (zero net force and moment) for a flat element.
//  * Drilling: formulation 2 has no stiffness about the normal (m^z = 0). On a bent or curved
//    mesh the local moments of neighbouring facets then leave a small unbalanced nodal moment
//    about the normal that nothing resists: the node spins up (a simply supported plate under
//    pressure, mass-damped: 0.36 rad/s of drilling spin at the end, growing with refinement, test
//    ShellBtStatics.Drilling...). As MITC4 in this library (shell_mitc4.hpp) and most explicit
//    codes' shells, a small penalty ties each node's rotation about the normal to the element's
//    in-plane spin at the centre, omega_m = (B_1I du^y_I - B_2I du^x_I) / 2 (zero for every rigid
//    motion): drilling moments m^z_I += k_d (dth^z_I - omega_m), k_d = r_d G t A / 4, with the
//    conjugate in-plane forces f^x_J += B_2J sum m^z / 2, f^y_J -= B_1J sum m^z / 2. r_d = 1e-3
//    (ShellSection::drilling; 0 gives formulation 2 as published); its energy sum (m^z)^2 / 2 k_d
//    is reported with the hourglass energy (both are artificial stabilization).
//  * Hourglass control (Belytschko-Tsay, stiffness form, LS-DYNA IHQ 4/5 type for shells): the
//    hourglass vector h = (1, -1, 1, -1) made orthogonal to linear fields, gamma_I = h_I -
//    (h . x^) B_1I - (h . y^) B_2I; generalized hourglass increments dq = gamma_I (dth^x_I,
//    dth^y_I, dw_I, du^x_I, du^y_I) accumulate hourglass "stresses" Q += k dq with
//      bending     k_theta = r_theta E t^3 A / 192 B_bI B_bI   (moments about x^ and y^)
//      transverse  k_w     = r_w kappa G t^3 / 12 B_bI B_bI
//      membrane    k_m     = r_m E t A / 8 B_bI B_bI
//    (the coefficients of Belytschko-Tsay as documented for LS-DYNA), forces/moments gamma_I Q,
//    energy Q^2 / 2k (stored, like the elastic energy: the stiffness form neither dissipates nor
//    damps the free vibrations that the verification tests measure). gamma is orthogonal to every
//    linear field, so rigid motions and the patch tests are untouched. Chosen over the viscous form
//    because the thesis's parts vibrate freely for long times after the contacts (the viscous form
//    would add damping no thesis number accounts for). Default r = 0.01 (ShellSection).
//    One change to the transverse mode: w is quadratic in plate bending, and gamma . w of a twist
//    w = x y (with theta = grad w, no shear) is not zero, so BT's k_w resists legitimate twisting
//    (a simply supported square plate under pressure came out 0.15 % too stiff at r_w = 0.01 and
//    1.4 % at 0.1, converging away from Timoshenko). As in Belytschko-Leviathan's physical
//    stabilization, the transverse hourglass increment is taken relative to the quadratic w that the
//    element's rotation gradients imply (w_xx = -d theta_y/dx, w_yy = d theta_x/dy, w_xy =
//    (d theta_x/dx - d theta_y/dy) / 2 from the one-point gradients B theta):
//      dq_w = gamma_I dw_I - [-(B_1 . dth^y) g_xx + (B_2 . dth^x) g_yy + (B_1 . dth^x - B_2 . dth^y) g_xy] / 2,
//    g_ab = sum_I gamma_I a^_I b^_I; its conjugate moments go to the nodal rotations. It still
//    resists the w-hourglass (w = h, theta = 0) fully and vanishes for every bending and twisting
//    mode and every rigid motion (tests).
//  * Triangles: stored as degenerate quadrilaterals (node 3 repeated as node 4): A and the summed B
//    of the repeated node are the constant-strain triangle's (membrane and curvature), and every
//    hourglass increment vanishes (three nodes carry only linear fields). The one-point shear of the
//    degenerate quadrilateral (LS-DYNA's formulation 2 without ESORT) locks: a cantilever strip of
//    such triangles deflected 93 % too little with 8 x 2 x 2 triangles, 45 % with 32 x 2 x 2 (test
//    ShellBtStatics.TriangleCantilever...). So triangles take their transverse shear from the
//    tangential shear strains of their three edges, e_s = (w_j - w_i) / l + s_x thbar^y - s_y
//    thbar^x (thbar the edge's mean rotation: zero for every Kirchhoff bending and twisting mode,
//    because a quadratic w's secant slope is its mid-edge slope), fitted by the MITC3 field g_xz =
//    a1 + c y, g_yz = a2 - c x (Lee and Bathe 2004) and taken at the centroid, (a1, a2); the
//    nodal forces and moments are its conjugates. This stands in for LS-DYNA's C0 triangle
//    (ESORT = 1), which the degenerate quadrilateral is not fit to replace.
//    Lumped mass rho t A / 3 per node (not the quadrilateral's 1/4, 1/4, 1/2).
//
// Energies: the stored elastic energy A sum_k w_k sigma_k . C^-1 sigma_k / 2 + A t tau . tau /
// (2 kappa G) and the hourglass energy sum Q^2 / 2k are state functions of the stored stresses
// (exact for the hypoelastic law at small strain, what the energy balance of the solver compares).
#include <array>

#include "core/types.hpp"
#include "material/elastic.hpp"

namespace fem::shellbt {

/// Integration points through the thickness (Lobatto): bottom (z = -t/2), mid-surface, top (+t/2).
inline constexpr int kPoints = 3;
inline constexpr double kPointZ[kPoints] = {-0.5, 0.0, 0.5};               // z / t
inline constexpr double kPointWeight[kPoints] = {1.0 / 6, 4.0 / 6, 1.0 / 6};  // weight / t

/// Shell section of a part (LS-DYNA *SECTION_SHELL ELFORM 2 + *HOURGLASS for shells).
struct ShellSection {
    double thickness = 0.0;             // t [m]
    double shear_factor = 5.0 / 6.0;    // kappa of the transverse shear
    double hourglass_membrane = 0.01;   // r_m
    double hourglass_bending = 0.01;    // r_theta
    double hourglass_transverse = 0.01; // r_w
    double drilling = 1e-3;             // r_d (0: no drilling stiffness, LS-DYNA's formulation 2)
    /// InputError naming `owner` when t <= 0, kappa <= 0 or a coefficient < 0 (or not finite).
    void validate(const char* owner) const;
};

/// Constants the kernel needs, from the material and the section.
struct Constants {
    double E = 0, nu = 0, G = 0, rho = 0;
    double c11 = 0, c12 = 0;  // plane-stress E / (1 - nu^2), nu E / (1 - nu^2); c33 = G
    double kappa_G = 0;       // transverse shear modulus kappa G
    double t = 0;             // thickness
    double r_m = 0, r_theta = 0, r_w = 0, r_d = 0;
    static Constants from(const ElasticMaterial& m, const ShellSection& s);
};

/// The element's corotational frame and one-point operators at one configuration.
struct Frame {
    Mat3 E;                       // columns e1, e2, e3
    double area = 0.0;            // A = |r31 x r42| / 2
    std::array<double, 4> b1{}, b2{};  // B_1I, B_2I [1/m]
    std::array<double, 4> gamma{};     // hourglass vector
    std::array<double, 4> warp{};      // z^_I: the nodes' offsets from the frame's plane (z_w h_I)
    double gxx = 0, gyy = 0, gxy = 0;  // sum_I gamma_I x^_I^2, gamma_I y^_I^2, gamma_I x^_I y^_I [m^2]
    std::array<double, 4> px{}, py{};  // x^_I, y^_I (about the centroid)
    bool triangle = false;             // node 3 coincides with node 2 (a triangle)
    // Triangles: edge e (nodes e, e+1 mod 3) unit tangent (sx, sy), length, and the centroid shear
    // (a1, a2) = sum_e shear[e] * e_s(e) of the MITC3 fit (rows 0, 1 of its inverse).
    std::array<double, 3> sx{}, sy{}, len{};
    std::array<std::array<double, 3>, 2> shear{};
    double bb = 0.0;              // sum_I B_1I^2 + B_2I^2 [1/m^2]
};
/// Frame at nodes x. area <= 0 (or not finite) when the element is degenerate; the operators are
/// then not computed.
Frame make_frame(const std::array<Vec3, 4>& x);

/// The element's stored state: stresses in the corotational frame, hourglass resultants. Zero
/// initially (stress-free reference).
struct State {
    double sigma[kPoints][3] = {};  // sigma_xx, sigma_yy, sigma_xy per point [Pa]
    double tau[2] = {};             // tau_xz, tau_yz [Pa] (constant through the thickness)
    double hourglass[5] = {};       // Q: moments about x^, y^ [N m]; forces along z^, x^, y^ [N]
    double drilling[4] = {};        // drilling moments m^z_I [N m]
};

struct Result {
    std::array<Vec3, 4> force, moment;   // internal (resisting) nodal forces and moments, global
    double strain_energy = 0.0;          // elastic, hourglass excluded [J]
    double hourglass_energy = 0.0;       // hourglass and drilling stabilization [J]
    std::array<double, kPoints> von_mises_sq{};  // squared von Mises stress at bottom, mid, top [Pa^2]
    bool bad = false;                    // degenerate or non-finite: outputs meaningless
};

/// Nodal rotation increment of a step from the nodal rotation matrices before and after it: the
/// Cayley vector 2 tan(phi/2) n of R_new R_old^T (see the header comment: it matches the mid-step
/// strain increment of a rigid rotation exactly).
Vec3 rotation_increment(const Mat3& R_new, const Mat3& R_old);

/// Adds the strain increments of one step (local components on the mid-step frame `mid`; global
/// displacement and rotation increments du, dtheta) to the state (stresses, hourglass resultants).
void update_state(const Constants& c, const Frame& mid, const std::array<Vec3, 4>& du,
                  const std::array<Vec3, 4>& dtheta, State& state);

/// Nodal forces, moments, energies and surface stresses of a state on the frame `end`.
void forces(const Constants& c, const Frame& end, const State& state, Result& out);

/// One step of one element: update_state on the mid-step frame of (x_old + x_new) / 2 with du =
/// x_new - x_old, then forces on the frame of x_new. out.bad when either frame is degenerate (the
/// state is then left unchanged).
void internal_force(const Constants& c, const std::array<Vec3, 4>& x_old, const std::array<Vec3, 4>& x_new,
                    const std::array<Vec3, 4>& dtheta, State& state, Result& out);

/// Linear stiffness (24 x 24, DOFs ux uy uz rx ry rz per node, global axes) of the element at
/// nodes X: forces of the state that unit increments on the frame of X produce (exact, the kernel
/// is linear in the increments on a fixed frame). For verification (eigenvalues, comparisons).
Eigen::Matrix<double, 24, 24> linear_stiffness(const Constants& c, const std::array<Vec3, 4>& X);

/// Lumped masses of one element at reference nodes X: translational mass per node (rho t A / 4;
/// a triangle, X[3] == X[2], rho t A / 3 on each of its three nodes and 0 for the repeat) and the
/// isotropic rotational inertia per node (see rotational_inertia).
struct LumpedMass {
    std::array<double, 4> mass{}, inertia{};
};
LumpedMass lumped_mass(const Constants& c, const std::array<Vec3, 4>& X, bool triangle);

/// Rotational inertia per node of one element, scaled so that the rotations do not control the
/// time step (as LS-DYNA scales shell rotary inertia): the smallest isotropic J (per node, equal
/// for the element's nodes) for which no rotational row of the element's Gershgorin bound on
/// omega^2 (transverse shear, bending and bending-hourglass rows against J, shear coupling to the
/// translations against sqrt(J m)) exceeds (2 / dt)^2, dt the element's Table 2-1 step; never below
/// the physical rho t^3/12 A/n (the drilling row, k_d against J, is checked too). For a thin square element of side a this is m a^2 / y^2 (m = rho t
/// a^2 / 4 the nodal mass) with kappa G / E (y^2 + 2 y) = 4 / (1 - nu^2): m a^2 / 8.04 at nu = 0.3,
/// m a^2 / 7.76 at nu = 0.28. The rotary inertia grows with the element area, not with t^2 (the
/// physical m t^2 / 12), so the step stays Table 2-1's membrane value.
double rotational_inertia(const Constants& c, const Frame& reference, double nodal_mass, double table_dt,
                          bool triangle);

/// Table 2-1 shell step L_e / c_w on nodes x (quadrilateral: A / longest side; triangle, x[3] ==
/// x[2]: 2A / longest side; c_w the plate wave speed), through fem::cfl.
double critical_time_step(const ElasticMaterial& m, const std::array<Vec3, 4>& x, bool triangle);

}  // namespace fem::shellbt
