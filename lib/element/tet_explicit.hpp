#pragma once
// Explicit internal-force kernels of the 4-node (constant strain) and 10-node (quadratic)
// tetrahedra, for the tetrahedral finger meshes from Gmsh (thesis Cases C and D). Used by
// explicit/tet_groups.hpp every cycle.
//
// Formulation (the hexahedron's, element/hex8_explicit.hpp, without hourglass control, which
// tetrahedra do not need: they are fully integrated):
//  * Total Lagrangian. The gradients dN_a/dX and weights w_q det J0 at the integration points are
//    computed once on the reference geometry. F = sum_a x_a (x) dN_a/dX at every point. Tet4: one
//    point (exact: N is linear). Tet10: the 4-point rule of degree 2 (the rule of
//    fem::solid::tet10_stiffness and CalculiX C3D10; exact for the linear stiffness of a
//    straight-edged element). An isoparametric element reproduces any linear displacement field
//    exactly, so the patch test is passed at every integration point, curved edges included.
//  * Material: the hexahedron's compressible neo-Hookean law W = mu/2 (I1 - 3) - mu ln J +
//    lambda/2 (ln J)^2 with the Lame constants of fem::ElasticMaterial (hex8::Hex8Material::from,
//    so both elements use the same constants), P = mu (F - F^-T) + lambda ln J F^-T. Hyperelastic,
//    frame indifferent (a rigid rotation stores no energy).
//  * Viscous stresses: bulk viscosity of Table 2-1 (compression only, length = cube root of the
//    current volume J V0 of the element) and stiffness-proportional damping beta (2 mu D +
//    lambda tr D I) of Eq 2-39, as in the hexahedron.
//  * Nodal forces f_a = sum_q w_q det J0 P_q dN_a/dX (internal, resisting).
//
// Node order (mesh/element_shape.hpp, Gmsh): corners 0-3, then the mid-edge nodes of edges 01, 12,
// 20, 03, 23, 13.
#include <array>
#include <span>

#include <Eigen/Core>

#include "core/types.hpp"
#include "element/critical_time_step.hpp"
#include "element/hex8_explicit.hpp"

