#pragma once
// The compliant robotic hand of thesis Ch 4 (Sec 4.2, Fig 4-1, Table 4-1): a rigid stepped drum
// turning about the vertical y axis and carrying rubber fingers, each given by one row of Table 4-1.
// Everything here is plain data that a case-file reader can fill one key per field (issue 11,
// item 6), plus the geometry that follows from it (where each finger sits, its mesh).
//
// Frame (THESIS_CH4_5.md Sec 9 items 1-4, reconstructed; README of studies/football_sweep):
//   - origin at the centre of the drum's bottom face, y vertical and up, the drum axis along y;
//   - the object side of the drum is +z (the symmetry plane of the half model is z = 184 mm);
//   - a finger's angular position phi is measured from -z (finger D at t = 0, theta_f = 0) in the
//     drum's sense of rotation; its radial direction is e_r(phi) = (sin phi, 0, -cos phi) and its
//     direction of motion e_t(phi) = (cos phi, 0, sin phi). The drum turns at omega about -y
//     (signed angular velocity about +y is -omega), so on the object side (phi = 180 deg) the
//     fingers move in -x, with the conveyor flow;
//   - theta_f: phi(0) = -theta_f (theta_sign = -1 by default): a negative theta_f (A, C) is ahead in
//     the rotation, "leading" (Sec 9 item 2: the only reading that puts the Ch 5 finger tips where
//     the text says they are; the mirror reading is theta_sign = +1);
//   - finger-local frame: x' = e_r (the finger axis), y' = global y, z' = e_t. At R_x = R_z = 0 the
//     cross-section's major axis (2a = 24 mm) lies along y', so the soft bending direction is
//     tangential. R_x rolls the section about x' (right-hand rule, roll_sign = +1; the mirror case is
//     roll_sign = -1), then R_z pitches the finger about z' (+ lifts the tip);
//   - the root face's centre is at radius r_drum and height h_f; the finger leaves the drum from
//     there.
#include <string>
#include <vector>

#include "core/types.hpp"
#include "core/units.hpp"
#include "explicit/curve.hpp"
#include "explicit/rigid_motion.hpp"
#include "material/elastic.hpp"
#include "mesh/finger.hpp"
#include "mesh/mesh.hpp"

namespace fem::hand {

/// One finger: one column of Table 4-1 (SI units, angles in radians).
struct FingerRow {
    std::string name;          // "A".."E"
    double length = 0.0;       // [m]
    double root_height = 0.0;  // h_f [m]
    double initial_angle = 0.0;  // theta_f [rad]
    double drum_radius = 0.0;  // r_drum [m]
    double roll = 0.0;         // R_x [rad]
    double pitch = 0.0;        // R_z [rad]
    double alpha = 0.0;        // mass damping [1/s] (Table 3-3 by length)
};

/// Table 4-1 (the printed rounded radii 82.6/108 mm and height 19 mm are the inch values 3.25,
/// 4.25 and 0.75 in: THESIS_CH4_5.md Sec 10 item 9; the inch values are used).
std::vector<FingerRow> table_4_1();

/// One cylindrical level of the stepped drum.
struct DrumLevel {
    double y_bottom = 0.0, y_top = 0.0, radius = 0.0;  // [m]
};

/// The rigid drum: stepped cylinder about the y axis through `centre` (its bottom-face centre),
/// turning at angular speed omega(t) [rad/s] in the sense that carries the object-side fingers in
/// -x (about -y). A speed schedule with stops is Curve::steps (explicit/curve.hpp).
struct Drum {
    Vec3 centre = Vec3::Zero();
    std::vector<DrumLevel> levels;
    Curve omega = Curve::constant(0.0);
    /// Drum angle at t = 0 [rad] (in its sense of rotation): every finger starts this much further
    /// round (a run that starts part-way through a turn, e.g. just before contact).
    double initial_angle = 0.0;
    /// The drum's rigid motion (rotation about -y through the centre at omega).
    RigidMotion motion() const;
};

/// The stepped drum of Sec 4.2 (THESIS_CH4_5.md Sec 9 item 4, reconstructed): radius 4.25 in for
/// y 0..2 in (fingers C, D, E), 3.25 in for y 2..4 in (A, B), turning at `omega` (Table 4-3:
/// 2.0944 rad/s, 20 rpm).
Drum stepped_drum(double omega = 20.0 * units::rpm);

/// Hexahedral finger mesh layout: the mapped n x n cross-section of Table 3-2 Case A
/// (finger::mapped_cross_section) and ceil(L / layer_length) layers: 5 x 5 and 4 mm give the
/// thesis's 725 elements / 1080 nodes (4.5 in) and 500 / 756 (3 in) of Table 4-2.
struct FingerMesh {
    int section = 5;
    double layer_length = 4.0 * units::mm;
    double semi_major = 12.0 * units::mm;   // a (Table 3-1)
    double semi_minor = 8.45 * units::mm;   // b
};

struct HandSpec {
    Drum drum = stepped_drum();
    std::vector<FingerRow> fingers = table_4_1();
    FingerMesh mesh;
    ElasticMaterial rubber = finger::rubber();  // finger material (Tables 3-1, 4-2)
    double theta_sign = -1.0;        // phi(0) = theta_sign * theta_f (see the frame notes above)
    double roll_sign = 1.0;          // R_x applied as roll_sign * R_x (mirror case: -1)
};

/// Where a finger sits at t = 0: its root-face centre and the rotation taking the finger mesh's
/// own frame (major axis x, minor axis y, axis z from root z = 0 to tip) to global axes.
struct Placement {
    Vec3 root = Vec3::Zero();
    Mat3 rotation = Mat3::Identity();
    double angle = 0.0;              // phi(0) = drum initial angle + theta_sign theta_f [rad]
    Vec3 axis() const { return rotation.col(2); }  // root -> tip
};
Placement place_finger(const HandSpec& hand, const FingerRow& finger);

/// The fingers' meshes, placed, as parts "finger-<name>" with node sets "root-<name>" (root face),
/// "tip-<name>" (tip face) and "tip-centre-<name>" (one node). The drum is meshed apart
/// (drum_mesh): HandModel adds it as a rigid part.
Mesh hand_mesh(const HandSpec& hand);

/// The drum's cylindrical surfaces as Quad4 shells, `segments` around each level, numbered so that
/// their normals point away from the axis: a rigid part (ExplicitModel::add_rigid_part) whose
/// faces are a contact master (ContactSurface::rigid_part). Part "drum".
Mesh drum_mesh(const Drum& drum, int segments = 48);

/// Number of layers of a finger of length L: ceil(L / layer_length) (rounding guard 1e-9).
int finger_layers(const FingerMesh& m, double length);

/// Validates a hand (positive lengths, radii, levels, alpha >= 0, unique names): InputError naming
/// the finger and field.
void validate(const HandSpec& hand);

}  // namespace fem::hand
