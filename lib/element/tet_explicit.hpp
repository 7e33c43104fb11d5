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
#include "element/hex8_explicit.hpp"

namespace fem::tet {

/// Reference data of an element with N nodes and Q integration points (computed once).
template <int N, int Q>
struct Reference {
    std::array<std::array<Vec3, N>, Q> dndx;  // dN_a/dX at point q
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
/// hexahedron (its hourglass_qm is not used).
template <int N, int Q>
void internal_force(const Reference<N, Q>& ref, const hex8::Hex8Material& mat, std::span<const Vec3> x,
                    std::span<const Vec3> v, Result<N>& out);

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
