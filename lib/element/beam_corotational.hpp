#pragma once
// Explicit internal-force kernel of a 3D two-node corotational Euler-Bernoulli beam (for slender
// wires such as the compliant beam of thesis Table 2-8, LS-DYNA's Belytschko-Schwer BEAM161 in the
// thesis), valid for large rotations with small strains.
//
// Formulation:
//  * Each node carries a rotation matrix R_i (its triad relative to the start of the run).
//  * The element frame E = [e1 e2 e3] follows the element: e1 along the current chord x2 - x1,
//    e2 from the mean of the two nodal triads' second axes made orthogonal to e1, e3 = e1 x e2.
//    Rigid motion of the element therefore leaves all local deformations at zero (no spurious
//    strain under large rotations).
//  * Local deformations: elongation l - L0, and the small local nodal rotations theta_i =
//    log(E^T R_i E0) (rotation of each nodal triad relative to the element frame).
//  * Local resultants from the linear Euler-Bernoulli stiffness: N = EA (l-L0)/L0, torsion
//    T = GJ (theta2x - theta1x)/L0, end moments M1 = EI/L0 (4 theta1 + 2 theta2), M2 = EI/L0 (2 theta1
//    + 4 theta2) in each bending plane, and end shears from moment equilibrium over the current
//    length, (M1 + M2)/l. The element forces are thus exactly self-equilibrated (zero net force and
//    moment) in every configuration. They are rotated back with E.
//  * Lumped mass rho A L/2 per node. Rotational inertia: the physical rho I L/2 is scaled up (as
//    LS-DYNA does for its beams) to the smallest isotropic value for which no rotational row of
//    the element's Gershgorin bound on omega_max exceeds the axial one, 2c/L; the critical step
//    then stays the Table 2-1 beam value L/c. Slender wires have the rotary inertia of an
//    Euler-Bernoulli beam negligible anyway (it is absent from the EB equation), so the scaling
//    does not change the bending frequencies measurably (tested).
#include <array>

#include "core/types.hpp"
#include "element/hex8_explicit.hpp"
#include "material/elastic.hpp"

