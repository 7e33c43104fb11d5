#pragma once
// A hand scene of thesis Ch 4 as plain data, and the explicit model built from it: the hand (drum +
// Table 4-1 fingers, hand.hpp), deformable ellipsoidal objects (the football of Sec 4.2, the
// ellipsoid of Sec 4.4), rigid plates moving with a speed schedule (the conveyor pallet), contact
// pairs, gravity and the symmetry plane of the half model. Each field is one key of a future case
// file (issue 11 item 6); nothing of a particular study is hard-wired here.
//
//   hand::Scene s;                                   // hand = Table 4-1 on the stepped drum
//   s.objects.push_back({...football...});
//   s.plates.push_back({...pallet...});
//   s.contacts = {{"finger-A", "football", mu}, ..., {"football", "pallet", mu}};
//   hand::HandModel hm(s);                           // mesh + ExplicitModel + contact interfaces
//   ExplicitSolver solver(hm.model(), options);
//
// Part names: fingers "finger-<name>", objects and plates by their `part`, and "drum" for the drum
// surface. The drum and the plates are rigid parts of the explicit model (ExplicitModel::
// add_rigid_part) moved by their RigidMotion, contact masters through ContactSurface::rigid_part;
// the finger roots follow the drum's motion (ExplicitModel::prescribe_motion).
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "contact/contact.hpp"
#include "contact/rigid_wall.hpp"
#include "element/critical_time_step.hpp"
#include "explicit/offset_tie.hpp"
#include "explicit/solver.hpp"
#include "hand/hand.hpp"
#include "mesh/ellipsoid.hpp"

