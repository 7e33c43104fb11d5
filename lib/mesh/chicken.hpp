#pragma once
// The chicken of thesis Chapter 5: a parametric passive bird built with the Gmsh API (OpenCASCADE
// kernel) and meshed in 4- or 10-node tetrahedra, and the single-limb models of Table 5-2.
//
// What the thesis prints (Sec 5.2.1, Table 5-1; Sec 5.2.2, Table 5-3) and what is reconstructed here
// ([R], every number a field of `Chicken` so that a study can vary it):
//
// Frame ("bird frame", Table 5-1): origin at the geometric centre of the body ellipsoid, x along the
// body's long axis with the head toward -x, y up, z lateral; the legs lie in the planes z = +-40 mm
// and the symmetry plane is z = 0. The head toward -x follows from Fig 5-16 (the neck is under
// finger A at x ~ 8 mm while the leg sits between fingers D and E at x ~ 47-120 mm, i.e. the head is
// on the side the bird travels to); the frame's axes are those of the global model rotated by
// theta_b = 7.8 degrees about +z: rotating Table 5-1's J1 = (-24.72, -67.3) mm by +7.8 degrees gives
// (-15.4, -70.0) mm, and Table 5-6 puts the perch's top centre at (387 - 402, -39 - 32) = (-15, -71) mm
// from the centroid. `place()` applies that rotation and translation.
//
//  body   ellipsoid with semi-axes 97 (x), 57 (y), 66 (z) mm [T, Table 5-1; Yin and Lee 2002]; Table
//         5-3 gives 97 and 57 with width 130 (65 along z) for the shackle model.
//  head   [R] an ellipsoid of semi-axes 28 x 20 x 18 mm whose front end sits at the bird length L
//         from the tail end (x = 97 - L: L = 250 mm [T, Sec 5.2.1], 371.5 mm [T, Table 5-3]) and whose
//         centre lies on the x axis, so that theta_b (the angle of the line from the head to the body
//         centre, Sec 5.3) is the placement angle, 7.8 degrees initially [T, Table 5-6].
//  neck   [R] a cylinder of radius 14 mm along x from inside the body (x = -80 mm) to the head centre.
//  leg    the chain J1 (paw) - L1 - J2 - L2 - J3 - L3 - J4 (hip) of Table 5-1 [T: joint coordinates,
//         limb lengths and "thicknesses"; the segments J1J2, J2J3, J3J4 measure 75.4, 76.6 and 70.8 mm
//         against the printed L1..L3 = 75, 77, 71 mm, and point at 12.0, 147.7 and 33.2 degrees from
//         +x]. Each limb is a straight bar between its joints in the leg plane z = 40 mm:
//           - z-depth = the printed limb "thickness" (L1 20, L2 10 on its lower half (J2 side) and 20
//             on its upper half, L3 10) [R: "thickness" read as the dimension normal to the side
//             view, as in the joint column where the J4 bricks' third dimension is a thickness and J4
//             sits 5 mm nearer the symmetry plane than J1..J3; read as an in-plane width, L3 (10 x 10
//             x 71 mm) could not be stiffer than ~43 N/m, against Table 5-2's 465 N/m];
//           - in-plane width: not printed (Appendix F, the drawing, has no numbers in the text) and
//             calibrated to Table 5-2's stiffness, limb by limb (`limb_mesh`, study chicken_shackling).
//         Hinges J2, J3 [T: "circular hole radius = 5.7 / 10, thickness = 10"]: a round knuckle of
//         depth 10 mm around the joint with the printed hole bored through the joint; the knuckle's
//         rim is a ring ("neck") of `neck` = 3 mm around the hole [R: "thin neck", not dimensioned].
//         Hip J4 [T: "brick (l, h, t) (9.85, 7.52, 5.93); (13, 4.76, 5)"]: both bricks centred at J4
//         (J4's z = 35 mm is the inner face of the 10 mm deep L3), length along L3 for the first
//         and across it for the second [R], thickness along z: they bridge the clearance between
//         the leg and the body and are the leg's only connection to it ("The leg model is
//         connected with the ellipsoidal body at joint 4", Sec 5.2.1).
//  pocket [R] J3 and much of L2, L3 lie inside the body ellipsoid (J3 at (-15.7, -10.7, 40) mm is at
//         0.43 of the ellipsoid's "radius"), so the body is hollowed around the leg: a groove of
//         clearance `pocket_gap` around every limb and knuckle, open to the outside, leaves the leg
//         free to bend except at the hip.
//  shackle model (Table 5-3) [T: L1 75 / 30, L2 70 / 30, theta1 = 14, theta2 = 35 degrees, L3
//         omitted, chicken length 371.5, body 97 / 57 / width 130]: the chain J1 - L1 - J2 - L2 - J3
//         with L1 at theta1 from +x and the included angle theta2 at J2 (as Table 5-1's angles
//         relate to its coordinates: theta1 = 10 ~ 12.0, theta2 = 40 ~ 44); [R] J3 (the hip of this
//         model) placed at Table 5-1's J3, the J2 hinge and the hip bricks of Table 5-1.
//
// Meshes: the whole bird (`chicken_mesh`, full or half model) and each limb alone with its joint
// features (`limb_mesh`). Tetrahedra by Gmsh (Delaunay + optimiser), 10-node ones with mid-edge
// nodes on the true geometry. The bird's nodes are in reverse Cuthill-McKee order
// (mesh_tools.hpp: Gmsh's own order puts every mid-edge node after all corner nodes, which made the
// explicit gather / scatter of the tet10 bird cost more than its element kernel). Node sets of the bird:
//   "paw"          the paw end faces of the legs (J1, tied to the perch / gripper);
//   "symmetry"     the nodes on z = 0 (half model only);
//   "body_center"  one node at the body ellipsoid's centre (an embedded mesh point);
//   "head"         one node at the head centre (an embedded mesh point).
// SI units (metres) throughout.
#include <array>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "material/elastic.hpp"
#include "mesh/mesh.hpp"

