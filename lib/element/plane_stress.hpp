#pragma once
// Plane-stress continuum elements of constant thickness: the 4-node bilinear quadrilateral (2x2
// Gauss points) and the 8-node serendipity quadrilateral (3x3 Gauss points, like ANSYS PLANE82,
// which the thesis uses for the topology optimizations of Sec 2.6). The element lies in the x-y
// plane (z of the nodes is ignored); two DOF per node, ordered (u1, v1, u2, v2, ...); node order
// as in mesh/element_shape.hpp (corners counter-clockwise, then mid-side nodes 01, 12, 23, 30).
//
//   K_e = t * sum_g  B^T D B  det J  w_g,   D = E / (1 - nu^2) [1 nu 0; nu 1 0; 0 0 (1 - nu)/2]
#include <span>

#include <Eigen/Dense>

#include "core/types.hpp"
#include "mesh/element_shape.hpp"

namespace fem::plane {

/// Plane-stress elasticity matrix (engineering shear strain). Throws InputError for E <= 0 or nu
/// outside (-1, 0.5).
Eigen::Matrix3d plane_stress_matrix(double youngs_modulus, double poissons_ratio);

/// Shape functions N (n) and their derivatives dN/dxi, dN/deta (n x 2) of a Quad4 or Quad8 at the
/// parametric point (xi, eta) in [-1, 1]^2.
void shape_functions(ElementShape shape, double xi, double eta, Eigen::VectorXd& N, Eigen::MatrixXd& dN);

/// Strain-displacement matrix B (3 x 2n: eps_xx, eps_yy, gamma_xy) at (xi, eta); returns det J.
/// Throws InputError when det J <= 0 (inverted or degenerate element).
double strain_displacement(ElementShape shape, std::span<const Vec3> x, double xi, double eta,
                           Eigen::MatrixXd& B);

/// Stiffness matrix (2n x 2n) of a plane-stress Quad4 (2x2 Gauss) or Quad8 (3x3 Gauss) element of
/// thickness t. Throws InputError for another shape, t <= 0, or an inverted element.
Eigen::MatrixXd stiffness(ElementShape shape, std::span<const Vec3> x, double youngs_modulus,
                          double poissons_ratio, double thickness);

/// Area of the element (integral of det J with the element's Gauss rule: exact for straight edges).
double area(ElementShape shape, std::span<const Vec3> x);

/// Number of Gauss points per direction the element uses (2 for Quad4, 3 for Quad8).
int gauss_order(ElementShape shape);

}  // namespace fem::plane
