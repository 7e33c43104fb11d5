#pragma once
// Explicit internal-force kernel of the 8-node hexahedron with one-point (uniform strain)
// integration and Flanagan-Belytschko (1981) stiffness hourglass control (LS-DYNA hourglass
// type 4/5 family). Used by the explicit solver (lib/explicit) every cycle.
//
// Formulation (chosen for rubber fingers: large rotations, large strains, nu = 0.49):
//  * Total Lagrangian. The uniform gradient B_a = integral over the reference element of dN_a/dX
//    (Flanagan-Belytschko's "mean" gradient, exact with 2x2x2 Gauss because adj(J) dN/dxi is at
//    most quadratic in each natural coordinate) is computed once. F = sum_a x_a (x) B_a / V0 is the
//    element's mean deformation gradient. Because sum_a X_a (x) B_a = V0 I exactly, any linear
//    displacement field gives its exact constant F, and the forces of a constant stress balance
//    at interior nodes of a distorted patch: the patch test is passed exactly.
//  * Material: compressible neo-Hookean, W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2, with
//    mu, lambda the Lame constants of the (E, nu) of fem::ElasticMaterial, so that it reduces to
//    the linear material of the thesis at small strain. It is hyperelastic (the internal energy is
//    a state function: no drift, exact energy bookkeeping), frame-indifferent (a rigid rotation
//    F = R gives W = 0 and no force: no spurious strain in a spinning finger), and stays
//    well-behaved at large compression (W -> infinity as J -> 0). With one integration point the
//    volumetric part is sampled once per element, so nu = 0.49 does not lock.
//  * Hourglass: gamma_alpha,a = h_alpha,a - (h_alpha . X) B_a / V0 (four vectors orthogonal to
//    every linear field, so rigid motions and the patch test are untouched); generalized hourglass
//    displacements q_alpha = sum_a gamma_alpha,a u_a; restoring force f_a = k sum gamma_alpha,a q_alpha with
//    stored energy k/2 |q|^2. The stiffness k = QM * 2 mu * sum_a |B_a|^2 / (8 V0) scales with the
//    shear modulus: FB 1981 scale with lambda + 2 mu, which over-stiffens nearly incompressible
//    rubber by (lambda + 2 mu) / 2 mu = 25 at nu = 0.49. The 1/8 normalizes the gamma vectors
//    (|h|^2 = 8). For a cube of side a this gives k = QM 0.375 mu a: with QM = 0.1 (LS-DYNA's default)
//    it is close to the exact stiffness mu a / 24 of a fully integrated cube in the transverse
//    (xi eta -> z) hourglass shape, and the hourglass frequency (omega^2 = 2.4 QM/0.1 mu / (rho a^2))
//    stays well below the dilatational omega_max of Table 2-1, so the step is not affected.
//    The hourglass force is expressed in the reference frame (total form): exact for rigid
//    rotations (they carry no hourglass displacement), approximate when large hourglass
//    deformation and large rotation combine - keep QM small and the mesh regular.
//  * Viscous stresses (bulk viscosity of Table 2-1 and stiffness-proportional Rayleigh damping
//    beta K of Eq 2-39) are added to the Cauchy stress from the velocity gradient.
#include <array>

#include "core/types.hpp"
#include "element/critical_time_step.hpp"
#include "material/elastic.hpp"

namespace fem::hex8 {

/// Reference geometry of one element, computed once (total Lagrangian).
struct Hex8Reference {
    std::array<Vec3, 8> B;         // integral of dN_a/dX over the reference volume [m^2]
    std::array<std::array<double, 8>, 4> gamma;  // hourglass shape vectors
    double volume = 0.0;           // V0
    double hourglass_norm = 0.0;   // sum_a |B_a|^2 / V0 [m]
};

/// Computes B_a, V0 and the gamma vectors from the reference coordinates. Throws InputError when
/// the element is inverted or degenerate (the message names `element_name`).
Hex8Reference make_reference(const std::array<Vec3, 8>& X, const char* element_name = "hex8");

/// Material constants the kernel needs, precomputed from an ElasticMaterial.
struct Hex8Material {
    double mu = 0.0, lambda = 0.0, density = 0.0;
    double hourglass_qm = 0.1;   // QM
    double rayleigh_beta = 0.0;  // beta of Eq 2-39 [s]
    BulkViscosity bulk{};
    bool bulk_viscosity = true;
    static Hex8Material from(const ElasticMaterial& m, double qm = 0.1, double beta = 0.0,
                             BulkViscosity q = {}, bool bulk_on = true);
};

/// What one evaluation of the element returns.
struct Hex8Result {
    std::array<Vec3, 8> force;   // internal (resisting) nodal forces, hourglass included
    double strain_energy = 0.0;  // V0 W(F)
    double hourglass_energy = 0.0;
    double viscous_power = 0.0;  // V sigma_visc : D (bulk viscosity + beta damping) [W]
    double volumetric_strain_rate = 0.0;  // tr D
    double jacobian = 1.0;       // det F
    double von_mises = 0.0;      // of the elastic Cauchy stress
    Mat3 cauchy = Mat3::Zero();  // elastic Cauchy stress
    bool inverted = false;       // det F <= 0: the forces are not computed
};

/// Internal forces of one element at nodal displacements u = x - X and velocities v. `length` is
/// the length used by the bulk viscosity; <= 0 takes the cube root of the current volume.
void internal_force(const Hex8Reference& ref, const Hex8Material& mat, const std::array<Vec3, 8>& u,
                    const std::array<Vec3, 8>& v, double length, Hex8Result& out);

/// Von Mises equivalent of a (symmetric) stress tensor.
double von_mises(const Mat3& s);

}  // namespace fem::hex8
