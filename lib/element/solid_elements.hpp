#pragma once
// Linear solid elements for implicit (modal) analysis: the element stiffness K = int B^T D B dV and
// mass M = int rho N^T N dV (thesis Eq 2-36/2-38 need both) of the 8-node hexahedron and the 4- and
// 10-node tetrahedra. Three displacement DOFs per node, ordered ux, uy, uz node after node, so the matrices
// are 3n x 3n with n = 8 or 10. Node orders are the library's (mesh/element_shape.hpp): hex8 bottom
// face 0-3 counter-clockwise then the top face; tet10 corners 0-3 then the mid-edge nodes of edges
// 01, 12, 02, 03, 23, 13 (Gmsh order; CalculiX C3D10 and VTK swap the last two).
#include <span>

#include <Eigen/Core>

#include "core/types.hpp"
#include "material/elastic.hpp"

namespace fem::solid {

enum class MassKind {
    Consistent,  // int rho N^T N dV
    Lumped,      // diagonal: row sums for hex8; HRZ (diagonal scaled to the element mass) for tet10,
                 // because the row sums of the tet10 corner nodes are negative
};

/// Isotropic elasticity matrix D (6 x 6) in Voigt order xx, yy, zz, xy, yz, zx with engineering
/// shear strains.
Eigen::Matrix<double, 6, 6> elasticity_matrix(const ElasticMaterial& m);

/// Hex8 stiffness (24 x 24), 2x2x2 Gauss. With incompatible_modes the element gets the nine
/// Wilson-Taylor bubble modes (1 - xi^2 etc., statically condensed, with Taylor's centre-Jacobian
/// correction so the patch test passes): it then bends like a quadratic element instead of locking
/// in shear, which is what thin cantilever modes need. Without them it is the plain trilinear brick.
/// Throws InputError when the Jacobian is non-positive at an integration point.
Eigen::MatrixXd hex8_stiffness(std::span<const Vec3> x, const ElasticMaterial& m, bool incompatible_modes = true);

/// The same incompatible-modes brick with its nine bubble amplitudes kept as element DOFs instead of
/// condensed, as CalculiX's C3D8I keeps them (three extra nodes per element): 33 x 33 matrices, the
/// 24 nodal DOFs, then bubble 1 - xi^2 (x, y, z components), 1 - eta^2, 1 - zeta^2. The stiffness is
/// the one hex8_stiffness condenses (statically condensing this one gives hex8_stiffness exactly);
/// the mass is that of the whole displacement field, bubbles included, with the 2x2x2 rule as ccx
/// integrates it (shape8humass.f). The bubbles then carry mass, so in an eigenproblem this element
/// is more flexible than the condensed one (its frequencies are lower; tests/deck measures how much).
struct Hex8IncompatibleDofs {
    Eigen::MatrixXd stiffness, mass;  // 33 x 33
};
Hex8IncompatibleDofs hex8_incompatible_dofs(std::span<const Vec3> x, const ElasticMaterial& m);

/// Hex8 mass (24 x 24): consistent with 2x2x2 Gauss (exact for parallelepipeds) or lumped row sums.
Eigen::MatrixXd hex8_mass(std::span<const Vec3> x, double density, MassKind kind = MassKind::Consistent);

/// Tet10 stiffness (30 x 30) with the 4-point rule (degree 2: exact for straight-edged tets, the
/// rule CalculiX uses for C3D10). Throws InputError for a non-positive Jacobian.
Eigen::MatrixXd tet10_stiffness(std::span<const Vec3> x, const ElasticMaterial& m);

/// Quadrature rule for the tet10 consistent mass: N^T N is of degree 4.
enum class Tet10MassRule {
    Exact,      // conical-product rule exact to degree 7 (64 points): the true consistent mass
    FourPoint,  // the stiffness rule (degree 2), as some codes use: slightly underintegrated
};

/// Tet10 mass (30 x 30): consistent (rule above) or HRZ-lumped (positive masses: on a straight-edged
/// tet each corner node gets 1/36 and each mid-edge node 4/27 of the element mass).
Eigen::MatrixXd tet10_mass(std::span<const Vec3> x, double density, MassKind kind = MassKind::Consistent,
                           Tet10MassRule rule = Tet10MassRule::Exact);

/// Tet4 (constant-strain tetrahedron, CalculiX C3D4) stiffness (12 x 12), exact with one point.
/// Throws InputError for a non-positive volume.
Eigen::MatrixXd tet4_stiffness(std::span<const Vec3> x, const ElasticMaterial& m);
/// Quadrature rule for the tet4 consistent mass (N^T N is of degree 2).
enum class Tet4MassRule {
    Exact,     // rho V / 20 (1 + delta_ab)
    Centroid,  // the stiffness's one point, as CalculiX integrates C3D4 (e_c3d.f: the mass uses the
               // element's integration points): rho V / 16 in every entry, rank one per element
};
/// Tet4 mass (12 x 12): consistent (rule above), or lumped rho V / 4 per node.
Eigen::MatrixXd tet4_mass(std::span<const Vec3> x, double density, MassKind kind = MassKind::Consistent,
                          Tet4MassRule rule = Tet4MassRule::Exact);

/// Hex20 (20-node serendipity brick, CalculiX C3D20 / C3D20R; node order of ElementShape::Hex20)
/// stiffness (60 x 60): 3x3x3 Gauss (full), or 2x2x2 (reduced: the C3D20R rule, exact for a
/// parallelepiped's constant-strain states; it leaves one spurious zero-energy mode per element that
/// neighbours usually suppress). Throws InputError for a non-positive Jacobian.
Eigen::MatrixXd hex20_stiffness(std::span<const Vec3> x, const ElasticMaterial& m, bool reduced = false);
/// Hex20 mass (60 x 60): consistent with the stiffness rule (3x3x3 exact for parallelepipeds; 2x2x2
/// with reduced, as CalculiX integrates C3D20R's mass), or HRZ-lumped (the corner row sums are
/// negative, as for tet10).
Eigen::MatrixXd hex20_mass(std::span<const Vec3> x, double density, MassKind kind = MassKind::Consistent,
                           bool reduced = false);

/// Volumes by the element's own mapping (for mass checks).
double hex8_volume(std::span<const Vec3> x);
double tet10_volume(std::span<const Vec3> x);

}  // namespace fem::solid