namespace fem::chicken {

/// One limb: a straight bar from joint i to joint i+1 of the leg.
struct Limb {
    double width = 0.0;        // in-plane width (normal to the limb in the side view) [m]
    double depth_lower = 0.0;  // z-depth of the half toward joint i [m]
    double depth_upper = 0.0;  // z-depth of the half toward joint i+1 [m]
};

/// A compliant hinge at an inner joint: a knuckle of radius hole_radius + neck and z-depth `depth`
/// with a hole of hole_radius bored through the joint.
struct HoleHinge {
    double hole_radius = 0.0;
    double neck = 0.0;
    double depth = 0.0;
};

/// A brick of the hip (Table 5-1, J4): length along the last limb (`along_limb`) or across it.
struct HipBrick {
    double length = 0.0, height = 0.0, thickness = 0.0;
    bool along_limb = true;
};

/// The leg in the bird frame (one side, z > 0; the other is its mirror image).
struct Leg {
    std::vector<Vec3> joints;       // J1 (paw) .. Jn (hip); J1..J(n-1) share the leg plane's z
    std::vector<Limb> limbs;        // joints.size() - 1
    std::vector<HoleHinge> hinges;  // at joints 2 .. n-1: joints.size() - 2
    std::vector<HipBrick> hip;      // at the last joint, centred on it (its z)
    double pocket_gap = 0.0;        // clearance of the groove in the body around the leg [m]

    int limb_count() const { return static_cast<int>(limbs.size()); }
    double plane_z() const { return joints.front().z(); }
    /// Length of limb i (0-based): |J(i+1) - J(i)| in the side view.
    double limb_length(int i) const;
    /// Angle of limb i from +x in the side view, from joint i toward joint i+1 [rad].
    double limb_angle(int i) const;
};

struct Chicken {
    std::string name;
    double body_a = 0.0, body_b = 0.0, body_c = 0.0;  // semi-axes along x, y, z
    double length = 0.0;                              // tail end (x = body_a) to the front of the head
    double head_a = 0.0, head_b = 0.0, head_c = 0.0;  // head semi-axes
    double neck_radius = 0.0;
    double neck_root_x = 0.0;                         // where the neck cylinder starts, inside the body
    Leg leg;
    double mass = 0.0;                                // weight of the whole bird [kg] (Sec 5.4.2: 1.69 kg)

