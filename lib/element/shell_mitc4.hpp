#pragma once
// MITC4: the 4-node shell element of Dvorkin and Bathe (1984) with assumed (mixed-interpolated)
// transverse shear strains, for thin steel plates and folded plate assemblies (the portal frame of
// thesis Sec 2.4.2, which the thesis models with ANSYS SHELL93).
//
// Kinematics (degenerated solid, linear):
//   x(r,s,z) = sum_k h_k(r,s) [ x_k + z t/2 V_k ]            z in [-1, 1] through the thickness
//   u(r,s,z) = sum_k h_k(r,s) [ u_k + z t/2 (theta_k x V_k) ]
// with V_k the unit normal (director) at node k of the possibly warped mid-surface, u_k and theta_k
// the nodal translations and rotations in GLOBAL axes (6 DOF per node: ux uy uz rx ry rz). The
// covariant strains are computed from this field; the transverse shear strains e_rz, e_sz are
// replaced by their values at the edge midpoints (tying points A, B, C, D), linearly interpolated
// across the element: this removes shear locking (a thin element bends like a Kirchhoff plate).
// Plane stress (sigma_33 = 0) in the local Cartesian frame of each integration point; transverse
// shear with the correction factor 5/6. Integration 2x2 in-plane, 2 points through the thickness.
//
// Drilling: the rotation about the director does not enter the kinematics. So that flat assemblies
// (coplanar elements meeting at a node) are not singular, a small penalty ties the drilling rotation
// theta_k . V_k at each node to the in-plane rotation of the membrane field there,
// (u_r . x_s - u_s . x_r) / (2 |x_r x x_s|); this is zero for every rigid-body motion, so the six
// rigid modes keep zero energy. Its stiffness is drilling_factor * G * t * A_k per node.
//
// DOF order: node 0 (ux uy uz rx ry rz), node 1, node 2, node 3. Nodes counter-clockwise seen from
// the side the normal points to (r: node 0 -> 1, s: node 0 -> 3).
#include <array>

#include <Eigen/Core>

#include "core/types.hpp"
#include "material/elastic.hpp"

namespace fem::shell {

using Mat24 = Eigen::Matrix<double, 24, 24>;

struct Mitc4Options {
    /// Drilling penalty relative to G t A_k (small: it must not stiffen the membrane noticeably).
    double drilling_factor = 1e-3;
    /// Rotary inertia of the lumped mass: rotary_inertia_scale * rho t^3/12 * A_k about each global
    /// axis. 1 is the physical rotary inertia of the plate; explicit codes scale it up so that the
    /// rotational modes do not control the time step.
    double rotary_inertia_scale = 1.0;
};

struct ShellMatrices {
    Mat24 stiffness;        // K, linear
    Mat24 consistent_mass;  // integral rho N^T N dV (translation + rotary inertia rho t^3/12), plus
                            // the drilling inertia rho t^3/12 A_k about V_k so that M is definite
    Mat24 lumped_mass;      // diagonal: rho t A_k per translation, scale * rho t^3/12 A_k per rotation
    double area = 0.0;      // mid-surface area
};

/// Element matrices from the four node coordinates (possibly warped), the thickness and the
/// material. Throws fem::InputError for a non-positive thickness, coincident nodes or a degenerate
/// or inverted (non-convex) element, naming the problem.
ShellMatrices mitc4_matrices(const std::array<Vec3, 4>& x, double thickness, const ElasticMaterial& material,
                             const Mitc4Options& options = {});

/// Unit normal (director) of the mid-surface at node k, as the element uses it.
std::array<Vec3, 4> mitc4_directors(const std::array<Vec3, 4>& x);

}  // namespace fem::shell
