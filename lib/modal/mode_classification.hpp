#pragma once
// What kind of deformation a mode shape of a slender body is (thesis Fig 3-3: "most of these mode
// shapes correspond to the bending deformation except mode 5 and 10 are due to torsion, and mode 9 is
// in elongation"), decided from the shape itself instead of by looking at a picture.
//
// Method. The body is cut into slices across its axis. In each slice the nodal displacements are
// fitted, in the mass-weighted least-squares sense, by the motions of a rigid cross-section:
//   in-plane   u_t = t + theta e_axis x (X - c)     (translation t: bending; rotation theta: torsion)
//   axial      w   = w0 + r1 (X - c).e1 + r2 (X - c).e2  (w0: elongation; r1, r2: the cross-section
//                                                          rotations that accompany bending)
// with c the slice's mass centre, so translation, twist and the three axial fields are mutually
// mass-orthogonal and the fitted "kinetic energies" sum_i m_i |u_fit,i|^2 split exactly into
//   bending    = |t|^2 terms + the r1, r2 terms,
//   torsion    = theta^2 terms,
//   elongation = w0^2 terms,
// and whatever the rigid-section fit leaves is "other" (cross-section distortion: breathing,
// ovalling). Each is reported as a fraction of sum_i m_i |u_i|^2 (the four add up to 1). The mode is
// the largest of the four; a bending mode also says in which plane it bends (axis-e1 or axis-e2),
// from the direction of its section translations.
//
// Works for any node cloud (hex, tet10 mid-edge nodes included) as long as each slice holds enough
// nodes spread over the cross-section to fix the six rigid-section parameters.
#include <span>
#include <string>
#include <vector>

#include "core/types.hpp"

namespace fem::modal {

enum class ModeType { Bending, Torsion, Elongation, Other };
std::string to_string(ModeType t);

struct ModeClassificationOptions {
    Vec3 origin = Vec3::Zero();          // a point on the body's axis
    Vec3 axis = Vec3::UnitZ();           // the body's axis (need not be unit length)
    Vec3 transverse = Vec3::UnitX();     // e1: first bending direction (made orthogonal to the axis)
    /// Number of slices along the axis; 0 = automatic (about one slice per 40 nodes, 4..60).
    int slices = 0;
};

struct ModeClassification {
    ModeType type = ModeType::Other;
    double bending = 0.0, torsion = 0.0, elongation = 0.0, other = 0.0;  // fractions, sum 1
    /// Bending modes: 1 when the section translations are mostly along e1 (bending in the axis-e1
    /// plane), 2 when along e2; 0 for other types.
    int bending_direction = 0;
    double bending_e1 = 0.0, bending_e2 = 0.0;  // the bending fraction's split by direction
    /// "bending (e1)", "bending (e2)", "torsion", "elongation", "other".
    std::string label() const;
};

/// Classifies the displacement field `u` (one vector per node, the mode shape's translations) of the
/// nodes at reference positions `x`, weighted by the nodal masses `weights` (empty: equal weights).
/// Nodes with zero weight and zero displacement (e.g. unused nodes) do not matter. Throws InputError
/// on size mismatch, a zero axis, a transverse direction parallel to the axis, negative weights, or
/// an all-zero displacement field.
ModeClassification classify_mode(std::span<const Vec3> x, std::span<const Vec3> u, std::span<const double> weights,
                                 const ModeClassificationOptions& options = {});

/// Same, with the displacements given flat as (ux, uy, uz) per node (AssembledSystem::translations).
ModeClassification classify_mode(std::span<const Vec3> x, std::span<const double> u_flat,
                                 std::span<const double> weights, const ModeClassificationOptions& options = {});

}  // namespace fem::modal