namespace fem::hand {

/// A deformable ellipsoid (hexahedral O-grid, mesh/ellipsoid.hpp), long axis along x.
struct EllipsoidObject {
    std::string part = "object";
    Vec3 semi_axes = Vec3::Zero();
    Vec3 centre = Vec3::Zero();
    EllipsoidGrid grid;
    bool half = true;            // keep only z <= centre.z (the half model of Sec 4.2; cut plane z = centre.z)
    ElasticMaterial material;    // density replaced when mass > 0
    double mass = 0.0;           // > 0: mass of the modelled part [kg], density = mass / mesh volume
    Vec3 initial_velocity = Vec3::Zero();
    double alpha = 0.0;          // mass damping [1/s] (thesis: objects undamped)
    /// Carried by the conveyor without slip (the "ideal grasping" of Sec 4.4): every node's velocity
    /// component along each non-zero axis of `carried_velocity` is prescribed as that component x
    /// carried_scale(t) (ExplicitModel::prescribe_velocity); the other components stay free. Zero:
    /// free (riding a pallet by contact, as the football).
    Vec3 carried_velocity = Vec3::Zero();
    Curve carried_scale;         // default: constant 1
};

/// A rigid flat plate translating along `direction` at speed(t) (the conveyor pallet; a schedule
/// with step changes is Curve::steps). Spanned by the full edge vectors u, v about `centre`
/// (mesh: parallelogram_quad4, a rigid part); contact pushes towards u x v.
struct Plate {
    std::string part = "plate";
    Vec3 centre = Vec3::Zero();
    Vec3 u = Vec3::UnitX(), v = -Vec3::UnitZ();
    int nu = 2, nv = 1;          // segments (Table 4-2's pallet: 2 shells)
    Vec3 direction = -Vec3::UnitX();
    Curve speed = Curve::constant(0.0);  // [m/s]
    /// Deepest penetration taken as contact [m]: the plate's thickness. A thin plate, as the thesis's
    /// shell pallet: 2 mm is ~15x the football's largest pallet penetration in a run (0.14 mm); a
    /// deeper limit (the first sessions' 30 mm) lets a node falling past the edge, within the edge
    /// tolerance and below the top, be shot up by the penalty spring (football_sweep README), unless
    /// the plate tracks the side nodes come from (below).
    double depth = 0.002;
    /// Capture only nodes that reach the plate from in front (contact::ContactOptions::
    /// track_approach_side): a node that enters the plate's outline from behind an edge (a leg
    /// crossing the plane of the shackle plate near its end) is left alone until it is in front
    /// again; a node that came from in front is held to `depth` (deeper it is let go, and taken
    /// again if it comes back within `depth`). Then `depth` can be the plate's thickness
    /// without nodes past the edge being shot up.
    bool track_approach_side = false;
    /// A motion other than one direction with a speed schedule (then `direction` and `speed` are
    /// not used): the perch of Ch 5 on the conveyor inclined, then declined
    /// (RigidMotion::piecewise_translation). A scene with one cannot be seen_from a later time.
    std::optional<RigidMotion> path;
    RigidMotion motion() const { return path ? *path : RigidMotion::translation(direction, speed); }
};

/// Nodes of a mesh object held to a plate by penalty ties (explicit/offset_tie.hpp: each node held
/// where the plate's motion carries its starting point) until `options.release_time`: the chicken's
/// paws (J1) tied to the perch until the shackling time (thesis Sec 5.3; THESIS_CH4_5.md
/// reconstruction 14). With an `options.engage_time` the ties act only from that time on, each node
/// held at the plate's point where the node is then: the shackle's gripper taking the paws.
struct PlateTie {
    std::string node_set;  // a node set of the object's mesh, as named in MeshObject::mesh
    std::string plate;     // the part name of a scene plate
    OffsetTieOptions options;  // frequency, damping, release and engage times
};

/// A deformable object given as a mesh in the scene's frame: every block of part `part` (tet4,
/// tet10 or hex8), e.g. the chicken of Ch 5 (mesh/chicken.hpp) placed on its perch. Its node sets
/// are renamed "<set>-<part>" in the model's mesh, as an ellipsoid object's. A half model names
/// the node set on its cut plane (`symmetry_set`): those nodes get u_z = 0, the faces on it are
/// left out of the contact surface, and the plane (z of those nodes, which must all lie on one
/// plane z = const) is the mirror plane of Scene::mirror_contact.
struct MeshObject {
    std::string part = "object";
    Mesh mesh;
    ElasticMaterial material;
    Vec3 initial_velocity = Vec3::Zero();
    double alpha = 0.0;          // mass damping [1/s]
    double hourglass_qm = 0.1;   // hexahedral objects: QM of the stiffness hourglass control (Hex8Options)
    BulkViscosity bulk{};        // Table 2-1's bulk viscosity (Hex8Options, TetGroupOptions); both 0: none
    std::string symmetry_set;    // empty: a whole object
    std::vector<PlateTie> ties;
};

/// Deepest penetration the mirror wall (Scene::mirror_contact) takes as contact [m]: two finger
/// elements (4 mm layers), far beyond any penetration a contact that holds allows.
inline constexpr double kMirrorDepth = 0.008;

/// A contact pair: the slave part's surface nodes against the master part's faces (two_way: and
/// back). A rigid master is a plate's part name or "drum". "fingers" stands for every finger of
/// the hand as one surface (one search and one stable-step bound; forces per finger follow from
/// the contact points' owning elements, HandModel::finger_of_block).
struct ContactPair {
    std::string slave, master;
    contact::FrictionLaw friction;
    bool two_way = true;         // deformable pairs only
    double penalty_scale = 0.1;  // LS-DYNA SLSFAC (contact/contact.hpp)
};

/// Frame of the fingers' mass damping. LS-DYNA's *DAMPING_PART_MASS damps absolute velocity, so
/// the drum's rigid rotation is damped too and the fingers trail (the thesis's "cannot spring back
/// when the drum rotates", Sec 3.5.2): `absolute`. `drum`: damping of the velocity relative to the
/// drum's rigid rotation (-alpha m (v - omega x r)), the co-rotating variant.
enum class DampingFrame { absolute, drum };

/// A rigid rotation of the whole hand (drum and fingers) on top of the drum's spin, about the axis
/// through `point` along `axis` at omega(t): the flip of Sec 4.4 (135 deg about the global z axis in
/// 0.5 s, Table 4-6). The hand's motion is compose(turn, drum spin) (explicit/rigid_motion.hpp).
/// omega zero (the default): no turn.
struct HandTurn {
    Vec3 point = Vec3::Zero();
    Vec3 axis = Vec3::UnitZ();
    Curve omega = Curve::constant(0.0);
};

struct Scene {
    HandSpec hand;
    HandTurn turn;
    std::vector<EllipsoidObject> objects;
    std::vector<MeshObject> meshes;
    std::vector<Plate> plates;
    std::vector<ContactPair> contacts;
    Vec3 gravity = Vec3::Zero();
    Curve gravity_curve;         // gravity x curve(t) (default: on from t = 0)
    /// Half objects get u_z = 0 on their cut plane (Table 4-3 "ellipsoid symmetric plane DOF UZ = 0"),
    /// and their cut faces are left out of the contact surface (the mirrored half is there, not a wall).
    bool symmetry = true;
    /// Half models: the fingers meet their mirror images (the other half's fingers) on the symmetry
    /// plane of the half objects. By symmetry a finger and its mirror image touch on that plane
    /// itself and do not slide against each other there, so a frictionless rigid wall at the plane
    /// models that contact exactly: HandModel adds a fixed planar rigid wall (contact/rigid_wall.hpp,
    /// LS-DYNA *RIGIDWALL_PLANAR) "fingers on mirror-plane" on the plane z = the half object's centre
    /// z, normal -z (towards the fingers' side), kMirrorDepth deep, holding every finger's surface
    /// nodes (HandModel::mirror_wall). A finger and the mirror image of another finger are not
    /// modelled (they would touch beside the plane). Needs a half object. The wall holds the fingers'
    /// free nodes; root nodes ride the drum's prescribed motion and are not stopped by it (test
    /// Hand.MirrorContactKeepsFingersOnTheirSideOfTheSymmetryPlane).
    bool mirror_contact = false;
    DampingFrame damping_frame = DampingFrame::absolute;
    /// true: the fingers start with the drum's rigid-rotation velocity (spinning, undeformed);
    /// false: at rest while their roots start turning (a jolt at t = 0).
    bool fingers_start_spinning = true;
    /// Drum surface segments around the circumference (rigid part and contact master "drum").
    int drum_segments = 48;
};

/// The scene seen from physical time t0 on (the model's t = 0 is then t0): what a run that skips
/// [0, t0) starts from, valid while nothing has touched before t0 (a study's judged run that starts
/// shortly before the first contact, football_sweep and ellipsoid_flip). The drum is turned by the
/// integral of its speed to t0 (the fingers undeformed, spinning with it), objects moved by their
/// initial velocity x t0 (mesh objects too: their nodes), plates by their motion to t0, and every
/// curve (drum speed, turn, plate speeds, carriage, gravity) shifted by t0 (Curve::shifted).
/// InputError when the hand's turn has turned before t0 or a carried object's carriage changed
/// before t0 (neither can be skipped), and for mesh objects tied to a plate or plates on a `path`
/// (not written yet: a tied object rides its plate, the chicken of Ch 5 on its perch).
Scene seen_from(Scene scene, double t0);

/// The built model. Owns the mesh's model; contact interfaces are reachable by pair name
/// "<slave> on <master>".
class HandModel {
public:
    explicit HandModel(const Scene& scene);
    ExplicitModel& model() { return *model_; }
    const Mesh& mesh() const { return model_->mesh(); }
    const Scene& scene() const { return scene_; }

