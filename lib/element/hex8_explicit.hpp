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
    std::array<Vec3, 4> hourglass_base;  // sum_a h_alpha,a X_a: gamma_alpha,a = h_alpha,a - hourglass_base . B_a / V0
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
    double wave_speed = 0.0;     // sqrt((lambda + 2 mu) / rho), set by from(): used by the bulk viscosity
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

// --- The per-cycle kernel (what the explicit solver's Hex8Group calls) ---------------------------
//
// The same formulation as internal_force() above, organized for speed: plain fixed-size arrays
// with the 8 nodes contiguous per component (x[i][a] = component i of node a), no allocation, the
// hourglass control folded into the stress (below), von Mises kept squared (the sqrt is taken only
// when a stress is output). Results equal internal_force()'s to round-off (tests/explicit).
//
// Hourglass folding: with gamma_alpha,a = h_alpha,a - (hX_alpha . B_a) / V0 and hX_alpha =
// sum_a h_alpha,a X_a (Hex8Reference::hourglass_base),
//   q_alpha = sum_a gamma_alpha,a u_a = sum_a h_alpha,a u_a - H hX_alpha              (H = F - I)
//   sum_alpha gamma_alpha,a k q_alpha = sum_alpha h_alpha,a k q_alpha - (k/V0) (sum_alpha q_alpha (x) hX_alpha) B_a,
// so the second part joins the stress term P B_a and h (entries +-1) needs no storage.

/// Eight elements processed together, one per lane (GCC/Clang vector extension). Each lane does
/// exactly the scalar kernel's operations in the same order (element-wise IEEE arithmetic, no
/// reassociation, no contraction into FMAs: the .cpp sets fp-contract=off), so
/// batching changes no bit. The block functions are compiled for AVX-512, AVX2 and baseline x86-64
/// and chosen at load time (see the .cpp): one AVX-512 instruction per Lanes operation, two with
/// AVX2, four with SSE2. Batching elements, not nodes, needs no shuffles.
/// Alignment: the baseline and AVX2 versions align this 64-byte type to less than 64 bytes, while
/// the AVX-512 version of the kernel loads it with aligned moves. So every Lanes object handed to
/// the kernel must be 64-byte aligned: the structs below are alignas(64) for T = Lanes, and callers
/// declare their Lanes arrays alignas(kLanesAlign).
using Lanes = double __attribute__((vector_size(64)));
inline constexpr int kLanes = 8;
inline constexpr int kLanesAlign = 64;

/// Reference data in the kernel's layout: T = double for one element (312 bytes), T = Lanes for
/// kLanes elements (component i of node a of element lane l at B[i][a][l]).
template <class T>
struct alignas(sizeof(T)) Hex8PackedT {
    T B[3][8];      // B[i][a] = component i of B_a [m^2]
    T hx[4][3];     // hourglass_base[alpha][i] [m]
    T volume;       // V0 [m^3]
    T hourglass_k;  // stiffness k = QM 2 mu sum_a |B_a|^2 / (8 V0) [N/m]
    T length0;      // cube root of V0 [m] (bulk viscosity length cbrt(J V0) = length0 cbrt(J))
};
using Hex8Packed = Hex8PackedT<double>;
using Hex8PackedBlock = Hex8PackedT<Lanes>;
Hex8Packed pack(const Hex8Reference& ref, const Hex8Material& mat);
/// Puts one element's data `p` into lane `lane` of a block.
void pack_lane(const Hex8Packed& p, int lane, Hex8PackedBlock& block);