    /// The head centre in the bird frame: on the x axis, head_a behind the front end.
    Vec3 head_center() const { return Vec3(body_a - length + head_a, 0.0, 0.0); }
};

/// The bird of the body-grasping and leg-gripping model (Sec 5.2.1, Table 5-1: L = 250 mm). The limb
/// widths are the calibrated ones (calibrated_widths_table_5_1); pass others to explore.
Chicken table_5_1_chicken();
/// The in-plane limb widths of L1, L2, L3 calibrated to Table 5-2's stiffnesses by the study
/// chicken_shackling (the record of that calibration is in its README).
std::array<double, 3> calibrated_widths_table_5_1();
/// The bird of the shackle rotating/inverting model (Sec 5.2.2, Table 5-3: L = 371.5 mm, L1 75 / 30,
/// L2 70 / 30, theta1 14, theta2 35 degrees, L3 omitted). Its limb widths are Table 5-1's L1 and
/// L2 widths [R].
Chicken table_5_3_chicken();

/// Throws InputError naming the field when the geometry is not usable (non-positive sizes, a
/// hinge hole that leaves no neck, limbs or joints that do not match, a leg outside the half space).
void validate(const Chicken& c);

// --- meshes ---------------------------------------------------------------------------------------------

struct MeshOptions {
    double body_size = 12.0e-3;  // target tetrahedron size in the body, neck and head [m]
    double leg_size = 3.0e-3;    // target size in the leg and its groove (a box around each leg) [m]
    int order = 2;               // 1: tet4, 2: tet10
    bool half = true;            // half model (z >= 0, symmetry plane z = 0) or full model
    // tet10 only: mid-edge nodes on the true (curved) surfaces, or at the edges' midpoints. On the
    // full Table 5-3 bird at 20 / 5 mm, the curved placement inverts an element (det J ratio -2.2:
    // a small element on the knuckle's hole; Gmsh's high-order optimiser does not mend it), which the
    // explicit solver refuses: the shackle model takes straight-sided tet10.
    bool curved = true;
    std::string part = "chicken";
};

/// The bird's volume [m^3] (of the half model when `half`), from the OpenCASCADE geometry.
double volume(const Chicken& c, bool half);
/// Volume, centroid and inertia tensor about the centroid per unit density [m^5] of a solid, from
/// its OpenCASCADE geometry (OpenCASCADE integrates the B-spline surfaces numerically: ~1e-3
/// relative; the half model's volume is half the full one's to that accuracy).
struct MassProperties {
    double volume = 0.0;
    Vec3 centroid = Vec3::Zero();
    Mat3 inertia = Mat3::Zero();
};
MassProperties mass_properties(const Chicken& c, bool half);
/// The same for limb `limb` (1-based) of one leg as limb_mesh() models it.
MassProperties limb_mass_properties(const Chicken& c, int limb);
/// The density that gives the bird its mass: mass / full volume (the same for the half model).
double density_for_mass(const Chicken& c);
/// The same with the full volume already computed (mass_properties(c, false).volume): no second
/// OpenCASCADE integration.
double density_for_mass(const Chicken& c, double full_volume);
/// The bird's rubber (Sec 5.1 assumption 3: "similar to rubber"; Tables 5-2, 5-5, 5-7: E 6.1 MPa,
/// nu 0.49) with the given density.
ElasticMaterial material(double density);

/// Tetrahedral mesh of the bird with the node sets listed above.
Mesh chicken_mesh(const Chicken& c, const MeshOptions& options);

/// Rotates the bird frame by theta_b about +z (Table 5-6: 7.8 degrees) and moves its body centre to
/// `centroid` (the thesis's global frame, the symmetry plane at centroid.z()).
void place(Mesh& mesh, const Vec3& centroid, double theta_b);
/// theta_b of Sec 5.3: the angle from +x of the line from the head to the body centre, in the x-y
/// plane (positive: the head below the body centre, the bird pitched head-down).
double theta_b(const Vec3& head, const Vec3& body_center);

// --- Table 5-2: one limb alone --------------------------------------------------------------------------

/// The single-limb model of Table 5-2: limb `limb` (1-based) with its joint features (the hinge
/// knuckles at its ends), fixed at its upper joint J(i+1) (the end toward the hip) and loaded at
/// its lower joint J(i) [R: Fig 5-3 shows the set-up; the text says only "fixed at one end joint and
/// a known force is applied at the other end"]. A hinge joint is held or loaded through its hole
/// (a pin: the nodes of the hole's wall), a joint without hole through the limb's end face.
/// Node sets "fixed" and "loaded". Bird frame.
struct LimbMeshOptions {
    double size = 2.0e-3;  // target tetrahedron size [m]
    int order = 2;
    std::string part = "limb";
};
Mesh limb_mesh(const Chicken& c, int limb, const LimbMeshOptions& options);

}  // namespace fem::chicken