    struct Pair {
        std::string name;
        const ContactPair* spec = nullptr;
        contact::ContactInterface* contact = nullptr;
    };
    const std::vector<Pair>& pairs() const { return pairs_; }
    contact::ContactInterface& contact(const std::string& name) const;
    /// The ties of mesh object `part` to plate `plate` (MeshObject::ties); InputError when none.
    const OffsetTie& tie(const std::string& part, const std::string& plate) const;
    /// The mirror wall (Scene::mirror_contact); null without one.
    const contact::PlanarWall* mirror_wall() const { return mirror_wall_; }
    /// Every contact of the model as (name, report): the pairs in scene order, then the mirror wall
    /// (a planar wall is a ForceProvider of its own, not a ContactInterface). What a study samples
    /// per cycle (impulse, contact time, penetration) in one loop.
    std::vector<std::pair<std::string, ContactReport>> contact_reports() const;

    /// Nodes of a part (every node of its elements, sorted).
    std::vector<int> part_nodes(const std::string& part) const;
    /// Mass of a part (density x mesh volume) [kg].
    double part_mass(const std::string& part) const;
    /// Mass-weighted centre of a part's nodes at positions x (lumped masses: element volume / 8).
    Vec3 centre_of_mass(const std::string& part, std::span<const Vec3> x) const;
    /// The finger ("A".."E") whose part owns mesh block b; empty when none.
    const std::string& finger_of_block(int block) const;
    /// The finger owning node n; empty when none.
    const std::string& finger_of_node(int node) const;
    /// Tip-centre node of finger `name`.
    int tip_node(const std::string& finger) const;
    /// Where a material point of the drum-fixed frame with reference position X is at time t (the
    /// drum's spin, and the hand's turn when the scene has one).
    Vec3 drum_position(const Vec3& X, double t) const { return drum_motion_.position(X, t); }
    const RigidMotion& drum_motion() const { return drum_motion_; }
    /// Current position of a plate's reference centre.
    Vec3 plate_centre(const std::string& part, double t) const;

private:
    Scene scene_;
    std::unique_ptr<ExplicitModel> model_;
    std::vector<Pair> pairs_;
    std::map<std::pair<std::string, std::string>, const OffsetTie*> ties_;
    const contact::PlanarWall* mirror_wall_ = nullptr;
    RigidMotion drum_motion_;
    std::map<std::string, std::vector<double>> lumped_;  // per part: lumped node mass (aligned with part_nodes)
    std::map<std::string, std::vector<int>> part_nodes_;
    std::map<std::string, double> part_mass_;
    std::vector<std::string> block_finger_, node_finger_;
};

}  // namespace fem::hand