/// What the kernel returns (per element, or per lane).
template <class T>
struct alignas(sizeof(T)) Hex8KernelResultT {
    T f[3][8];                 // internal forces f[i][a], hourglass included
    T strain_energy;           // V0 W(F)
    T hourglass_energy;
    T viscous_power;           // as Hex8Result
    T volumetric_strain_rate;  // tr D
    T jacobian;                // det F; <= 0: inverted, the other outputs are meaningless
    T von_mises_sq;            // square of the von Mises stress of the elastic Cauchy stress
    T H[3][3];                 // displacement gradient F - I
    T ln_j;                    // ln det F
    T fv[3][8];                // the viscous part of f (bulk viscosity + beta damping), filled only
                               // when asked for (viscous_forces = true); f includes it either way
};
using Hex8KernelResult = Hex8KernelResultT<double>;
using Hex8KernelResultBlock = Hex8KernelResultT<Lanes>;
static_assert(alignof(Hex8PackedBlock) == kLanesAlign && alignof(Hex8KernelResultBlock) == kLanesAlign);

/// Internal forces from the nodal displacements u[i][a] = x - X and velocities v[i][a]. `length`
/// as in internal_force() (<= 0: cube root of the current volume J V0); the block version always
/// uses the cube root.
void internal_force(const Hex8Packed& p, const Hex8Material& mat, const double (&u)[3][8], const double (&v)[3][8],
                    double length, Hex8KernelResult& out, bool viscous_forces = false);
void internal_force(const Hex8PackedBlock& p, const Hex8Material& mat, const Lanes (&u)[3][8], const Lanes (&v)[3][8],
                    Hex8KernelResultBlock& out, bool viscous_forces = false);

/// ln(1 + x) as the kernel computes ln J = log1p(J - 1) (x > -1): a vectorizable log1p, within
/// 2 ulp of std::log1p (tests/explicit).
double kernel_log1p(double x);

/// Exact volume of the trilinear hexahedron with nodes x[i][a] (node order of internal_force).
/// Closed form of the integral of det J over the natural cube (see the .cpp); equals the 2x2x2
/// Gauss volume of fem::cfl::hexahedron_length and Flanagan-Belytschko's sum_a b_a . x_a / 3.
double exact_volume(const double (&x)[3][8]);

/// Table 2-1 characteristic length of the hexahedron, V_e / A_emax (largest face area as
/// fem::cfl::hexahedron_length: half the norm of the cross product of the face diagonals), from
/// the current nodes x[i][a]. Equals fem::cfl::hexahedron_length to round-off, at a fraction of
/// its cost (no Gauss loop, one square root).
double characteristic_length(const double (&x)[3][8]);
void characteristic_length(const Lanes (&x)[3][8], Lanes& length);

/// Table 2-1 critical step of the hexahedra of a block on their current nodes x[i][a]:
/// fem::cfl::solid_time_step(characteristic_length(x), wave_speed, trD, bulk) per lane, the same
/// operations in the same order (same bits), with trD the volumetric strain rate of the kernel
/// (pass zeros when the bulk viscosity is off).
void critical_time_step(const Lanes (&x)[3][8], const Lanes& trD, double wave_speed, const BulkViscosity& bulk,
                        Lanes& dt);

// The nodal coordinates x, displacements u = x - X and velocities v of kLanes elements, gathered into
// lanes: node a's component i of the element in lane l at [i][a][l]. xs, Xs, vs are node-major (3
// doubles per node), conn[l] the nodes of the element in lane l; lanes at and beyond `lanes` repeat
// the last element. With AVX-512 the lanes' (x, y, z) triples are transposed in registers and each
// lane vector is stored whole; scalar stores into the lanes, read back at once by the kernel's vector
// loads, stall the store-to-load forwarding (rotating_finger_contact: -11 % CPU per case). Data
// movement and one IEEE subtraction per lane either way: the same bits.
void gather(const double* xs, const double* Xs, const double* vs, const std::array<int, 8>* conn, int lanes,
            Lanes (&x)[3][8], Lanes (&u)[3][8], Lanes (&v)[3][8]);

/// Convenience overloads on an array of points (tests; the solver's flattest-hexahedron survey).
double exact_volume(const std::array<Vec3, 8>& x);
double characteristic_length(const std::array<Vec3, 8>& x);

}  // namespace fem::hex8