namespace fem::tet {

/// Reference data of an element with N nodes and Q integration points (computed once).
template <int N, int Q>
struct Reference {
    std::array<std::array<Vec3, N>, Q> dndx;  // dN_a/dX at point q
    std::array<Mat3, Q> jinv;                 // J0^-1 at point q (J0 = dX/dxi): dN_a/dX = J0^-T dN_a/dxi
    std::array<double, Q> weight{};           // w_q det J0 (sums to V0)
    double volume = 0.0;                      // V0
};
using Tet4Reference = Reference<4, 1>;
using Tet10Reference = Reference<10, 4>;

/// Reference data from the element's reference coordinates X (N points). Throws InputError naming
/// `element_name` when det J0 <= 0 at an integration point (inverted or degenerate element).
Tet4Reference make_tet4_reference(std::span<const Vec3> X, const char* element_name = "tet4");
Tet10Reference make_tet10_reference(std::span<const Vec3> X, const char* element_name = "tet10");

/// What one evaluation of an element returns.
template <int N>
struct Result {
    std::array<Vec3, N> force;         // internal (resisting) nodal forces
    std::array<Vec3, N> viscous_force; // the viscous part of `force` (bulk viscosity, beta damping)
    double strain_energy = 0.0;        // sum_q w_q W(F_q)
    double viscous_power = 0.0;        // sum_q w_q J sigma_visc : D [W]
    double volumetric_strain_rate = 0.0;  // tr D, averaged over the current volume
    double min_jacobian = 1.0;         // smallest det F over the points; <= 0: inverted (no forces)
    Mat3 cauchy = Mat3::Zero();        // elastic Cauchy stress averaged over the current volume
    double von_mises = 0.0;            // of `cauchy`
};

/// Internal forces at current coordinates x and velocities v (N each). `mat` as for the
/// hexahedron (its hourglass_qm is not used). The direct, readable form (Eigen, one element): the
/// reference the per-cycle kernel below is tested against.
template <int N, int Q>
void internal_force(const Reference<N, Q>& ref, const hex8::Hex8Material& mat, std::span<const Vec3> x,
                    std::span<const Vec3> v, Result<N>& out);

// --- The per-cycle kernel (what the explicit solver's tet groups call) ----------------------------
//
// The same formulation as internal_force() above, organized for speed as the hexahedron's
// (hex8_explicit.hpp): plain arrays with the nodes contiguous per component, kLanes elements per
// pass (one per lane, each doing exactly the one-element operations: the same bits), the material
// point shared with the hexahedron (displacement gradient H = F - I from the displacements, ln J by
// a vectorizable log1p, the bulk-viscosity length cbrt(J V0) = cbrt(V0) cbrt(J)), von Mises kept
// squared. Results equal internal_force()'s to round-off (tests/explicit).
//
// Gradients in barycentric form. With the natural coordinates xi_k = L_{k+1} (L_0 = 1 - sum), the
// element stores per point only A = J0^-1 (9 numbers, not the 3N of dN/dX) and
//   H = G A,  G_ik = sum_a u_a,i dN_a/dxi_k = c_{k+1},i - c_0,i,  c_m = sum_a u_a dN_a/dL_m,
//   f_a = sum_m dN_a/dL_m s_m,  s_{k+1} = column k of S = w P A^T,  s_0 = -(s_1 + s_2 + s_3),
// where dN_a/dL_m are constants of the point: tet10 corner m: 4 L_m - 1, mid-edge node of edge
// (i, j): 4 L_j for m = i and 4 L_i for m = j (N = L_i (2 L_i - 1), 4 L_i L_j); tet4: N_m = L_m.

/// Reference data in the kernel's layout: T = double for one element, T = Lanes for kLanes elements
/// (entry [..][l] for the element in lane l).
template <int Q, class T>
struct alignas(sizeof(T)) TetPackedT {
    T A[Q][3][3];  // J0^-1 at point q: A[q][k][j] = d xi_k / d X_j
    T weight[Q];   // w_q det J0 [m^3]
    T length0;     // cube root of V0 [m] (bulk viscosity length cbrt(J V0) = length0 cbrt(J))
};
template <int Q>
using TetPacked = TetPackedT<Q, double>;
template <int Q>
using TetPackedBlock = TetPackedT<Q, hex8::Lanes>;
template <int N, int Q>
TetPacked<Q> pack(const Reference<N, Q>& ref);
/// A straight-sided tet10 (every mid-edge node at its edge's midpoint, to `kStraightTolerance` of
/// the edge length) has a constant reference Jacobian J0 (its geometry is the corner tetrahedron's),
/// so its 4 points share one J0^-1 and one weight: packed as TetPacked<1> (11 instead of 41 doubles,
/// the kernel's largest memory stream). The forces differ from pack()'s by round-off only (the four
/// J0 computed at the points are equal to ~1e-16). Curved (Gmsh boundary) tet10s keep pack().
inline constexpr double kStraightTolerance = 1e-12;
bool straight_sided(std::span<const Vec3> X);
TetPacked<1> pack_straight(const Reference<10, 4>& ref);
/// Puts one element's data `p` into lane `lane` of a block.
template <int Q>
void pack_lane(const TetPacked<Q>& p, int lane, TetPackedBlock<Q>& block);

/// What the kernel returns (per element, or per lane).
template <int N, class T>
struct alignas(sizeof(T)) TetKernelResultT {
    T f[3][N];                 // internal forces f[i][a]
    T fv[3][N];                // their viscous part (bulk viscosity, beta damping): only when asked for
    T strain_energy;           // sum_q w_q W(F_q)
    T viscous_power;           // sum_q w_q J_q sigma_visc : D
    T volumetric_strain_rate;  // tr D averaged over the current volume
    T min_jacobian;            // smallest det F over the points; <= 0: inverted (the rest is meaningless)
    T von_mises_sq;            // squared von Mises stress of the elastic Cauchy stress averaged over the current volume
};
template <int N>
using TetKernelResult = TetKernelResultT<N, double>;
template <int N>
using TetKernelResultBlock = TetKernelResultT<N, hex8::Lanes>;

/// Internal forces from the nodal displacements u[i][a] = x - X and velocities v[i][a] (node order
/// of the element); the viscous part also in out.fv when `viscous_forces`.
void internal_force(const TetPacked<1>& p, const hex8::Hex8Material& mat, const double (&u)[3][4],
                    const double (&v)[3][4], TetKernelResult<4>& out, bool viscous_forces = false);
void internal_force(const TetPackedBlock<1>& p, const hex8::Hex8Material& mat, const hex8::Lanes (&u)[3][4],
                    const hex8::Lanes (&v)[3][4], TetKernelResultBlock<4>& out, bool viscous_forces = false);
void internal_force(const TetPacked<4>& p, const hex8::Hex8Material& mat, const double (&u)[3][10],
                    const double (&v)[3][10], TetKernelResult<10>& out, bool viscous_forces = false);
void internal_force(const TetPackedBlock<4>& p, const hex8::Hex8Material& mat, const hex8::Lanes (&u)[3][10],
                    const hex8::Lanes (&v)[3][10], TetKernelResultBlock<10>& out, bool viscous_forces = false);
/// The straight-sided tet10 (pack_straight): the 4 points with the one packed J0^-1 and weight.
void internal_force(const TetPacked<1>& p, const hex8::Hex8Material& mat, const double (&u)[3][10],
                    const double (&v)[3][10], TetKernelResult<10>& out, bool viscous_forces = false);
void internal_force(const TetPackedBlock<1>& p, const hex8::Hex8Material& mat, const hex8::Lanes (&u)[3][10],
                    const hex8::Lanes (&v)[3][10], TetKernelResultBlock<10>& out, bool viscous_forces = false);

/// The corner coordinates x (nodes 0-3, for the Table 2-1 step), displacements u = x - X and
/// velocities v of the N nodes of kLanes elements, gathered into lanes: component i of node a of the
/// element in lane l at [i][a][l]. xs, Xs, vs are node-major (3 doubles per node), conn[l] the nodes
/// of the element in lane l; lanes at and beyond `lanes` repeat the last element. With AVX-512 each
/// node's (x, y, z) triples of the eight lanes are transposed in registers and the lane vectors
/// stored whole (scalar stores into lanes that the kernel reads back at once as vectors stall the
/// store-to-load forwarding: hex8::gather, whose method this is). Data movement and one IEEE
/// subtraction per lane either way: the same bits.
template <int N>
void gather(const double* xs, const double* Xs, const double* vs, const std::array<int, N>* conn, int lanes,
            hex8::Lanes (&x)[3][4], hex8::Lanes (&u)[3][N], hex8::Lanes (&v)[3][N]);

/// Table 2-1 critical step of the tetrahedra of a block on their current corner nodes x[i][a]
/// (a = 0..3): fem::cfl::solid_time_step(fem::cfl::tetrahedron_length(x), wave_speed, trD, bulk)
/// per lane, to round-off, with trD the kernel's volumetric strain rate (zeros when the bulk
/// viscosity is off).
void critical_time_step(const hex8::Lanes (&x)[3][4], const hex8::Lanes& trD, double wave_speed,
                        const BulkViscosity& bulk, hex8::Lanes& dt);
/// Table 2-1 length (minimum altitude 3 V / largest face area) of one tetrahedron, the kernel's way.
double characteristic_length(const double (&x)[3][4]);

/// The tet10's Table 2-1 step on its current deformation as the element feels it: the length is the
/// smallest, over the 4 integration points, altitude of the corner tetrahedron mapped by the
/// current Jacobian at the point, J_q = J0 + du/dxi (J0: the corner tetrahedron's edges, the exact
/// reference Jacobian of a straight-sided element). Why not the current corners' altitude (the tet4's
/// rule): a tet10's forces, hence its stiffness and highest frequency, depend on the deformation at
/// its 4 points only, while its corners alone can flatten with small strain when its edges curve; a
/// sliver of the grasp model's bird (chicken_shackling Step 3) had 0.57 of its corner volume, det F
/// 0.99-1.01 at its points and 0.14 MPa, and the corner rule cut the whole model's step from 2.6 to
/// 1.45 us (tests/explicit: its highest frequency follows this length, not the corners'). For an
/// affine deformation the two lengths are equal (to round-off), and at rest both are the Table 2-1
/// length of the corner tetrahedron. x: the corner coordinates, u: the displacements of the 10 nodes.
void critical_time_step_tet10(const hex8::Lanes (&x)[3][4], const hex8::Lanes (&u)[3][10], const hex8::Lanes& trD,
                              double wave_speed, const BulkViscosity& bulk, hex8::Lanes& dt);
/// That length for one element (x: corners, u: the 10 nodes' displacements).
double characteristic_length_tet10(const double (&x)[3][4], const double (&u)[3][10]);

/// Tangent stiffness of the element at the reference state (3N x 3N, DOFs ux, uy, uz node after
/// node): the linearized neo-Hookean law is linear elasticity with the same lambda, mu, so this is
/// int B^T D B dV by the element's own rule (equal to fem::solid::tet10_stiffness for tet10).
template <int N, int Q>
Eigen::MatrixXd linear_stiffness(const Reference<N, Q>& ref, const hex8::Hex8Material& mat);

/// Lumped nodal masses (per node, one value for the three directions).
///  Tet4: rho V0 / 4 per node (row sums of the consistent mass).
///  Tet10: HRZ lumping (Hinton-Rock-Zienkiewicz 1976: the diagonal of the consistent mass scaled
///  to the element mass), taken from fem::solid::tet10_mass(..., MassKind::Lumped). On a straight-
///  edged element the consistent diagonal is rho V0 (6/420) at a corner and rho V0 (32/420) at a
///  mid-edge node; their sum over the ten nodes is 216/420, so HRZ gives corners 6/216 = 1/36 and
///  mid-edge nodes 32/216 = 4/27 of the element mass (4/36 + 24/27 = 1). Curved elements (Gmsh
///  puts boundary mid-edge nodes on the CAD surface) get their own HRZ values.
std::array<double, 4> tet4_lumped_mass(std::span<const Vec3> X, double density);
std::array<double, 10> tet10_lumped_mass(std::span<const Vec3> X, double density);

/// Largest natural frequency omega_e of the element alone (free, lumped mass m, stiffness K):
/// omega_e^2 = lambda_max(M^-1/2 K M^-1/2). By the element eigenvalue inequality (Irons; Hughes,
/// The Finite Element Method, Sec 9.1.5), the assembled lumped-mass system has omega_max <=
/// max_e omega_e, so dt = 2 / max_e omega_e is a guaranteed stable step of the linearized system.
double element_omega_max(const Eigen::MatrixXd& stiffness, std::span<const double> nodal_mass);

}  // namespace fem::tet