namespace fem::beam {

/// Cross-section properties [m^2, m^4].
struct Section {
    double area = 0.0;
    double iy = 0.0;       // second moment about local y (bending in the local x-z plane)
    double iz = 0.0;       // second moment about local z (bending in the local x-y plane)
    double torsion = 0.0;  // torsion constant J
    /// Solid circular section of diameter d (the wire of Table 2-8).
    static Section circular(double diameter);
    /// Solid rectangle, width b along local y, height h along local z.
    static Section rectangular(double b, double h);
    void validate(const char* name) const;  // InputError when a value is not positive
};

/// Reference state of one element.
struct Reference {
    double length = 0.0;  // L0
    Mat3 frame0;          // initial element frame [e1 e2 e3]
};

/// e1 along b - a; e2 normal to e1, closest to `orientation` (when zero: to the global axis least
/// aligned with e1). Throws InputError when the element has zero length.
Reference make_reference(const Vec3& a, const Vec3& b, const Vec3& orientation = Vec3::Zero());

struct Result {
    Vec3 force[2];    // internal (resisting) forces on the nodes, global
    Vec3 moment[2];   // internal moments on the nodes, global
    double length = 0.0;  // current length l
    double strain_energy = 0.0;
    double axial_force = 0.0;
    double max_stress = 0.0;  // |N|/A + max bending stress (circular/rectangular fibre) for output
};

/// What the kernel needs of the section and the material for one element (computed once).
struct Stiffness {
    double length = 0.0;                // L0
    double axial = 0.0;                 // EA / L0
    double torsion = 0.0;               // GJ / L0
    double bend_y = 0.0, bend_z = 0.0;  // E Iy / L0, E Iz / L0
    double inv_area = 0.0;              // 1 / A, and outer fibre over second moment (c_y / Iy,
    double fibre_y = 0.0, fibre_z = 0.0;  // c_z / Iz) for the output stress
    static Stiffness of(const Reference& ref, const Section& s, const ElasticMaterial& m);
};

/// Internal forces at current positions x and nodal rotation matrices R.
void internal_force(const Reference& ref, const Stiffness& k, const Vec3& x1, const Vec3& x2, const Mat3& R1,
                    const Mat3& R2, Result& out);

// --- The per-cycle kernel (what the explicit solver's BeamGroup calls) ---------------------------
//
// hex8::kLanes elements per pass, one per lane, each doing exactly the operations of the one-element
// internal_force() above (which runs the same code with T = double): the same bits (fp-contract=off,
// no FMA in any clone; element/kernel_lanes.hpp). The small-rotation branch of the local rotation
// vector (the usual case) runs in the lanes; a lane that needs the general formula (asin or the
// angle-axis of a large local rotation) gets it alone, as the scalar path does.

/// Reference frame and stiffness in the kernel's layout: T = double for one element, T = Lanes for
/// kLanes elements.
template <class T>
struct alignas(sizeof(T)) PackedT {
    T frame0[3][3];  // initial element frame, frame0[i][j] = E0(i, j)
    T length, axial, torsion, bend_y, bend_z, inv_area, fibre_y, fibre_z;  // as Stiffness
};
using Packed = PackedT<double>;
using PackedBlock = PackedT<hex8::Lanes>;
Packed pack(const Reference& ref, const Stiffness& k);
void pack_lane(const Packed& p, int lane, PackedBlock& block);

/// What the kernel returns (per element, or per lane).
template <class T>
struct alignas(sizeof(T)) KernelResultT {
    T force[3];      // internal force on node 1 (node 2: the opposite)
    T moment[2][3];  // internal moments on nodes 1 and 2
    T length, strain_energy, axial_force, max_stress;  // as Result
};
using KernelResult = KernelResultT<double>;
using KernelResultBlock = KernelResultT<hex8::Lanes>;

/// Nodal positions x_n[i] and rotation matrices R_n[i][j] (node n = 1, 2 of the element).
void internal_force(const Packed& p, const double (&x1)[3], const double (&x2)[3], const double (&R1)[3][3],
                    const double (&R2)[3][3], KernelResult& out);
void internal_force(const PackedBlock& p, const hex8::Lanes (&x1)[3], const hex8::Lanes (&x2)[3],
                    const hex8::Lanes (&R1)[3][3], const hex8::Lanes (&R2)[3][3], KernelResultBlock& out);
/// The same with the stiffness computed from the section and material on each call (tests).
void internal_force(const Reference& ref, const Section& s, const ElasticMaterial& m, const Vec3& x1,
                    const Vec3& x2, const Mat3& R1, const Mat3& R2, Result& out);

/// Nodal triad update of the explicit solver: R <- exp([phi]x) R for the rotation vector phi = omega
/// dt (Rodrigues: exp([phi]x) = I + sin|phi|/|phi| [phi]x + (1 - cos|phi|)/|phi|^2 [phi]x^2, the two
/// factors by their Taylor series below |phi| = 0.01, where they are exact to round-off and cost no
/// libm call; a step turns a node by ~1e-6 rad).
void rotate(const Vec3& phi, Mat3& R);

/// Isotropic rotational inertia lumped at each node of one element (see the header comment).
double nodal_rotational_inertia(const Section& s, const ElasticMaterial& m, double length);
/// Physical (unscaled) value rho max(Iy + Iz, J) L / 2, for reporting the scaling.
double physical_rotational_inertia(const Section& s, const ElasticMaterial& m, double length);

/// Critical step of one element: Table 2-1's L/c (through fem::cfl::critical_time_step), or the
/// transverse Gershgorin bound 2/omega when a stubby element makes that smaller.
double critical_time_step(const Section& s, const ElasticMaterial& m, const Vec3& x1, const Vec3& x2);
/// The transverse Gershgorin bound 2/omega alone, for an element of length L whose nodes carry the
/// rotational inertia Jr (per element); the solver caches Jr and adds Table 2-1's L/c itself.
double transverse_time_step(const Section& s, const ElasticMaterial& m, double L, double Jr);

}  // namespace fem::beam
