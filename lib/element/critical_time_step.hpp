#pragma once
// Element critical time step, thesis Table 2-1 (after Hallquist 1998, LS-DYNA Theory Manual):
//
//   element           characteristic length L_e        wave speed c_w          critical step
//   beam              element length                   sqrt(E/rho)             L_e / c_w
//   quad shell        A / max(L1..L4)                  sqrt(E/(rho(1-nu^2)))   L_e / c_w
//   triangular shell  2A / max(L1..L3)                 sqrt(E/(rho(1-nu^2)))   L_e / c_w
//   hexahedron        V_e / A_emax (largest face)      dilatational            L_e / (Q + sqrt(Q^2 + c_w^2))
//   tetrahedron       minimum altitude                 dilatational            L_e / (Q + sqrt(Q^2 + c_w^2))
//
// with the bulk-viscosity term Q = C1 c_w + C0 L_e |eps_kk| when the volumetric strain rate
// eps_kk < 0 (compression) and Q = 0 otherwise. The explicit solver calls critical_time_step() on
// every element's current coordinates each cycle (Eq 2-27 takes 0.9 x the minimum), so the
// functions are allocation-free and take the nodes as a span of points.
#include <array>
#include <span>

#include "core/types.hpp"
#include "mesh/element_shape.hpp"
#include "material/elastic.hpp"

namespace fem {

/// Bulk-viscosity coefficients of Table 2-1: C0 quadratic, C1 linear. The defaults are LS-DYNA's
/// *CONTROL_BULK_VISCOSITY defaults (Q1 = 1.5, Q2 = 0.06), which the thesis ran with.
struct BulkViscosity {
    double quadratic = 1.5;  // C0
    double linear = 0.06;    // C1
};

namespace cfl {

// --- characteristic lengths (Table 2-1, third column) --------------------------------------------

/// Beam: the element length.
double beam_length(const Vec3& a, const Vec3& b);

/// Triangular shell: 2A / longest side.
double triangle_shell_length(const std::array<Vec3, 3>& x);

/// Quadrangular shell: A / longest side. A is the area of the (possibly warped) quadrilateral,
/// half the norm of the cross product of its diagonals.
double quad_shell_length(const std::array<Vec3, 4>& x);

/// Hexahedron: V_e / A_emax. V_e is the exact volume of the trilinear element (2x2x2 Gauss
/// integration of det J is exact for it); face areas as for the quadrangular shell. Node order is
/// the usual one: 0-3 the bottom face counter-clockwise seen from the top, 4-7 above them.
double hexahedron_length(const std::array<Vec3, 8>& x);

/// Tetrahedron: the minimum altitude, 3 V / (largest face area).
double tetrahedron_length(const std::array<Vec3, 4>& x);

/// 10-node tetrahedron (Gmsh order: corners 0-3, mid-edge nodes on edges 01, 12, 20, 03, 23, 13) read
/// as the eight straight 4-node tetrahedra its nodes span: one at each corner, four filling the inner
/// octahedron split along its shortest diagonal. Returns the smallest of their minimum altitudes.
/// Not Table 2-1's rule (which this library keeps for tet10: the corner tetrahedron's altitude), but
/// the candidate for the tet10 step rule of the thesis's LS-DYNA runs that finger_damping examines
/// (Table 3-2 Cases C and D; README "Table 3-2: the tet10 time step"). For a regular tetrahedron of
/// edge a it is a / (2 sqrt 2) (an octahedron piece), 0.433 x the corner altitude a sqrt(2/3).
double tet10_subtetrahedron_length(std::span<const Vec3> nodes);

/// Characteristic length for any shape from its nodes (corner nodes for Quad8/Tet10).
double characteristic_length(ElementShape shape, std::span<const Vec3> nodes);

// --- critical time steps (Table 2-1, second column) ----------------------------------------------

/// Beams and shells: L_e / c_w (Eq 2-26).
double time_step(double length, double wave_speed);

/// Solids with bulk viscosity: L_e / (Q + sqrt(Q^2 + c_w^2)).
double solid_time_step(double length, double wave_speed, double volumetric_strain_rate,
                       const BulkViscosity& q);

/// Table 2-1's solid step in compression at a vanishing strain rate (Q = C1 c) over L_e / c:
/// sqrt(1 + C1^2) - C1 (0.942 for LS-DYNA's C1 = 0.06).
double compression_step_factor(double linear);

/// How far a flat hexahedron's bulk viscosity shortens its stable step below Table 2-1's, as a
/// factor <= 1 of the Table 2-1 step in compression, (L_e / c)(sqrt(1 + C1^2) - C1). The viscosity's
/// pressure acts over l = cbrt(V) (LS-DYNA's length for solids), the step over L_e = V / A_max; the
/// element's axial mode then has the damping ratio xi = C1 max(1, (l / L_e) / 2) (half the 1-D ratio
/// C1 l / L_e: the viscosity acts in compression only) and the damped limit (L_e / c)(sqrt(1 + xi^2)
/// - xi). So the factor is 1 up to l / L_e = 2 and falls below beyond: 0.90 at 5.5 with C1 = 0.06,
/// where a run at dt_scale 0.9 goes unstable (lib/explicit/README.md, "Flat hexahedra and bulk
/// viscosity": the model predicts 61 of 63 measured cases, the other two within 0.3 %).
double flat_hexahedron_step_factor(double length_ratio, double linear);

/// The wave speed Table 2-1 uses for a shape: bar, plate or dilatational.
double wave_speed(ElementShape shape, const ElasticMaterial& m);

/// The function the explicit solver calls for each element each cycle: the critical time step of
/// an element with these current nodal coordinates and this material. `volumetric_strain_rate` is
/// eps_kk (only solids use it, and only when negative).
double critical_time_step(ElementShape shape, std::span<const Vec3> nodes, const ElasticMaterial& m,
                          double volumetric_strain_rate = 0.0, const BulkViscosity& q = {});

/// Selective mass scaling (thesis Sec 2.3.5, observation 4): dt ~ sqrt(rho), so multiplying an
/// element's density by (dt_target / dt)^2 lifts its critical step to dt_target. Returns 1 when the
/// element already meets the target.
double density_scale_for_time_step(double dt_element, double dt_target);

}  // namespace cfl
}  // namespace fem
